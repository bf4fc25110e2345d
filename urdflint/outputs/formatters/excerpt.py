"""The source line a finding points to, with a caret under its column
(``--output-format full``)::

       |
    61 |     <limit lower="1.2" upper="-1.2" effort="10" velocity="1"/>
       |     ^

Lines are numbered as libxml2 counts them (split on ``\\n`` only) and columns are code
points. A file that cannot be read (standard input, the HTTP API's upload, a path that has
gone) gets no excerpt.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

MAX_WIDTH = 100  # characters of a long line shown, around the column
LEAD = 40  # characters shown before the column when a long line is cut


class Sources:
    """The text of the files the findings point to, each read once."""

    def __init__(self, unread: Iterable[str] = ()) -> None:
        self.lines: dict[str, list[str] | None] = dict.fromkeys(unread)

    def line(self, path: str, number: int) -> str | None:
        if path not in self.lines:
            self.lines[path] = _read(path)
        found = self.lines[path]
        if found is None or not 1 <= number <= len(found):
            return None
        return found[number - 1].rstrip("\r")

    def excerpt(self, path: str, number: int, column: int) -> list[str]:
        """The gutter, the source line and the caret; nothing when the line is unknown."""
        text = self.line(path, number)
        if text is None:
            return []
        text, at = _window(text, column - 1)
        pad = "".join("\t" if c == "\t" else " " for c in text[:at])  # the caret under tabs
        gutter = " " * len(str(number))
        return [f"{gutter} |", f"{number} | {text}".rstrip(), f"{gutter} | {pad}^"]


def _window(text: str, at: int) -> tuple[str, int]:
    """A long line cut around offset ``at`` (with ``…`` where cut), and the new offset."""
    at = max(0, min(at, len(text)))
    if len(text) <= MAX_WIDTH:
        return text, at
    start = max(0, min(at - LEAD, len(text) - MAX_WIDTH))
    end = start + MAX_WIDTH
    head = "…" if start else ""
    return head + text[start:end] + ("…" if end < len(text) else ""), at - start + len(head)


def _read(path: str) -> list[str] | None:
    try:
        data = Path(path).read_bytes()
    except (OSError, ValueError):  # not a file (<stdin>, an upload), unreadable, NUL in name
        return None
    return data.decode("utf-8", "replace").split("\n")
