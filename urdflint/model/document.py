"""The :class:`Document` every rule reads.

One parse per file (:mod:`urdflint.model.parsing`: hardened, never expands entities
or loads a DTD; a document with a DOCTYPE or entity references is refused (X002),
never expanded). An XML declaration or stray text that the TinyXML-based consumers read
past is blanked out first (``Document.repairs``: the tree is exact, nothing is skipped). A
file that is still not well-formed XML gets its rules run on the tree libxml2 recovers,
when that is a ``<robot>`` (``Document.recovered``).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

from lxml import etree

from urdflint.model.finding import Call
from urdflint.model.graph import Graph
from urdflint.model.memo import table
from urdflint.model.parsing import MAX_BYTES, XACRO_NS, XmlProblem, local_tag, make_parser, parse
from urdflint.model.positions import Lines, attribute_offset, tag_start
from urdflint.model.providers import provided

if TYPE_CHECKING:  # provided by the engine at run time, see provide()
    from urdflint.engine.config import Settings
    from urdflint.engine.context import Context
    from urdflint.sources.resolve import Resolver

__all__ = [  # the parsing names are re-exported: the rest of urdflint imports them from here
    "MAX_BYTES",
    "XACRO_NS",
    "Document",
    "Joint",
    "Link",
    "Origin",
    "Origins",
    "XmlProblem",
    "children",
    "local_tag",
    "make_parser",
]


@dataclass(frozen=True, slots=True)
class Origin:
    """Where an element of an expanded xacro document was written.

    ``exact`` is false when only the top-level file and the expanded line are known.
    """

    path: str
    line: int
    column: int = 1
    exact: bool = True
    trace: tuple[Call, ...] = ()  # the macro calls that produced it, innermost first


class Origins(Protocol):
    """Where the elements of an expanded document are written (the xacro source map)."""

    def __call__(self, el: etree._Element, attribute: str | None = None) -> Origin | None: ...


def children(el: etree._Element, tag: str | None = None) -> list[etree._Element]:
    """Element children (no comments), optionally only those named ``tag`` (a new list each
    time; read once per element)."""
    found = table(el, "children")
    key = (el, tag)
    listed = found.get(key)
    if listed is None:
        listed = [c for c in el if isinstance(c.tag, str) and (tag is None or c.tag == tag)]
        found[key] = listed
    return list(listed)


# a link's first <inertial>, its <visual>s and its <collision>s
_Parts = tuple[etree._Element | None, list[etree._Element], list[etree._Element]]


class Link:
    """A ``<link>`` with its name; its ``<inertial>``, visuals and collisions are read on first
    use, in one pass over its children, and kept (the tree is never edited)."""

    __slots__ = ("_parts", "element", "name")

    def __init__(self, element: etree._Element) -> None:
        self.element = element
        self.name: str | None = element.get("name")
        self._parts: _Parts | None = None

    def _read(self) -> _Parts:
        inertial: etree._Element | None = None
        visuals: list[etree._Element] = []
        collisions: list[etree._Element] = []
        for child in self.element:
            tag = child.tag
            if tag == "visual":
                visuals.append(child)
            elif tag == "collision":
                collisions.append(child)
            elif tag == "inertial" and inertial is None:
                inertial = child
        self._parts = (inertial, visuals, collisions)
        return self._parts

    @property
    def inertial(self) -> etree._Element | None:
        """The first ``<inertial>`` (the one urdfdom reads)."""
        return (self._parts or self._read())[0]

    @property
    def visuals(self) -> list[etree._Element]:
        return (self._parts or self._read())[1]

    @property
    def collisions(self) -> list[etree._Element]:
        return (self._parts or self._read())[2]

    def __repr__(self) -> str:
        return f"Link({self.name!r})"


class Joint:
    """A ``<joint>`` with its name, type, parent and child link; :meth:`find` reads the first
    child of each tag once."""

    __slots__ = ("_first", "child", "element", "name", "parent", "type")

    def __init__(self, element: etree._Element) -> None:
        self.element = element
        self.name: str | None = element.get("name")
        self.type: str | None = element.get("type")
        first: dict[str, etree._Element] = {}
        for el in element:
            tag = el.tag
            if isinstance(tag, str) and tag not in first:
                first[tag] = el
        self._first = first
        parent = first.get("parent")
        child = first.get("child")
        self.parent: str | None = parent.get("link") if parent is not None else None
        self.child: str | None = child.get("link") if child is not None else None

    def find(self, tag: str) -> etree._Element | None:
        """The first child element ``<tag>`` (``element.find(tag)`` for a plain tag name)."""
        if tag.isidentifier():
            return self._first.get(tag)
        return self.element.find(tag)

    def __repr__(self) -> str:
        return f"Joint({self.name!r}, {self.type!r}, {self.parent!r} -> {self.child!r})"


class Document:
    """A parsed file with lazy views over its ``<robot>``.

    ``problem`` is set when the file is not well-formed XML (X001) or not a
    URDF robot (X002); then ``ok`` is false and only the rules that declare
    ``requires_robot=False`` run, unless the tree libxml2 recovered from a file
    that is not well-formed is a ``<robot>``: then ``recovered`` is true, ``robot``
    is that tree and the engine runs the rules on it too, marking their findings.
    ``repairs`` are what was blanked out before parsing (an XML declaration or stray text
    that TinyXML and TinyXML2 read past, reported by X001); a repaired document is ``ok``.
    """

    def __init__(
        self,
        path: str,
        source: bytes,
        *,
        targets: frozenset[str] = frozenset({"gazebo-classic"}),
        settings: Settings | None = None,
        context: Context | None = None,
        base_dir: Path | None = None,
        origin: Origins | None = None,
        problem: XmlProblem | None = None,
        library: bool = False,
    ) -> None:
        self.path = path
        self.source = source
        self.targets = targets
        self._settings = settings
        self._context = context
        self.base_dir = base_dir
        self.origin = origin  # set for documents expanded from xacro
        self.problem: XmlProblem | None = problem
        self.root: etree._Element | None = None
        self.library = library  # an included xacro file: only document-level rules run
        self.recovered = False  # root is libxml2's recovery of a file with an X001 problem
        self.repairs: tuple[XmlProblem, ...] = ()  # blanked out before parsing (X001)
        self.undeclared_prefixes: tuple[str, ...] = ()  # used without xmlns: (X012)
        self.default_namespace: str | None = None  # <robot xmlns="..."> (X002 warning)
        if problem is None:
            self._parse()

    # -- parsing -----------------------------------------------------------------

    def _parse(self) -> None:
        parsed = parse(self.source)
        self.root, self.problem, self.recovered = parsed.root, parsed.problem, parsed.recovered
        self.undeclared_prefixes = parsed.undeclared
        self.default_namespace = parsed.default_namespace
        self.repairs = parsed.repairs

    @property
    def ok(self) -> bool:
        """A usable ``<robot>`` from a well-formed file, or from one whose XML declaration or
        stray leading text was blanked out (``repairs``); not a recovered tree."""
        return self.root is not None and not self.recovered

    @property
    def robot(self) -> etree._Element:
        if self.root is None:
            raise RuntimeError("document is not a usable <robot>")
        return self.root

    @cached_property
    def memo(self) -> dict[str, Any]:
        """What the model and source helpers compute once per document (dropped with it;
        per-element results are in :mod:`urdflint.model.memo`)."""
        return {}

    @cached_property
    def lines(self) -> list[bytes]:
        return self.source.splitlines()

    # -- run context (provided by the engine: the model imports nothing above it) -------

    @property
    def settings(self) -> Settings:
        if self._settings is None:
            self._settings = provided("settings", self)
        return self._settings

    @property
    def context(self) -> Context:
        if self._context is None:
            self._context = provided("context", self)
        return self._context

    @cached_property
    def resolver(self) -> Resolver:
        """Resolves this document's mesh URIs (``package://``, ``file://``, relative)."""
        return self.context.resolver(self.base_dir, self.settings)

    @property
    def meshes(self) -> Any:
        """The run's mesh cache (trimesh is imported on first use)."""
        return self.context.meshes

    @cached_property
    def physics(self) -> Any:
        """The Pinocchio view of this document (Pinocchio is imported on first use)."""
        return provided("physics", self)

    # -- views ---------------------------------------------------------------------

    @cached_property
    def links(self) -> list[Link]:
        return [Link(el) for el in children(self.robot, "link")]

    @cached_property
    def joints(self) -> list[Joint]:
        return [Joint(el) for el in children(self.robot, "joint")]

    @cached_property
    def materials(self) -> list[etree._Element]:
        """Robot-level ``<material>`` definitions."""
        return children(self.robot, "material")

    @cached_property
    def gazebo(self) -> list[etree._Element]:
        """Robot-level ``<gazebo>`` extension blocks (with or without ``reference``)."""
        return children(self.robot, "gazebo")

    @cached_property
    def transmissions(self) -> list[etree._Element]:
        return children(self.robot, "transmission")

    @cached_property
    def link_map(self) -> dict[str, Link]:
        """Links by name; the first definition wins when a name repeats (S001)."""
        found: dict[str, Link] = {}
        for link in self.links:
            if link.name is not None:
                found.setdefault(link.name, link)
        return found

    @cached_property
    def joint_map(self) -> dict[str, Joint]:
        found: dict[str, Joint] = {}
        for joint in self.joints:
            if joint.name is not None:
                found.setdefault(joint.name, joint)
        return found

    @cached_property
    def material_map(self) -> dict[str, etree._Element]:
        found: dict[str, etree._Element] = {}
        for material in self.materials:
            name = material.get("name")
            if name is not None:
                found.setdefault(name, material)
        return found

    @cached_property
    def graph(self) -> Graph:
        return Graph.build(self.link_map, self.joints)

    # -- locations -----------------------------------------------------------------

    def element_path(self, el: etree._Element | None) -> str:
        """A name-based path such as ``/robot/link[@name='arm']/visual[2]/geometry``."""
        if el is None or self.root is None:
            return "/robot"
        parts: list[str] = []
        node: etree._Element | None = el
        while node is not None and not isinstance(node, etree._Comment):
            parts.append(self._step(node))
            if node is self.root:
                break
            node = node.getparent()
        return "/" + "/".join(reversed(parts))

    @staticmethod
    def _step(node: etree._Element) -> str:
        tag = local_tag(node)
        for key in ("name", "reference"):
            value = node.get(key)
            if value is not None and node.getparent() is not None:
                quote = '"' if "'" in value else "'"
                return f"{tag}[@{key}={quote}{value}{quote}]"
        parent = node.getparent()
        if parent is None:
            return tag
        same = [c for c in parent if c.tag == node.tag]
        return f"{tag}[{same.index(node) + 1}]" if len(same) > 1 else tag

    @cached_property
    def _positions(self) -> Lines:
        return Lines(self.source)

    def _tag_offset(self, el: etree._Element) -> int | None:
        tag = local_tag(el)
        if not el.sourceline or not tag or "/" in tag:
            return None
        return tag_start(self._positions, tag, el.sourceline)

    def start_of(self, el: etree._Element) -> tuple[int, int]:
        """1-based line and column of the element's ``<tag``."""
        offset = self._tag_offset(el)
        if offset is None:
            line = el.sourceline or 1
            return line, self.column_of(el, line)
        return self._positions.position(offset)

    def attribute_at(self, el: etree._Element, name: str) -> tuple[int, int] | None:
        """1-based line and column of ``name=`` in the element's start tag, if written there."""
        offset = self._tag_offset(el)
        found = attribute_offset(self.source, offset, name) if offset is not None else None
        return self._positions.position(found) if found is not None else None

    def column_of(self, el: etree._Element, line: int) -> int:
        """1-based column of ``<tag`` on the element's start line (1 when not found)."""
        if not 1 <= line <= len(self.lines):
            return 1
        text = self.lines[line - 1]
        tag = local_tag(el).encode()
        index = text.find(b"<" + tag)
        return len(text[:index].decode("utf-8", "replace")) + 1 if index >= 0 else 1
