"""Where an element ends in the text as written: the outline's ranges cover whole elements
(a link from ``<link`` to ``</link>``), so breadcrumbs and "symbol at cursor" work inside."""

from __future__ import annotations

import bisect
import re

from lsprotocol import types as T

from urdflint.lsp import convert

TAG_RE = re.compile(
    r"<!--.*?-->|<!\[CDATA\[.*?\]\]>|<\?.*?\?>"
    r"|<(/?)[^\s>/!?]+(?:[^>\"']|\"[^\"]*\"|'[^']*')*?(/?)>",
    re.S,
)


class Text:
    """A file's lines joined once, with the offset where each line starts."""

    def __init__(self, lines: list[str]) -> None:
        self.lines = lines
        self.text = "\n".join(lines)
        self.starts = [0]
        for line in lines[:-1]:
            self.starts.append(self.starts[-1] + len(line) + 1)

    def end(self, row: int, column: int) -> T.Position | None:
        """Where the element whose start tag is at (``row``, ``column``: 0-based, code
        points) ends: after its end tag, or its ``/>`` (tags counted from there; comments,
        CDATA and processing instructions skipped). ``None`` when the text does not say
        (a half-typed file)."""
        if row >= len(self.lines):
            return None
        depth = 0
        for match in TAG_RE.finditer(self.text, self.starts[row] + column):
            closing, empty = match.group(1), match.group(2)
            if closing is None:
                continue  # a comment, CDATA or processing instruction
            depth += -1 if closing else (0 if empty else 1)
            if depth <= 0:
                end = match.end()
                line = bisect.bisect_right(self.starts, end) - 1
                return T.Position(line, convert.units(self.text[self.starts[line] : end]))
        return None


MACRO_RE = re.compile(
    r"""<xacro:macro\b(?:[^>"']|"[^"]*"|'[^']*')*?\bname\s*=\s*["']([^"']*)["']"""
)


def nested(source: Text, symbols: list[T.DocumentSymbol]) -> list[T.DocumentSymbol]:
    """``symbols`` (links and joints written in a xacro file) under the ``<xacro:macro>``
    that writes each, the macros as symbols of their own (a macro file's outline)."""
    groups: list[T.DocumentSymbol] = []
    for match in MACRO_RE.finditer(source.text):
        line = bisect.bisect_right(source.starts, match.start()) - 1
        column = match.start() - source.starts[line]
        end = source.end(line, column)
        if end is None:
            continue
        start = T.Position(line, convert.units(source.lines[line][:column]))
        head = T.Range(start, T.Position(line, convert.units(source.lines[line])))
        groups.append(
            T.DocumentSymbol(
                match.group(1), T.SymbolKind.Function, T.Range(start, end), head, "xacro:macro",
                children=[],
            )
        )  # fmt: skip
    top: list[T.DocumentSymbol] = []
    for symbol in symbols:
        at = _key(symbol.range.start)
        inside = [g for g in groups if _key(g.range.start) <= at <= _key(g.range.end)]
        if inside:  # the innermost macro that holds it
            inside[-1].children.append(symbol)  # type: ignore[union-attr]
        else:
            top.append(symbol)
    return sorted([*groups, *top], key=lambda s: _key(s.range.start))


def _key(position: T.Position) -> tuple[int, int]:
    return position.line, position.character
