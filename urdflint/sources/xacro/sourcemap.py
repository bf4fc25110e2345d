"""The xacro source map: where each element of the expanded document is written.

xacro works on ``xml.dom.minidom`` trees. While urdflint expands a file, every DOM node
xacro parses is marked with its source (which file, at which byte) by an instrumented
expat builder, and every node xacro clones carries its original's mark: a macro body
instantiated by a call (``m.body.cloneNode``) gets the call site pushed on its call chain,
a block (``*param``/``**param``) keeps the chain of the caller that wrote it. Conditions,
includes and ``xacro:element`` move or rename nodes in place, so their marks survive as
they are.

After expansion the final DOM and the lxml tree the rules read are walked in parallel
(both hold the same elements and comments in the same order); each lxml element then
knows its :class:`~urdflint.model.document.Origin`: the file, line and column of its
start tag, and the chain of macro calls that produced it, innermost first.
"""

from __future__ import annotations

import xml.dom
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any
from xml.dom.expatbuilder import ExpatBuilderNS

from lxml import etree

from urdflint.model.document import Origin
from urdflint.model.finding import Call
from urdflint.model.positions import Lines, attribute_offset

MARK = "_urdflint_mark"  # the attribute set on minidom nodes: (source, byte offset, chain)

# A chain link: the macro called and the (source index, byte offset) of its call.
Link = tuple[str, int, int]
Mark = tuple[int, int, tuple[Link, ...]]


@dataclass(eq=False)
class SourceFile:
    """One file xacro parsed, kept as bytes so expat's byte offsets index it."""

    path: str  # absolute
    shown: str  # as findings name it
    data: bytes

    @cached_property
    def _lines(self) -> Lines:
        return Lines(self.data)

    def position(self, offset: int) -> tuple[int, int]:
        """1-based line and (character) column of a byte offset."""
        return self._lines.position(offset)


def builder_class(files: list[SourceFile], index: int) -> type[ExpatBuilderNS]:
    """An expat DOM builder that marks each element and comment with its byte offset."""

    class Builder(ExpatBuilderNS):  # type: ignore[misc]
        def start_element_handler(self, name: str, attributes: Any) -> None:
            offset = self._parser.CurrentByteIndex  # type: ignore[attr-defined]
            super().start_element_handler(name, attributes)
            setattr(self.curNode, MARK, (index, offset, ()))

        def comment_handler(self, data: str) -> None:
            offset = self._parser.CurrentByteIndex  # type: ignore[attr-defined]
            super().comment_handler(data)
            last = self.curNode.lastChild
            if last is not None and last.nodeType == xml.dom.Node.COMMENT_NODE:
                setattr(last, MARK, (index, offset, ()))

    return Builder


@dataclass
class Tracker:
    """Carries marks through xacro's clones while one expansion runs."""

    files: list[SourceFile] = field(default_factory=list)
    pending: tuple[str, Any] | None = None  # a macro call about to clone its body
    active: tuple[Link, ...] | None = None  # the chain given to the body being cloned

    def parse(self, data: bytes, path: str, shown: str) -> Any:
        """``data`` as a marked minidom document."""
        index = next((i for i, f in enumerate(self.files) if f.path == path), None)
        if index is None:
            index = len(self.files)
            self.files.append(SourceFile(path, shown, data))
        return builder_class(self.files, index)().parseString(data)

    def calling(self, original: Callable[..., Any]) -> Callable[..., Any]:
        """Wrap xacro's ``handle_macro_call``: the next macro body cloned belongs to this call."""

        def handle_macro_call(node: Any, macros: Any, symbols: Any) -> Any:
            if not node.tagName.startswith("xacro:"):
                return original(node, macros, symbols)
            saved = self.pending
            self.pending = (node.tagName[6:], node)
            try:
                return original(node, macros, symbols)
            finally:
                self.pending = saved

        return handle_macro_call

    def cloning(self, original: Callable[..., Any]) -> Callable[..., Any]:
        """Wrap minidom's ``_clone_node`` so that clones keep (and extend) their marks."""

        def clone_node(node: Any, deep: bool, owner: Any) -> Any:
            if self.pending is not None and getattr(node, "tagName", None) == "xacro:macro":
                name, call = self.pending
                self.pending = None
                mark = getattr(call, MARK, None)
                chain = ((name, mark[0], mark[1]), *mark[2]) if mark is not None else ()
                saved, self.active = self.active, chain
                try:
                    return clone_node(node, deep, owner)
                finally:
                    self.active = saved
            copy = original(node, deep, owner)
            mark = getattr(node, MARK, None)
            if mark is not None:
                setattr(copy, MARK, mark if self.active is None else (*mark[:2], self.active))
            return copy

        return clone_node


def _dom_nodes(node: Any) -> Iterator[Any]:
    """Elements and comments of a minidom subtree in document order (what lxml keeps)."""
    stack = [node]
    element, comment = xml.dom.Node.ELEMENT_NODE, xml.dom.Node.COMMENT_NODE
    while stack:
        current = stack.pop()
        yield current
        kids = [c for c in current.childNodes if c.nodeType in (element, comment)]
        stack.extend(reversed(kids))


def nodes(root: etree._Element) -> Iterator[etree._Element]:
    """Elements and comments of an lxml tree in document order (what the DOM walk pairs)."""
    for el in root.iter():
        if isinstance(el.tag, str) or isinstance(el, etree._Comment):
            yield el


def _local(tag: str) -> str:
    return tag.rpartition("}")[2] if tag.startswith("{") else tag.rpartition(":")[2]


class SourceMap:
    """``el -> Origin``: where an element of the expanded document is written.

    Built lazily on the first question, by walking the final DOM and the lxml tree in
    parallel. If the two walks disagree (they never should), nothing is mapped and every
    element falls back to its line in the expanded document.

    A map :meth:`carried` over to a document patched from this one (:mod:`.patch`: same
    elements and comments in the same order, one source file edited) holds no DOM but the
    marks in document order, paired with the new tree on its first question.
    """

    def __init__(
        self,
        files: list[SourceFile],
        dom: Any,
        shown: str,
        expanded: bytes,
        *,
        order: list[Mark | None] | None = None,
    ) -> None:
        self.files = files
        self.dom = dom
        self.shown = shown
        self.expanded = expanded
        self._order = order  # the marks in document order (see sequence and carried)
        self._marks: dict[Any, Mark] | None = None
        self._origins: dict[Mark, Origin] = {}

    def _build(self, root: etree._Element) -> dict[Any, Mark]:
        if self._order is not None:
            return self._zip(root, self._order)
        dom = self.dom  # read once: another thread may be building too
        if dom is None:
            return {}
        marks: dict[Any, Mark] = {}
        dom_nodes = _dom_nodes(dom.documentElement)
        for el in root.iter():
            if not isinstance(el.tag, str) and not isinstance(el, etree._Comment):
                continue  # processing instructions are dropped by the document parser
            node = next(dom_nodes, None)
            if node is None:
                return {}
            if isinstance(el.tag, str):
                if node.nodeType != xml.dom.Node.ELEMENT_NODE or _local(node.tagName) != _local(
                    el.tag
                ):
                    return {}
            elif node.nodeType != xml.dom.Node.COMMENT_NODE:
                return {}
            mark = getattr(node, MARK, None)
            if mark is not None:
                marks[el] = mark
        self.dom = None  # the DOM is not needed any more
        return marks

    def _zip(self, root: etree._Element, order: list[Mark | None]) -> dict[Any, Mark]:
        listed = list(nodes(root))
        if len(listed) != len(order):
            self._order = None
            return {}
        return {el: mark for el, mark in zip(listed, order, strict=True) if mark is not None}

    def _all(self, root: etree._Element) -> dict[Any, Mark]:
        if self._marks is None:
            self._marks = self._build(root)
        return self._marks

    def mark(self, el: etree._Element) -> Mark | None:
        return self._all(el.getroottree().getroot()).get(el)

    def sequence(self, root: etree._Element) -> list[Mark | None] | None:
        """The mark of each element and comment of ``root`` in document order (``None``: the
        tree could not be mapped). Kept: the list is shared, do not change it."""
        marks = self._all(root)
        if not marks:
            return None
        if self._order is None:
            self._order = [marks.get(el) for el in nodes(root)]
        return self._order

    def written_at(self, root: etree._Element, source: int, offset: int) -> list[etree._Element]:
        """The elements of ``root`` written by the start tag at byte ``offset`` of file
        ``source`` (every copy a macro or block made of it), in document order."""
        return [
            el
            for el, mark in self._all(root).items()
            if mark[1] == offset and mark[0] == source and isinstance(el.tag, str)
        ]

    def carried(
        self, index: int, data: bytes, at: int, delta: int, expanded: bytes, root: etree._Element
    ) -> SourceMap | None:
        """The map of ``expanded``, a document with the same elements and comments in the same
        order as ``root``'s, for the sources where file ``index`` now reads ``data``: ``delta``
        bytes were inserted (removed, when negative) at byte ``at`` of that file, so the marks
        at or after ``at`` in it move by ``delta``."""
        order = self.sequence(root)
        if order is None:
            return None
        files = list(self.files)
        before = files[index]
        files[index] = SourceFile(before.path, before.shown, data)
        chains: dict[int, tuple[Link, ...]] = {}  # by identity: a macro call's nodes share one

        def moved(chain: tuple[Link, ...]) -> tuple[Link, ...]:
            found = chains.get(id(chain))
            if found is None:
                found = chain
                if any(i == index and o >= at for _, i, o in chain):
                    found = tuple(
                        (m, i, o + delta if i == index and o >= at else o) for m, i, o in chain
                    )
                chains[id(chain)] = found
            return found

        shifted: list[Mark | None] = []
        append = shifted.append
        for mark in order:
            if mark is None:
                append(None)
                continue
            source, offset, chain = mark
            new = moved(chain) if chain else chain
            if source == index and offset >= at:
                append((source, offset + delta, new))
            elif new is not chain:
                append((source, offset, new))
            else:
                append(mark)
        return SourceMap(files, None, self.shown, expanded, order=shifted)

    def __call__(self, el: etree._Element, attribute: str | None = None) -> Origin | None:
        mark = self.mark(el)
        if mark is None:
            return self._expanded(el)
        if attribute is not None:
            found = self._attribute(mark, attribute)
            if found is not None:
                return found
        found = self._origins.get(mark)
        if found is None:
            file = self.files[mark[0]]
            line, column = file.position(mark[1])
            chain = tuple(self._call(link) for link in mark[2])
            found = self._origins[mark] = Origin(file.shown, line, column, True, chain)
        return found

    def _attribute(self, mark: Mark, name: str) -> Origin | None:
        """Where ``name=`` is written in the start tag (for ``xacro:attribute``, nowhere)."""
        file = self.files[mark[0]]
        offset = attribute_offset(file.data, mark[1], name)
        if offset is None:
            return None
        line, column = file.position(offset)
        chain = tuple(self._call(link) for link in mark[2])
        return Origin(file.shown, line, column, True, chain)

    def _expanded(self, el: etree._Element) -> Origin | None:
        """The element's line in the expanded document, marked not exact."""
        line = el.sourceline
        if not line:
            return None
        text = self._lines[line - 1] if line <= len(self._lines) else b""
        tag = el.tag if isinstance(el.tag, str) else ""
        index = text.find(b"<" + _local(tag).encode()) if tag else -1
        column = len(text[:index].decode("utf-8", "replace")) + 1 if index >= 0 else 1
        return Origin(self.shown, line, column, exact=False)

    @cached_property
    def _lines(self) -> list[bytes]:
        return self.expanded.splitlines()

    def _call(self, link: Link) -> Call:
        macro, index, offset = link
        file = self.files[index]
        line, column = file.position(offset)
        return Call(macro, file.shown, line, column)
