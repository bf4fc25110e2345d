"""Positions in source bytes: where a start tag begins and where one of its attributes is.

libxml2 (lxml's ``sourceline``) gives the line on which a start tag *ends*; a tag written over
several lines (``<inertia ixx=...`` then ``iyy=...`` below) would be reported on its last
line. These helpers find the ``<tag`` itself and the ``name=`` of an attribute inside it, so
findings point where the user wrote the thing.
"""

from __future__ import annotations

import bisect
import re

ATTR_RE = re.compile(rb"""\s([^\s=/>]+)\s*=\s*(?:"[^"]*"|'[^']*')""")
TAG_END_RE = re.compile(rb"""(?:"[^"]*"|'[^']*'|[^'">])*>""")


NEWLINE_RE = re.compile(rb"\n")
_LAST: list[tuple[bytes, list[int]]] = []  # the last text indexed: a document and its fixes


class Lines:
    """Line starts of a byte string: offsets to 1-based (line, character column)."""

    def __init__(self, data: bytes) -> None:
        self.data = data
        last = _LAST[0] if _LAST else None  # one read: the LSP indexes on two threads
        if last is not None and last[0] is data:
            self.starts = last[1]
            return
        self.starts = [0] + [m.end() for m in NEWLINE_RE.finditer(data)]
        _LAST[:] = [(data, self.starts)]

    def position(self, offset: int) -> tuple[int, int]:
        line = bisect.bisect_right(self.starts, offset)
        start = self.starts[line - 1]
        return line, len(self.data[start:offset].decode("utf-8", "replace")) + 1

    def end_of_line(self, line: int) -> int:
        return self.starts[line] if line < len(self.starts) else len(self.data)


def tag_start(lines: Lines, qname: str, end_line: int) -> int | None:
    """Offset of the last ``<qname`` that begins at or before the end of ``end_line``."""
    if not 1 <= end_line <= len(lines.starts):
        return None
    needle = b"<" + qname.encode()
    end = lines.end_of_line(end_line)
    index = lines.data.rfind(needle, 0, end)
    while index >= 0:
        after = lines.data[index + len(needle) : index + len(needle) + 1]
        if after in (b"", b" ", b"\t", b"\n", b"\r", b"/", b">"):
            return index
        index = lines.data.rfind(needle, 0, index)
    return None


def attribute_offset(data: bytes, start: int, name: str) -> int | None:
    """Offset of ``name=`` inside the start tag that begins at ``start`` (``None`` if absent)."""
    match = TAG_END_RE.match(data, start + 1)
    end = match.end() if match else len(data)
    wanted = name.encode()
    for attr in ATTR_RE.finditer(data, start + 1, end):
        if attr.group(1) == wanted:
            return attr.start(1)
    return None
