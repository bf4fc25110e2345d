"""Hardened parsing and the :class:`Document` every rule reads.

One parse per file. The parser never expands entities, never loads a DTD,
never touches the network and keeps libxml2's size and depth limits; comments
stay in the tree because they carry suppressions. A document with a DOCTYPE or
entity references is refused (X002), never expanded.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

from lxml import etree

from urdflint.model.finding import Call
from urdflint.model.graph import Graph
from urdflint.model.positions import Lines, attribute_offset, tag_start
from urdflint.model.providers import provided

if TYPE_CHECKING:  # provided by the engine at run time, see provide()
    from urdflint.engine.config import Settings
    from urdflint.engine.context import Context
    from urdflint.sources.resolve import Resolver


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


MAX_BYTES = 64 * 2**20
XACRO_NS = "http://www.ros.org/wiki/xacro"


class Origins(Protocol):
    """Where the elements of an expanded document are written (the xacro source map)."""

    def __call__(self, el: etree._Element, attribute: str | None = None) -> Origin | None: ...


@dataclass(frozen=True, slots=True)
class XmlProblem:
    """Why a document is not a usable ``<robot>``: X001 (syntax) or X002 (not a robot)."""

    code: str
    message: str
    line: int = 1
    column: int = 1
    path: str | None = None  # xacro: the (shown) file the problem is in, when not the main file


def make_parser() -> etree.XMLParser:
    # One parser per parse: lxml parsers are not safe to share across threads.
    return etree.XMLParser(
        resolve_entities=False,
        no_network=True,
        load_dtd=False,
        dtd_validation=False,
        huge_tree=False,
        remove_comments=False,
        remove_pis=True,
        remove_blank_text=False,
    )


def local_tag(el: etree._Element) -> str:
    """``link`` for ``<link>``, ``xacro:macro`` for a namespaced xacro element."""
    tag = el.tag
    if not isinstance(tag, str):
        return ""
    if tag.startswith("{"):
        uri, _, local = tag[1:].partition("}")
        prefix = el.prefix or ("xacro" if "xacro" in uri else uri)
        return f"{prefix}:{local}"
    return tag


def children(el: etree._Element, tag: str | None = None) -> list[etree._Element]:
    """Element children (no comments), optionally only those named ``tag``."""
    return [c for c in el if isinstance(c.tag, str) and (tag is None or c.tag == tag)]


class Link:
    __slots__ = ("element", "name")

    def __init__(self, element: etree._Element) -> None:
        self.element = element
        self.name: str | None = element.get("name")

    @property
    def inertial(self) -> etree._Element | None:
        return self.element.find("inertial")

    @property
    def visuals(self) -> list[etree._Element]:
        return children(self.element, "visual")

    @property
    def collisions(self) -> list[etree._Element]:
        return children(self.element, "collision")

    def __repr__(self) -> str:
        return f"Link({self.name!r})"


class Joint:
    __slots__ = ("child", "element", "name", "parent", "type")

    def __init__(self, element: etree._Element) -> None:
        self.element = element
        self.name: str | None = element.get("name")
        self.type: str | None = element.get("type")
        parent = element.find("parent")
        child = element.find("child")
        self.parent: str | None = parent.get("link") if parent is not None else None
        self.child: str | None = child.get("link") if child is not None else None

    def find(self, tag: str) -> etree._Element | None:
        return self.element.find(tag)

    def __repr__(self) -> str:
        return f"Joint({self.name!r}, {self.type!r}, {self.parent!r} -> {self.child!r})"


class Document:
    """A parsed file with lazy views over its ``<robot>``.

    ``problem`` is set when the file is not well-formed XML (X001) or not a
    URDF robot (X002); then ``ok`` is false and only the rules that declare
    ``requires_robot=False`` run.
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
        if problem is None:
            self._parse()

    # -- parsing -----------------------------------------------------------------

    def _parse(self) -> None:
        if len(self.source) > MAX_BYTES:
            self.problem = XmlProblem(
                "X001", f"file is {len(self.source) / 2**20:.0f} MiB, over the 64 MiB limit"
            )
            return
        try:
            root = etree.fromstring(self.source, make_parser())
        except etree.XMLSyntaxError as exc:
            if b"<!DOCTYPE" in self.source or b"<!ENTITY" in self.source:
                # e.g. an entity bomb libxml2 stopped: refuse it as a DOCTYPE, not a typo
                self.problem = self._doctype_problem()
                return
            line, column = exc.position if exc.position else (1, 1)
            message = (exc.msg or str(exc)).strip()
            message = message.split(", line ")[0] if ", line " in message else message
            self.problem = XmlProblem("X001", message, max(line, 1), max(column, 1))
            return
        except ValueError as exc:  # e.g. an encoding declaration lxml refuses
            self.problem = XmlProblem("X001", str(exc))
            return
        tree = root.getroottree()
        if tree.docinfo.internalDTD is not None or tree.docinfo.doctype:
            self.problem = self._doctype_problem()
            return
        entity = next(root.iter(etree.Entity), None)
        if entity is not None:
            self.problem = XmlProblem(
                "X002", f"document uses the entity reference {entity.text}", entity.sourceline or 1
            )
            return
        if root.tag != "robot":
            self.problem = XmlProblem(
                "X002", f"root element is <{local_tag(root)}>, not <robot>", root.sourceline or 1
            )
            return
        self.root = root

    def _doctype_problem(self) -> XmlProblem:
        return XmlProblem(
            "X002",
            "document has a DOCTYPE declaration; URDF never needs one and it is not expanded",
            self._line_of(b"<!DOCTYPE"),
        )

    def _line_of(self, needle: bytes) -> int:
        index = self.source.find(needle)
        return self.source.count(b"\n", 0, index) + 1 if index >= 0 else 1

    @property
    def ok(self) -> bool:
        return self.root is not None

    @property
    def robot(self) -> etree._Element:
        if self.root is None:
            raise RuntimeError("document is not a usable <robot>")
        return self.root

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
