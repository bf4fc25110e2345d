"""Inline suppressions written as XML comments.

``<!-- urdflint: ignore[I001,J004] reason -->`` immediately before an element
(other comments may sit between) covers that element and its subtree; the same
comment as the first thing inside a start tag's line covers that element.
``<!-- urdflint: ignore-file[G002] -->`` anywhere covers the whole file. Codes
(or rule names, or family prefixes) are mandatory.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from lxml import etree

from urdflint.engine import registry

DIRECTIVE_RE = re.compile(
    r"^\s*urdflint\s*:\s*(?P<kind>[a-z-]+)\s*(?:\[(?P<codes>[^\]]*)\])?(?P<reason>.*)$", re.S
)


@dataclass(eq=False)
class Directive:
    kind: str  # "ignore" or "ignore-file"
    codes: frozenset[str]
    comment: etree._Element
    target: etree._Element | None  # None for ignore-file
    used: set[str] = field(default_factory=set)

    @property
    def line(self) -> int:
        return self.comment.sourceline or 1

    def covers(self, code: str, element: etree._Element | None, root: etree._Element) -> bool:
        if code not in self.codes:
            return False
        if self.target is None:
            return True
        node = element if element is not None else root
        while node is not None:
            if node is self.target:
                return True
            node = node.getparent()
        return False


@dataclass(frozen=True)
class Malformed:
    comment: etree._Element
    message: str


def _comments(root: etree._Element) -> list[etree._Element]:
    before = [c for c in root.itersiblings(preceding=True) if isinstance(c, etree._Comment)]
    after = [c for c in root.itersiblings() if isinstance(c, etree._Comment)]
    inside = [c for c in root.iter(etree.Comment)]
    return [*reversed(before), *inside, *after]


def _target(comment: etree._Element, root: etree._Element) -> etree._Element | None:
    """The element a directive covers: its parent when the comment is the first thing
    after the parent's start tag on the same line, else the next element sibling."""
    parent = comment.getparent()
    if parent is not None and parent.sourceline == comment.sourceline:
        first = next((c for c in parent if not isinstance(c, etree._Comment) or c is comment), None)
        if first is comment and not (parent.text or "").strip():
            return parent
    for sibling in comment.itersiblings():
        if isinstance(sibling, etree._Comment):
            continue
        if isinstance(sibling.tag, str):
            return sibling  # for a comment before the root element this is the root
    return None


def parse(root: etree._Element) -> tuple[list[Directive], list[Malformed]]:
    directives: list[Directive] = []
    malformed: list[Malformed] = []
    for comment in _comments(root):
        match = DIRECTIVE_RE.match(comment.text or "")
        if not match:
            continue
        kind = match["kind"]
        if kind not in ("ignore", "ignore-file"):
            malformed.append(
                Malformed(
                    comment,
                    f"unknown directive 'urdflint: {kind}' (use ignore[...] or ignore-file[...])",
                )
            )
            continue
        raw = [c.strip() for c in (match["codes"] or "").split(",") if c.strip()]
        if not raw:
            malformed.append(
                Malformed(comment, f"'urdflint: {kind}' needs rule codes, e.g. {kind}[I001]")
            )
            continue
        try:
            codes = registry.expand(raw)
        except ValueError as exc:
            malformed.append(Malformed(comment, f"suppression names an {exc}"))
            continue
        target = None
        if kind == "ignore":
            target = _target(comment, root)
            if target is None:
                malformed.append(Malformed(comment, "suppression is not followed by an element"))
                continue
        directives.append(Directive(kind, frozenset(codes), comment, target))
    return directives, malformed
