"""The examples on a rule's page (``urdflint explain``): the rule's test fixtures
(``fixtures/rules/<CODE>/``), failing ones first, without the comments only the tests read.
"""

from __future__ import annotations

import json
import re
import tomllib
from dataclasses import dataclass
from importlib import resources
from importlib.resources.abc import Traversable
from typing import Any

SUFFIXES = (".urdf", ".xacro", ".srdf")
EXPECT_RE = re.compile(r"\s*<!--\s*expect:.*?-->")  # the fixture runner's expectations
COMMENT_RE = re.compile(r"<!--(.*?)-->", re.S)
SETTINGS_NOTE_RE = re.compile(r" *\([^()\n]*\.toml[^()\n]*\)")  # "(bad_mujoco.toml selects it)"


@dataclass(frozen=True, slots=True)
class Example:
    """One fixture as a page shows it."""

    name: str  # bad*.urdf, good*.xacro, ...
    lines: tuple[str, ...]  # its text without test-only comments
    flagged: tuple[int, ...]  # indexes in ``lines`` of the lines the rule must flag
    settings: str  # the settings the tests lint it with, on one line ('' for the defaults)

    @property
    def bad(self) -> bool:
        return self.name.startswith("bad")


def load(code: str) -> list[Example]:
    """The rule's fixtures, failing ones first (none for a rule without fixtures)."""
    try:
        folder = resources.files("urdflint.fixtures") / "rules" / code
        names = sorted(p.name for p in folder.iterdir() if p.name.endswith(SUFFIXES))
    except (FileNotFoundError, ModuleNotFoundError, NotADirectoryError):
        return []
    ordered = [n for n in names if n.startswith("bad")] + [n for n in names if n.startswith("good")]
    return [_example(folder, name) for name in ordered]


def _example(folder: Traversable, name: str) -> Example:
    lines, flagged = clean((folder / name).read_text(encoding="utf-8"))
    return Example(name, tuple(lines), tuple(flagged), _settings(folder, name))


def clean(text: str) -> tuple[list[str], list[int]]:
    """The lines of a fixture without its test-only comments (the ``<!-- expect: ... -->``
    of the fixture runner, notes on the fixture's settings file), and the indexes of the
    lines that carried an expectation. A line that held nothing else is left out."""
    raws = text.splitlines()
    unexpected = [EXPECT_RE.sub("", raw) for raw in raws]
    shown = COMMENT_RE.sub(_shown_comment, "\n".join(unexpected)).split("\n")
    lines: list[str] = []
    flagged: list[int] = []
    pending = False  # an expectation on a line that is left out: it flags the next one
    for raw, bare, line in zip(raws, unexpected, shown, strict=True):
        pending = pending or bare != raw
        if line != raw:
            line = line.rstrip()
            if not line.strip():
                continue
        if pending:
            flagged.append(len(lines))
            pending = False
        lines.append(line)
    return lines, flagged


def _shown_comment(match: re.Match[str]) -> str:
    """A comment as the page shows it: without its notes on the test set-up, or not at all
    when it is only about the test (its line breaks are kept, then the empty lines left
    out)."""
    body = SETTINGS_NOTE_RE.sub("", match.group(1)).replace("this fixture's ", "the ")
    return "\n" * body.count("\n") if ".toml" in body else f"<!--{body}-->"


def _settings(folder: Traversable, name: str) -> str:
    """The settings the fixture runner lints ``name`` with (``<stem>.toml`` beside it, else
    the folder's ``config.toml``), as ``key = value`` pairs on one line."""
    stem = name.rsplit(".", 1)[0]
    for candidate in (f"{stem}.toml", "config.toml"):
        path = folder / candidate
        if path.is_file():
            data = tomllib.loads(path.read_text(encoding="utf-8"))
            return ", ".join(f"{key} = {value}" for key, value in _flat(data))
    return ""


def _flat(data: dict[str, Any], prefix: str = "") -> list[tuple[str, str]]:
    pairs: list[tuple[str, str]] = []
    for key, value in data.items():
        if isinstance(value, dict):
            pairs += _flat(value, f"{prefix}{key}.")
        else:
            pairs.append((f"{prefix}{key}", json.dumps(value, ensure_ascii=False)))
    return pairs
