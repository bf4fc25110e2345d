"""Suppression comments written into one file's text, for ``check --add-noqa``.

A finding's comment goes on its own line right before the start tag of its element,
indented like it (the form of the language server's quick fix); an element that does not
start its line is moved to a line of its own first. A directive already right before the
element (alone on its line) gets the new codes added to its list instead of a second
comment. File-level codes (robot-level findings, and an SRDF's, which the URDF suppresses)
extend the file's first ``ignore-file`` directive, else go in a new one on the line after
the root element's start tag.

Only comments are written: every other byte stays as it was (encoding, line endings,
indentation), and the result must parse as XML like the original, else nothing changes.
"""

from __future__ import annotations

import re
from collections.abc import Collection, Mapping
from dataclasses import dataclass, field

from lxml import etree

from urdflint.engine import registry
from urdflint.engine.suppress import DIRECTIVE_RE
from urdflint.model.parsing import make_parser

Key = tuple[int, int] | None  # (line, column) of a finding, or None: the whole file
DECLARED_RE = re.compile(rb"^(?:\xef\xbb\xbf)?<\?xml[^>]*?encoding\s*=\s*[\"']([A-Za-z0-9._-]+)")
COMMENT_RE = re.compile(r"<!--(.*?)-->", re.S)
TAG_RE = re.compile(r"<[A-Za-z_:]")


@dataclass
class Edited:
    """A file's new bytes, and what went into them."""

    data: bytes
    added: int = 0  # new comments
    extended: int = 0  # directives that were there and got more codes
    present: set[Key] = field(default_factory=set)  # spots whose directive had every code
    refused: dict[Key, str] = field(default_factory=dict)  # spots that take no comment, why


@dataclass
class _Text:
    text: str
    newline: str
    edits: list[tuple[int, int, int, str]] = field(default_factory=list)  # start, end, seq, new

    def edit(self, start: int, end: int, new: str) -> None:
        self.edits.append((start, end, len(self.edits), new))

    def result(self) -> str:
        """The text with the edits (which never overlap; insertions at one offset keep the
        order they were made in)."""
        pieces, done = [], 0
        for start, end, _, new in sorted(self.edits):
            pieces += [self.text[done:start], new]
            done = max(done, end)
        return "".join([*pieces, self.text[done:]])


def write(data: bytes, wanted: Mapping[Key, Collection[str]]) -> Edited:
    """``data`` with a directive for the codes of each spot (see the module docstring)."""
    decoded = _decode(data)
    why = None if decoded is not None else "its encoding cannot be kept (not UTF-8 or declared)"
    if decoded is not None and not _parses(data):
        why = "the file is not well-formed XML"
    if decoded is None or why is not None:
        return Edited(data, refused=dict.fromkeys(wanted, why or ""))
    text, codec = decoded
    first = text.find("\n")
    newline = "\r\n" if first > 0 and text[first - 1] == "\r" else "\n"
    doc = _Text(text, newline)
    done = Edited(data)
    if None in wanted:
        _file_level(doc, sorted(set(wanted[None])), done)
    spots: dict[int, list[Key]] = {}
    starts = [0, *(m.end() for m in re.finditer("\n", text))]
    for key in wanted:
        if key is None:
            continue
        offset = _tag_offset(text, starts, *key)
        if offset is None:
            done.refused[key] = "no element starts where the finding is"
        else:
            spots.setdefault(offset, []).append(key)
    for offset, keys in spots.items():
        codes = sorted({code for key in keys for code in wanted[key]})
        if not _element(doc, offset, codes, done):
            done.present.update(keys)
    if not doc.edits:
        return done
    new = doc.result().encode(codec)
    if not _parses(new):  # never expected: a comment between tags keeps the XML well-formed
        reason = "a comment there would break the XML"
        return Edited(data, refused=dict.fromkeys(wanted, reason))
    done.data = new
    return done


def _decode(data: bytes) -> tuple[str, str] | None:
    """The text and its codec, when writing ASCII into it keeps every other byte."""
    declared = DECLARED_RE.match(data)
    for codec in ("utf-8", declared.group(1).decode("ascii") if declared else None):
        if codec is None:
            continue
        try:
            text = data.decode(codec)
            if text.encode(codec) != data or "<!-- -->\n".encode(codec) != b"<!-- -->\n":
                continue
        except (LookupError, UnicodeError):
            continue
        if "\r" in text and "\n" not in text:
            return None  # classic Mac line endings: lines are not counted as we count them
        return text, codec
    return None


def _parses(data: bytes) -> bool:
    try:
        etree.fromstring(data, make_parser())
    except (etree.XMLSyntaxError, ValueError):
        return False
    return True


def _tag_offset(text: str, starts: list[int], line: int, column: int) -> int | None:
    """The offset of the ``<`` of the start tag holding (line, column) (``starts``: where
    each line starts): the position itself when the finding is at the tag, else the last
    ``<`` before it (an attribute's finding; no ``<`` is written inside a start tag)."""
    if not 1 <= line <= len(starts):
        return None
    start = starts[line - 1]
    end = text.find("\n", start)
    offset = min(start + column - 1, len(text) if end < 0 else end)
    found = text.rfind("<", 0, offset + 1)
    if found < 0 or not TAG_RE.match(text, found):
        return None
    if text.rfind("<!--", 0, found) > text.rfind("-->", 0, found):
        return None  # inside a comment
    return found


def _line_start(text: str, offset: int) -> int:
    return text.rfind("\n", 0, offset) + 1


def _indent(text: str, offset: int) -> str:
    start = _line_start(text, offset)
    line = text[start:offset]
    return line[: len(line) - len(line.lstrip(" \t"))]


def comment(kind: str, codes: Collection[str]) -> str:
    """``<!-- urdflint: ignore[I001,J004] missing-inertial, ... -->``: codes, then names."""
    names = ", ".join(_name(code) for code in codes)
    return f"<!-- urdflint: {kind}[{','.join(codes)}] {names} -->"


def _name(code: str) -> str:
    found = registry.lookup(code)
    return found.name if found is not None else code


def _element(doc: _Text, offset: int, codes: list[str], done: Edited) -> bool:
    """The codes on the element whose tag starts at ``offset``; False when the directive
    right before it already names every one."""
    text = doc.text
    before = _directive_before(text, offset)
    changed = _extend(doc, *before, codes) if before is not None else None
    if changed is not None:
        done.extended += changed
        return changed
    line = _line_start(text, offset)
    new = comment("ignore", codes)
    if not text[line:offset].strip():
        doc.edit(line, line, text[line:offset] + new + doc.newline)
    else:  # something precedes the element on its line
        inner = _indent(text, offset) + "  "
        doc.edit(offset, offset, f"{doc.newline}{inner}{new}{doc.newline}{inner}")
    done.added += 1
    return True


def _directive(text: str, start: int, end: int) -> re.Match[str] | None:
    """The directive in the comment ``text[start:end]`` (``<!--`` to ``-->``), matched on
    the comment's body (offsets from ``start + 4``)."""
    return DIRECTIVE_RE.match(text[start + 4 : end - 3])


def _directive_before(text: str, offset: int) -> tuple[int, re.Match[str]] | None:
    """The ``ignore`` directive right before the tag at ``offset`` (only blanks between),
    when nothing but blanks precedes it on its line: its comment's start and its match."""
    end = offset
    while end > 0 and text[end - 1] in " \t\r\n":
        end -= 1
    if not text.endswith("-->", 0, end):
        return None
    start = text.rfind("<!--", 0, end)
    if start < 0 or text[_line_start(text, start) : start].strip():
        return None
    match = _directive(text, start, end)
    if match is None or match["kind"] != "ignore" or match["codes"] is None:
        return None
    return start, match


def _extend(doc: _Text, start: int, match: re.Match[str], codes: list[str]) -> bool | None:
    """Add the missing ``codes`` to the directive ``match`` of the comment at ``start``;
    False when none is missing, None when it names an unknown code (U003 reports it; it
    is left alone and a new directive is written)."""
    raw = [c.strip() for c in match["codes"].split(",") if c.strip()]
    try:
        covered = registry.expand(raw)
    except ValueError:
        return None
    new = [code for code in codes if code not in covered]
    if not new:
        return False
    inner = match["codes"]
    sep = ", " if ", " in inner else ","
    listed = inner.rstrip() + (sep if raw else "") + sep.join(new) + inner[len(inner.rstrip()) :]
    reason = match["reason"]
    names = [part.strip() for part in reason.split(",")]
    if raw and all(_is_name(n) for n in names):  # a list of rule names: ours, kept complete
        kept = reason.rstrip()
        reason = kept + ", " + ", ".join(_name(c) for c in new) + reason[len(kept) :]
    base = start + 4
    doc.edit(base + match.start("codes"), base + match.end("reason"), listed + "]" + reason)
    return True


def _is_name(text: str) -> bool:
    found = registry.lookup(text) if text else None
    return found is not None and found.name == text


def _file_level(doc: _Text, codes: list[str], done: Edited) -> None:
    """The file's first ``ignore-file`` directive, extended, or a new one inside the root."""
    text = doc.text
    for found in COMMENT_RE.finditer(text):
        match = _directive(text, found.start(), found.end())
        if match is None or match["kind"] != "ignore-file" or match["codes"] is None:
            continue
        changed = _extend(doc, found.start(), match, codes)
        if changed is None:
            continue
        if changed:
            done.extended += 1
        else:
            done.present.add(None)
        return
    root = _root(text)
    if root is None:
        done.refused[None] = "the file has no root element"
        return
    tag, end = root
    new = comment("ignore-file", codes)
    if text[end - 1] == "/":  # <robot/>: no inside, so the line before it
        line = _line_start(text, tag)
        doc.edit(line, line, _indent(text, tag) + new + doc.newline)
    else:
        doc.edit(end + 1, end + 1, doc.newline + _child_indent(text, tag, end) + new)
    done.added += 1


def _root(text: str) -> tuple[int, int] | None:
    """The offsets of the root element's ``<`` and of the ``>`` that ends its start tag."""
    at = text.find("<")
    while at >= 0:
        if text.startswith("<?", at):
            at = text.find("?>", at)
        elif text.startswith("<!--", at):
            at = text.find("-->", at)
        elif text.startswith("<!", at):  # a DOCTYPE, maybe with an internal subset
            close = text.find(">", at)
            bracket = text.find("[", at, close)
            at = text.find(">", text.find("]", bracket)) if bracket >= 0 else close
        elif TAG_RE.match(text, at):
            end = _tag_end(text, at)
            return (at, end) if end is not None else None
        else:
            return None
        at = text.find("<", at) if at >= 0 else -1
    return None


def _tag_end(text: str, at: int) -> int | None:
    quote = ""
    for index in range(at, len(text)):
        char = text[index]
        if quote:
            quote = "" if char == quote else quote
        elif char in "\"'":
            quote = char
        elif char == ">":
            return index
    return None


def _child_indent(text: str, tag: int, end: int) -> str:
    """The indentation of the root's first child line (two blanks more than the root's)."""
    for line in text[end + 1 : end + 2000].splitlines()[1:]:
        if line.strip():
            blanks = line[: len(line) - len(line.lstrip(" \t"))]
            return blanks if not line.lstrip().startswith("</") else _indent(text, tag) + "  "
    return _indent(text, tag) + "  "
