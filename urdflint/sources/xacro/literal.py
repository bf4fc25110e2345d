"""The literal text of the files xacro read: start tags by line and column, for locating
expansion errors (a missing include, an undefined property) where they are written."""

from __future__ import annotations

import bisect
import html
import re
from collections.abc import Iterator
from dataclasses import dataclass, field
from functools import cached_property

BLANK_RE = re.compile(r"<!--.*?-->|<!\[CDATA\[.*?\]\]>|<\?.*?\?>", re.S)
TAG_RE = re.compile(
    r"<(?P<end>/)?(?P<tag>[A-Za-z_][\w.:-]*)"
    r"(?P<attrs>(?:\s+[^\s=/>]+\s*=\s*(?:\"[^\"]*\"|'[^']*'))*)\s*(?P<empty>/)?>"
)
ATTR_RE = re.compile(r"([^\s=/>]+)\s*=\s*(?:\"([^\"]*)\"|'([^']*)')")
TRANSPARENT = frozenset({"xacro:if", "xacro:unless"})  # literal children pass through


@dataclass(eq=False)
class Lit:
    """One start tag written in a source file, with its literal children."""

    tag: str
    attrs: dict[str, str]
    line: int
    column: int
    empty: bool
    source: Source
    parent: Lit | None = None
    children: list[Lit] = field(default_factory=list)

    def top_level(self) -> bool:
        """Written directly under ``<robot>``, possibly inside xacro macros or conditions."""
        node = self.parent
        if node is None or self.tag.startswith("xacro:"):
            return False
        while node is not None:
            if node.tag != "robot" and not node.tag.startswith("xacro:"):
                return False
            node = node.parent
        return True

    def effective_children(self) -> Iterator[Lit]:
        """Children as they appear after expansion, when written literally."""
        for child in self.children:
            if child.tag in TRANSPARENT:
                yield from child.effective_children()
            elif not child.tag.startswith("xacro:"):
                yield child


@dataclass(eq=False)
class Source:
    """One XML file xacro read: the main file or an include."""

    path: str  # absolute and normalised
    shown: str  # as findings name it
    text: str
    chain: tuple[str, ...]  # the include chain, main file first, this file last

    @cached_property
    def blanked(self) -> str:
        """The text with comments, CDATA and processing instructions blanked out."""
        return BLANK_RE.sub(lambda m: re.sub(r"[^\n]", " ", m.group()), self.text)

    @cached_property
    def _starts(self) -> list[int]:
        return [0, *(m.end() for m in re.finditer(r"\n", self.text))]

    def position(self, offset: int) -> tuple[int, int]:
        """1-based line and column of a character offset."""
        line = bisect.bisect_right(self._starts, offset)
        return line, offset - self._starts[line - 1] + 1

    @cached_property
    def lits(self) -> list[Lit]:
        """Every literal start tag, in document order, linked into a tree."""
        found: list[Lit] = []
        stack: list[Lit] = []
        for match in TAG_RE.finditer(self.blanked):
            tag = match.group("tag")
            if match.group("end"):
                while stack:
                    if stack.pop().tag == tag:
                        break
                continue
            line, column = self.position(match.start())
            attrs = {
                m.group(1): _attr_value(m.group(2) if m.group(2) is not None else m.group(3))
                for m in ATTR_RE.finditer(match.group("attrs"))
            }
            parent = stack[-1] if stack else None
            lit = Lit(tag, attrs, line, column, bool(match.group("empty")), self, parent)
            if parent is not None:
                parent.children.append(lit)
            found.append(lit)
            if not lit.empty:
                stack.append(lit)
        return found

    def find(self, needle: str) -> tuple[int, int] | None:
        index = self.blanked.find(needle)
        return self.position(index) if index >= 0 else None


def _attr_value(raw: str) -> str:
    return html.unescape(re.sub(r"[\t\n\r]", " ", raw))


def _all(text: str, needle: str) -> Iterator[int]:
    start = text.find(needle)
    while start >= 0:
        yield start
        start = text.find(needle, start + 1)
