"""Results computed once per element of the document being linted, shared by every rule.

Many rules read the same things (a visual's shape, a link's ``<inertial>``, the schema walk
of the whole tree): :func:`table` gives each kind of result a dictionary keyed by element.
The tables belong to one tree, found from the element itself (its root); the tables of at
most :data:`MAX_TREES` trees are kept, and the engine drops them all when a document's rules
have run (:func:`forget`): a long-running service keeps nothing between requests.

Keys are the lxml element proxies themselves: a table holds them, so lxml keeps returning
those same objects for their nodes (an element proxy is recreated only once nothing holds
it), and a lookup is by identity. The trees are never edited after parsing (``urdflint fix``
edits the text and parses it again), so a result stays true for its element.

Thread-safe for the language server, which lints on a worker thread while it answers hovers
on another: the last tree asked is one tuple swapped whole, and switching trees or
forgetting takes a lock.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar

if TYPE_CHECKING:
    from lxml import etree

T = TypeVar("T")

MAX_TREES = 4  # the document being linted, and the few trees read beside it (an SRDF...)
_LAST: tuple[Any, dict[str, dict[Any, Any]]] = (None, {})  # the tree asked last, its tables
_TREES: dict[Any, dict[str, dict[Any, Any]]] = {}  # root element -> tables, oldest first
_LOCK = threading.Lock()


def table(el: etree._Element, name: str) -> dict[Any, Any]:
    """The table ``name`` of the tree ``el`` belongs to (empty the first time)."""
    root = el.getroottree().getroot()
    last, tables = _LAST  # one read: a root and its own tables, whatever other threads do
    if last is not root:
        tables = _tables_of(root)
    found = tables.get(name)
    if found is None:
        found = tables[name] = {}
    return found  # type: ignore[no-any-return]


def _tables_of(root: etree._Element) -> dict[str, dict[Any, Any]]:
    global _LAST
    with _LOCK:
        tables = _TREES.pop(root, None)
        if tables is None:
            tables = {}
            while len(_TREES) >= MAX_TREES:
                del _TREES[next(iter(_TREES))]  # the tree asked least recently
        _TREES[root] = tables  # now the most recent
        _LAST = (root, tables)
    return tables


def once(el: etree._Element, name: str, build: Callable[[], T]) -> T:
    """``build()``, computed once per tree (``el`` is any element of it, usually the root)."""
    found = table(el, name)
    if None not in found:
        found[None] = build()
    return found[None]  # type: ignore[no-any-return]


def forget() -> None:
    """Drop every table: the engine calls it when a document's rules have run, so nothing
    outlives a lint."""
    global _LAST
    with _LOCK:
        _TREES.clear()
        _LAST = (None, {})
