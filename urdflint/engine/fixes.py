"""Turn a rule's :class:`~urdflint.model.edits.Repair` into text edits, and apply them.

An operation on an element becomes an edit at the element's exact span: in the URDF file
itself, or, for a document expanded from xacro, in the file and at the line where the
element is written (the xacro source map). A value that the xacro source computes (``${...}``,
``$(...)``) cannot be edited there: the fix is reported as unavailable, with the reason.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any

from lxml import etree

from urdflint.model import edits as E
from urdflint.model.document import Document
from urdflint.model.edits import Autofix, Edit, Repair
from urdflint.model.positions import Lines

EXPRESSION = ("${", "$(")
INDENT = "  "
MAX_ROUNDS = 4  # urdflint fix and POST /v1/fix
CHILD_RE = re.compile(rb"<[A-Za-z_]")  # the next element's start tag (not a comment or PI)
TRAILING = re.compile(rb"(?:[ \t]|<!--(?:(?!-->).)*-->)*", re.S)  # blanks and comments


class Unavailable(Exception):
    """Why an operation cannot become an edit."""


@dataclass(frozen=True)
class Place:
    """Where an element's start tag is written: the file, its bytes, the offset."""

    path: str
    data: bytes
    start: int


def resolve(doc: Document, repair: Repair) -> Autofix:
    """The repair as edits, or the reason it cannot be applied automatically."""
    if repair.unavailable:
        return Autofix(repair.applicability, repair.description, (), repair.unavailable)
    found: list[Edit] = []
    try:
        for operation in repair.operations:
            found.extend(_edits(doc, operation))
    except Unavailable as exc:
        return Autofix(repair.applicability, repair.description, (), str(exc))
    return Autofix(repair.applicability, repair.description, tuple(found))


def _edits(doc: Document, op: E.Operation) -> list[Edit]:
    if isinstance(op, E.SetAttribute):
        place = locate(doc, op.element)
        span = E.attribute_span(place.data, place.start, op.name)
        if span is None:  # not written yet: add it at the end of the start tag
            end = E.start_tag_end(place.data, place.start)
            end -= 2 if place.data[end - 2 : end] == b"/>" else 1
            return [edit(place, end, end, f' {op.name}="{_quoted(op.value)}"')]
        _literal(place.data[span[1] : span[2]])
        return [edit(place, span[1], span[2], _quoted(op.value))]
    if isinstance(op, E.RemoveAttribute):
        place = locate(doc, op.element)
        span = E.attribute_span(place.data, place.start, op.name)
        if span is None:
            return []
        begin = span[0]
        while begin > 0 and place.data[begin - 1 : begin].isspace():
            begin -= 1
        return [edit(place, begin, span[2] + 1, "")]
    if isinstance(op, E.RemoveElement):
        place = locate(doc, op.element)
        start, end = E.line_span(place.data, place.start, E.element_end(place.data, place.start))
        return [edit(place, start, end, "")]
    if isinstance(op, E.RenameElement):
        return _rename(locate(doc, op.element), op)
    if isinstance(op, E.CreateFile):
        return _create(op)
    return _insert(doc, op)


def _create(op: E.CreateFile) -> list[Edit]:
    """A new file's whole text; nothing when the file already holds that text."""
    try:
        present = Path(op.path).read_bytes()
    except FileNotFoundError:
        return [Edit(op.path, 0, 0, op.text, create=True)]
    except OSError as exc:
        raise Unavailable(f"{op.path} cannot be read ({exc.strerror})") from None
    if present != op.text.encode("utf-8"):
        raise Unavailable(f"{op.path} exists with other content; it is not overwritten")
    return []


def _rename(place: Place, op: E.RenameElement) -> list[Edit]:
    old = etree.QName(op.element).localname.encode()
    first = edit(place, place.start + 1, place.start + 1 + len(old), op.tag)
    end = E.element_end(place.data, place.start)
    closing = b"</" + old
    at = place.data.rfind(closing, place.start, end)
    if place.data[end - 2 : end] == b"/>" or at < 0:
        return [first]
    return [first, edit(place, at + 2, at + 2 + len(old), op.tag)]


def _insert(doc: Document, op: E.InsertChild) -> list[Edit]:
    parent = locate(doc, op.parent)
    data, nl = parent.data, E.newline(parent.data)
    unit = _unit(data, parent.start)
    op = E.InsertChild(op.parent, _reindent(op.xml, unit), op.after)
    if op.after is not None:
        after = locate(doc, op.after)  # the sibling's own file (xacro: maybe another one)
        at = _line_end(after.data, E.element_end(after.data, after.start))
        pad = E.indentation(after.data, after.start).decode()
        nl = E.newline(after.data)
        return [edit(after, at, at, nl + pad + op.xml.replace("\n", nl + pad))]
    pad = E.indentation(data, parent.start).decode() + unit
    body = op.xml.replace("\n", nl + pad)
    end = E.start_tag_end(data, parent.start)
    if data[end - 2 : end] == b"/>":  # <link name="x"/> -> <link name="x"> ... </link>
        tag = etree.QName(op.parent).localname
        outer = E.indentation(data, parent.start).decode()
        text = f">{nl}{pad}{body}{nl}{outer}</{tag}>"
        return [edit(parent, end - 2, end, text)]
    at = _line_end(data, end)
    return [edit(parent, at, at, nl + pad + body)]


@lru_cache(maxsize=16)  # one parent (often <robot>) takes many insertions
def _unit(data: bytes, start: int) -> str:
    """The file's indentation step: a child's indentation beyond its parent's (the element
    at ``start``, else the ``<robot>`` element), two spaces when unknown."""
    robot = re.search(rb"<robot[\s>]", data)
    for tag in (start, robot.start() if robot else -1):
        if tag < 0:
            continue
        outer = E.indentation(data, tag)
        child = CHILD_RE.search(data, E.start_tag_end(data, tag))
        inner = E.indentation(data, child.start()) if child else b""
        if len(inner) > len(outer) and inner.startswith(outer):
            return inner[len(outer) :].decode()
    return INDENT


def _reindent(xml: str, unit: str) -> str:
    """``xml`` written with two spaces per level, with ``unit`` per level instead."""
    if unit == INDENT:
        return xml
    return re.sub(r"(?m)^((?:  )+)", lambda m: unit * (len(m.group(1)) // 2), xml)


def _line_end(data: bytes, at: int) -> int:
    """The end of ``at``'s line when only blanks and comments follow ``at`` on it (a trailing
    ``<!-- ... -->`` stays beside the tag it follows); ``at`` otherwise."""
    stop = data.find(b"\n", at)
    stop = len(data) if stop < 0 else stop
    if data[stop - 1 : stop] == b"\r":
        stop -= 1
    return stop if TRAILING.fullmatch(data, at, stop) else at


def _quoted(value: str) -> str:
    return value.replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;")


def _literal(raw: bytes) -> None:
    text = raw.decode("utf-8", "replace")
    if any(marker in text for marker in EXPRESSION):
        raise Unavailable(f"the value is computed by xacro ({text.strip()}): edit it by hand")


@lru_cache(maxsize=16)
def _lines(data: bytes) -> Lines:
    """Line starts of a file, computed once per file content (bytes keep their hash)."""
    return Lines(data)


def edit(place: Place, start: int, end: int, text: str) -> Edit:
    lines = _lines(place.data)
    line, column = lines.position(start)
    end_line, end_column = lines.position(end)
    return Edit(place.path, start, end, text, line, column, end_line, end_column)


_FILES: dict[str, bytes] = {}


def locate(doc: Document, element: etree._Element) -> Place:
    """Where ``element`` is written (raises :class:`Unavailable`)."""
    if doc.origin is None:
        offset = doc._tag_offset(element)
        if offset is None or doc.path in ("-", "<stdin>") or doc.recovered:
            raise Unavailable("the element's position in the file is not known")
        return Place(doc.path, doc.source, offset)
    origin = doc.origin(element, None)
    if origin is None or not origin.exact:
        raise Unavailable("the element is generated by xacro, not written in a file")
    key = os.path.abspath(origin.path)  # the same file, whatever the current folder
    data = doc.context.overlay.get(key)  # an editor's unsaved buffer (urdflint lsp)
    data = data if data is not None else _FILES.get(key)
    if data is None:
        try:
            data = _FILES[key] = Path(origin.path).read_bytes()
        except OSError as exc:
            raise Unavailable(f"{origin.path} cannot be read ({exc.strerror})") from None
    lines = Lines(data)
    if origin.line > len(lines.starts):
        raise Unavailable("the element's position in its file is not known")
    line_start = lines.starts[origin.line - 1]
    text = data[line_start:].decode("utf-8", "replace")[: origin.column - 1]
    offset = line_start + len(text.encode("utf-8"))
    if not data.startswith(b"<", offset):
        raise Unavailable("the element's position in its file is not known")
    return Place(origin.path, data, offset)


def forget_files() -> None:
    """Drop the cached source files and their line indexes (between fix rounds: they
    changed; after the last one, so a long-running service keeps no file contents)."""
    _FILES.clear()
    _lines.cache_clear()
    _unit.cache_clear()
    E.newline.cache_clear()


def apply_all(
    fixes: Iterable[Autofix], unsafe: bool = False
) -> dict[str, tuple[bytes, bytes, int]]:
    """``{path: (old bytes, new bytes, fixes applied)}`` for the applicable fixes."""
    by_path: dict[str, list[Edit]] = {}
    counts: dict[str, int] = {}
    for fix in fixes:
        if fix.unavailable or not fix.edits or (fix.applicability == "unsafe" and not unsafe):
            continue
        for e in fix.edits:
            by_path.setdefault(e.path, []).append(e)
        first = fix.edits[0].path
        counts[first] = counts.get(first, 0) + 1
    changed: dict[str, tuple[bytes, bytes, int]] = {}
    for path, found in by_path.items():
        try:
            old = Path(path).read_bytes()
        except OSError:
            if not all(e.create for e in found) or os.path.lexists(path):
                continue
            old = b""  # a new file (a written collision mesh)
        else:
            if any(e.create for e in found):
                continue  # created meanwhile: never overwritten
        new, _ = E.apply(old, found)
        if new != old:
            changed[path] = (old, new, counts.get(path, 0))
    return changed


def rounds(
    lint: Callable[[], Any],
    unsafe: bool,
    write: Callable[[str, bytes], None],
    choose: Callable[[Autofix | None], Autofix | None] = lambda fix: fix,
) -> tuple[Any, dict[str, bytes], int]:
    """Lint, apply the fixes ``choose`` keeps, ``write`` the changed files, lint again, until
    nothing changes or :data:`MAX_ROUNDS` rounds have run (a fix that overlapped another, or
    only becomes possible after it, is applied in a later round). The last lint's result,
    each changed file's original bytes, and how many fixes were applied."""
    originals: dict[str, bytes] = {}
    applied = 0
    result = lint()
    for _ in range(MAX_ROUNDS):
        found = [fix for f in result.findings if (fix := choose(f.autofix)) is not None]
        changed = apply_all(found, unsafe=unsafe)
        if not changed:
            break
        for path, (old, new, count) in changed.items():
            originals.setdefault(path, old)
            applied += count
            write(path, new)
        forget_files()
        result = lint()
    forget_files()
    return result, originals, applied
