"""Rule metadata and the ``@rule`` decorator.

A rule is a generator over one parsed :class:`~urdflint.document.Document` that
yields :class:`Hit` objects. The engine (``linter.py``) stamps each hit with the
path, line, element path, code, name and the configured severity.
"""

from __future__ import annotations

import importlib
import inspect
import re
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from urdflint.model.edits import Repair
from urdflint.model.effects import Effect, Effects
from urdflint.model.finding import Severity

if TYPE_CHECKING:
    from lxml import etree

CODE_RE = re.compile(r"^[A-Z][0-9]{3}$")
NAME_RE = re.compile(r"^[a-z][a-z0-9]*(-[a-z0-9]+)*$")
SECTIONS = ("## What it does", "## Why is this bad?", "## How to fix")

FAMILIES: dict[str, str] = {
    "X": "document",
    "S": "structure",
    "I": "inertial",
    "C": "collision, visual and geometry",
    "G": "Gazebo extensions",
    "J": "joints",
    "T": "transmissions",
    "R": "ros2_control",
    "M": "MoveIt (SRDF)",
    "N": "naming conventions (REP profiles)",
    "P": "physics (Pinocchio)",
    "D": "statics: gravity torques and stability (Pinocchio)",
    "E": "simulation engines (--confirm)",
    "U": "urdflint itself",
}


@dataclass(frozen=True, slots=True)
class Hit:
    """What a rule reports: an element and a one-sentence message.

    ``element`` is ``None`` for robot-level findings. ``severity`` lets a
    target-aware rule lower or raise its default for the selected targets; a
    severity set in the user's configuration always wins. ``line`` and
    ``column`` override the element's position (parse errors have no element).
    """

    element: etree._Element | None
    message: str
    fix: str | None = None
    severity: Severity | None = None
    line: int | None = None
    column: int | None = None
    path: str | None = None  # with ``line``: a position in another file (a xacro include)
    attribute: str | None = None  # the attribute at fault: the finding points at it
    variant: str = ""  # which of the rule's effect tables applies (e.g. "negative", "zero")
    engine: str | None = None  # E rules: the --confirm engine the hit is about
    effects: Mapping[str, Effect] | None = None  # target -> effect, when the rule works it out
    repair: Repair | None = None  # the automatic fix (urdflint fix)


Check = Callable[..., Iterator[Hit]]


@dataclass(frozen=True, slots=True)
class Rule:
    code: str
    name: str
    severity: Severity
    check: Check
    doc: str
    fix: str | None = None
    needs: tuple[str, ...] = ()
    options: Mapping[str, Any] = field(default_factory=dict)
    requires_robot: bool = True
    targets: frozenset[str] = frozenset()  # runs only for these targets (empty: always)
    effects: Effects = field(default_factory=dict)  # variant -> target -> effect
    by_target: bool = False  # severity: the worst effect on the selected targets
    fixable: str | None = None  # "safe" or "unsafe" when the rule proposes automatic fixes

    def effect_table(self) -> list[tuple[str, str, str, str]]:
        """``(variant, target, consequence, detail)`` rows for the rule's page."""
        return [
            (variant, target, effect.consequence.key, effect.detail)
            for variant, table in self.effects.items()
            for target, effect in table.items()
        ]

    @property
    def family(self) -> str:
        return self.code[0]

    @property
    def summary(self) -> str:
        return self.doc.strip().splitlines()[0].strip() if self.doc.strip() else self.name

    def section(self, heading: str) -> str:
        """The text under ``## heading`` in the rule's docstring ('' if absent)."""
        match = re.search(rf"^## {re.escape(heading)}\s*\n(.*?)(?=^## |\Z)", self.doc, re.S | re.M)
        return match.group(1).strip() if match else ""


RULES: dict[str, Rule] = {}


def rule(
    code: str,
    name: str,
    severity: Severity,
    *,
    fix: str | None = None,
    needs: tuple[str, ...] = (),
    options: Mapping[str, Any] | None = None,
    requires_robot: bool = True,
    targets: tuple[str, ...] = (),
    effects: Effects | None = None,
    by_target: bool = False,
    fixable: str | None = None,
) -> Callable[[Check], Check]:
    """Register a rule; the module docstring is its documentation page.

    ``fix`` is the default how-to-fix sentence for its findings; ``needs``
    names optional modules (``"pinocchio"``, ``"trimesh"``) the check imports
    lazily; ``options`` maps option names to defaults, and a rule with options
    is called as ``check(doc, opts)``; ``requires_robot=False`` lets the rule
    run on documents that are not a usable ``<robot>`` (the X001/X002 rules);
    ``targets`` limits a target rule to runs that select one of those targets.
    ``effects`` says what each target does with the defect (per variant, see
    :mod:`urdflint.model.effects`); with ``by_target`` the finding's severity is the worst
    effect's on the run's targets instead of ``severity``.
    """

    def register(fn: Check) -> Check:
        if not CODE_RE.fullmatch(code) or not NAME_RE.fullmatch(name):
            raise RuntimeError(f"malformed rule declaration: {code} {name}")
        if code in RULES or any(r.name == name for r in RULES.values()):
            raise RuntimeError(f"duplicate rule declaration: {code} {name}")
        module = inspect.getmodule(fn)
        doc = inspect.cleandoc(module.__doc__ or "") if module else ""
        RULES[code] = Rule(
            code,
            name,
            severity,
            fn,
            doc,
            fix,
            tuple(needs),
            dict(options or {}),
            requires_robot,
            frozenset(targets),
            dict(effects or {}),
            by_target,
            fixable,
        )
        return fn

    return register


def lookup(key: str) -> Rule | None:
    """Find a rule by code (``I005``) or name (``triangle-inequality``)."""
    key = key.strip()
    load_rules(families_of([key]))
    return _find(key)


def _find(key: str) -> Rule | None:
    """:func:`lookup` among the families already loaded."""
    if key.upper() in RULES:
        return RULES[key.upper()]
    for candidate in RULES.values():
        if candidate.name == key.lower():
            return candidate
    return None


SELECTOR_RE = re.compile(r"[A-Z]\d{0,3}")


def families_of(selectors: list[str] | tuple[str, ...]) -> set[str] | None:
    """The family letters ``selectors`` can match, or ``None`` when one of them is a rule
    name or ``ALL`` (then every family is needed to resolve it)."""
    letters: set[str] = set()
    for raw in selectors:
        key = raw.strip().upper()
        if not key:
            continue
        if not SELECTOR_RE.fullmatch(key):
            return None
        letters.add(key[0])
    return letters


def expand(selectors: list[str] | tuple[str, ...]) -> set[str]:
    """Turn codes, names and code prefixes (``I``, ``I00``) into a set of codes.

    Loads only the families the selectors name. Raises ``ValueError`` naming the first
    selector that matches no rule.
    """
    load_rules(families_of(selectors))
    codes: set[str] = set()
    for raw in selectors:
        key = raw.strip()
        if not key:
            continue
        if key.upper() == "ALL":
            codes.update(RULES)
            continue
        found = _find(key)  # its family is loaded above
        if found is not None:
            codes.add(found.code)
            continue
        upper = key.upper()
        prefix = [c for c in RULES if c.startswith(upper)] if SELECTOR_RE.fullmatch(upper) else []
        if not prefix:
            raise ValueError(f"unknown rule or rule family {raw!r}")
        codes.update(prefix)
    return codes


# The rule catalogue: a plug-in package whose ``PACKAGES`` maps family letters to
# sub-packages that register their rules when imported. Rules sit above the engine (they
# import the registry), so the engine loads them by name, not by an import statement.
RULE_PACKAGES: tuple[str, ...] = ("urdflint.rules",)
_loaded: set[str] = set()  # family letters imported so far
ALWAYS = frozenset("U")  # urdflint's own rules (internal error, suppressions): every run


def load_rules(families: set[str] | frozenset[str] | None = None) -> dict[str, Rule]:
    """Import the rule families (all, or only ``families`` and urdflint's own) once each,
    and return the registry."""
    for package in RULE_PACKAGES:
        catalogue = importlib.import_module(package)
        wanted = catalogue.PACKAGES if families is None else families | ALWAYS
        for letter in sorted(set(wanted) - _loaded):
            if letter in catalogue.PACKAGES:
                importlib.import_module(f"{package}.{catalogue.PACKAGES[letter]}")
                _loaded.add(letter)
    return RULES


def catalogue() -> list[dict[str, Any]]:
    """Every rule as ``urdflint rules --format json`` (and the MCP catalogue) lists it."""
    return [
        {
            "code": r.code,
            "name": r.name,
            "severity": str(r.severity),
            "family": FAMILIES[r.family],
            "summary": r.summary,
            "needs": list(r.needs),
            "options": dict(r.options),
        }
        for r in sorted(load_rules().values(), key=lambda r: r.code)
    ]
