"""The one public result type: a :class:`Finding`, and its :class:`Severity`."""

from __future__ import annotations

import enum
import hashlib
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from urdflint.model.edits import Autofix
    from urdflint.model.effects import Effect


class Severity(enum.IntEnum):
    """How serious a finding is; ordered so that ``ERROR > WARNING > INFO``."""

    INFO = 1
    WARNING = 2
    ERROR = 3

    def __str__(self) -> str:
        return self.name.lower()

    @classmethod
    def parse(cls, text: str) -> Severity:
        """``"error"`` -> ``Severity.ERROR``; raises ``ValueError`` on anything else."""
        try:
            return cls[text.strip().upper()]
        except KeyError:
            raise ValueError(f"unknown severity {text!r} (use error, warning or info)") from None


@dataclass(frozen=True, slots=True)
class Call:
    """One macro call on the way from a xacro entry file to a finding's element: the macro
    ``macro`` was called at ``path:line:column``."""

    macro: str
    path: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"in macro `{self.macro}`, called from {self.path}:{self.line}:{self.column}"

    def __reduce__(self) -> tuple[type, tuple[str, str, int, int]]:
        return (Call, (self.macro, self.path, self.line, self.column))  # pickled fast


@dataclass(frozen=True, slots=True)
class Finding:
    """One problem in one file, stamped by the engine (never built by a rule)."""

    path: str
    line: int
    column: int
    code: str
    name: str
    severity: Severity
    message: str
    element: str
    fix: str | None = None
    trace: tuple[Call, ...] = ()  # xacro: the macro calls behind the element, innermost first
    effects: tuple[tuple[str, Effect], ...] = ()  # what each selected target does with it
    engine: str | None = None  # E rules: the --confirm engine that did it
    autofix: Autofix | None = None  # the automatic fix (urdflint fix), if the rule has one

    def __reduce__(self) -> tuple[type, tuple[object, ...]]:
        """Pickled as a constructor call (the analysis cache and ``--jobs`` send thousands;
        the dataclass default for frozen slots is four times slower)."""
        return (Finding, (
            self.path, self.line, self.column, self.code, self.name, self.severity,
            self.message, self.element, self.fix, self.trace, self.effects, self.engine,
            self.autofix,
        ))  # fmt: skip

    def __post_init__(self) -> None:
        if self.line < 1 or self.column < 1:
            raise ValueError(f"lines and columns are 1-based: {self.line}:{self.column}")

    def sort_key(self) -> tuple[str, int, int, str, str]:
        return (self.path, self.line, self.column, self.code, self.message)

    def fingerprint(self) -> str:
        """A line-independent identity: path, code and element path (not the line or message),
        so a finding keeps it when lines above it move or the message wording changes."""
        key = "\0".join((self.path.replace("\\", "/"), self.code, self.element))
        return hashlib.sha256(key.encode("utf-8")).hexdigest()[:32]

    def to_dict(self) -> dict[str, object]:
        """The JSON form (field order as declared; written out: ``asdict`` is slow)."""
        return {
            "path": self.path,
            "line": self.line,
            "column": self.column,
            "code": self.code,
            "name": self.name,
            "severity": str(self.severity),
            "message": self.message,
            "element": self.element,
            "fix": self.fix,
            "trace": tuple(
                {"macro": c.macro, "path": c.path, "line": c.line, "column": c.column}
                for c in self.trace
            ),
            "effects": {target: _effect(e) for target, e in self.effects},
            "engine": self.engine,
            "autofix": self.autofix.to_dict() if self.autofix is not None else None,
        }


def _effect(effect: Effect) -> dict[str, object]:
    """An effect's JSON: its consequence and detail, and its severity when the rule set one
    other than the consequence's own."""
    data: dict[str, object] = {"consequence": effect.consequence.key, "detail": effect.detail}
    if effect.severity is not None:
        data["severity"] = str(effect.severity)
    return data
