"""Automatic repairs: what a rule proposes (:class:`Repair`, operations on elements) and what
it becomes in a file (:class:`Edit`, bytes replaced at an exact span).

A rule describes a repair on the document's elements; the engine turns each operation into
a text edit at its exact source span (for xacro, in the file where the value is written),
so everything else in the file, comments, indentation, attribute order and line endings,
stays byte for byte.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING, Literal

if TYPE_CHECKING:
    from lxml import etree

Applicability = Literal["safe", "unsafe"]


# -- what a rule proposes ------------------------------------------------------------------


@dataclass(frozen=True)
class SetAttribute:
    element: etree._Element
    name: str
    value: str


@dataclass(frozen=True)
class RemoveElement:
    element: etree._Element


@dataclass(frozen=True)
class InsertChild:
    """``xml`` (one element, written without indentation) as the first child of ``parent``,
    or after ``after`` when given."""

    parent: etree._Element
    xml: str
    after: etree._Element | None = None


@dataclass(frozen=True)
class RenameElement:
    element: etree._Element
    tag: str


@dataclass(frozen=True)
class RemoveAttribute:
    element: etree._Element
    name: str


@dataclass(frozen=True)
class CreateFile:
    """A new file with ``text`` (a collision mesh beside its visual one): created only where
    no file is, or where the same text already is."""

    path: str
    text: str


Operation = (
    SetAttribute | RemoveElement | InsertChild | RenameElement | RemoveAttribute | CreateFile
)


@dataclass(frozen=True)
class Repair:
    """A rule's proposed fix: ``safe`` ones keep the model's meaning, ``unsafe`` ones change
    its physics (applied only with ``--unsafe-fixes``)."""

    applicability: Applicability
    description: str
    operations: tuple[Operation, ...]
    unavailable: str | None = None  # why the fix is not offered here (e.g. needs an option)


# -- what it becomes -------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Edit:
    """Replace ``data[start:end]`` of file ``path`` by ``text``; also 1-based positions
    for people and editors."""

    path: str
    start: int
    end: int
    text: str
    line: int = 1
    column: int = 1
    end_line: int = 1
    end_column: int = 1
    create: bool = False  # a new file whose whole text is ``text``

    def to_dict(self) -> dict[str, object]:
        data: dict[str, object] = {
            "path": self.path,
            "start": {"line": self.line, "column": self.column},
            "end": {"line": self.end_line, "column": self.end_column},
            "content": self.text,
            "offsets": [self.start, self.end],  # bytes of the file that ``content`` replaces
        }
        if self.create:
            data["create"] = True
        return data


@dataclass(frozen=True, slots=True)
class Autofix:
    """A finding's fix as text edits, or why it cannot be applied automatically."""

    applicability: Applicability
    description: str
    edits: tuple[Edit, ...] = ()
    unavailable: str | None = None  # e.g. the value comes from a xacro expression

    def to_dict(self) -> dict[str, object]:
        data: dict[str, object] = {
            "applicability": self.applicability,
            "description": self.description,
            "edits": [e.to_dict() for e in self.edits],
        }
        if self.unavailable:
            data["unavailable"] = self.unavailable
        return data


def apply(data: bytes, edits: Iterable[Edit]) -> tuple[bytes, list[Edit]]:
    """``data`` with the edits applied (byte offsets into ``data``); an edit that overlaps
    one applied before it is left out (and returned: the next round may apply it)."""
    chosen: list[Edit] = []
    left: list[Edit] = []
    for edit in sorted(set(edits), key=lambda e: (e.start, e.end)):
        if chosen and edit.start < chosen[-1].end:
            left.append(edit)
            continue
        chosen.append(edit)
    out = bytearray(data)
    for edit in reversed(chosen):
        out[edit.start : edit.end] = edit.text.encode("utf-8")
    return bytes(out), left


# -- spans in source bytes -------------------------------------------------------------------

TAG_RE = re.compile(rb"<(/?)([A-Za-z_][\w.:-]*)(?:\"[^\"]*\"|'[^']*'|[^'\">])*?(/?)>")
SKIP_RE = re.compile(rb"<!--.*?-->|<!\[CDATA\[.*?\]\]>|<\?.*?\?>", re.S)
ATTR_VALUE_RE = re.compile(rb"""\s([^\s=/>]+)(\s*=\s*)("[^"]*"|'[^']*')""")


def start_tag_end(data: bytes, start: int) -> int:
    """Offset just after the ``>`` of the start tag beginning at ``start``."""
    match = TAG_RE.match(data, start)
    return match.end() if match else len(data)


def element_end(data: bytes, start: int) -> int:
    """Offset just after the element whose start tag begins at ``start`` (its end tag, or its
    start tag when self-closing); comments, CDATA and processing instructions are skipped."""
    first = TAG_RE.match(data, start)
    if first is None:
        return len(data)
    if first.group(3):
        return first.end()
    depth, pos = 1, first.end()
    while depth:
        lt = data.find(b"<", pos)
        if lt < 0:
            return len(data)
        skipped = SKIP_RE.match(data, lt)
        if skipped:
            pos = skipped.end()
            continue
        tag = TAG_RE.match(data, lt)
        if tag is None:
            pos = lt + 1
            continue
        if tag.group(1):
            depth -= 1
        elif not tag.group(3):
            depth += 1
        pos = tag.end()
    return pos


def attribute_span(data: bytes, start: int, name: str) -> tuple[int, int, int] | None:
    """``(attribute start, value start, value end)`` of ``name`` in the start tag at
    ``start``; the value span excludes the quotes."""
    end = start_tag_end(data, start)
    for match in ATTR_VALUE_RE.finditer(data, start + 1, end):
        if match.group(1) == name.encode():
            return match.start(1), match.start(3) + 1, match.end(3) - 1
    return None


def line_span(data: bytes, start: int, end: int) -> tuple[int, int]:
    """Widen ``[start, end)`` to whole lines when nothing else is on them (so removing an
    element leaves no blank line), else keep it."""
    line_start = data.rfind(b"\n", 0, start) + 1
    line_end = data.find(b"\n", end)
    line_end = len(data) if line_end < 0 else line_end + 1
    before, after = data[line_start:start], data[end:line_end]
    if before.strip() == b"" and after.strip() == b"":
        return line_start, line_end
    return start, end


def indentation(data: bytes, start: int) -> bytes:
    """The whitespace before the tag at ``start`` on its line."""
    line_start = data.rfind(b"\n", 0, start) + 1
    prefix = data[line_start:start]
    return prefix if prefix.strip() == b"" else b""


@lru_cache(maxsize=16)
def newline(data: bytes) -> str:
    """The file's line ending (one scan per file: bytes keep their hash)."""
    return "\r\n" if b"\r\n" in data else "\n"
