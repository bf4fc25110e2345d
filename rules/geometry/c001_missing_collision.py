"""A link has a `<visual>` but no `<collision>`.

## What it does
Reports a link that is drawn (has a `<visual>`) but has no `<collision>`.
It is a warning when the rigid body the link belongs to (the link plus every
link welded to it by `fixed` joints) has no collision anywhere, and info when
another link of that body has one, as for a camera housing or a decorative
shell bolted to a part that does collide.

## Why is this bad?
Gazebo never uses a `<visual>` as a collision shape: the link is "invisible"
to laser scanners, depth cameras and collision checking (the "Using a URDF in
Gazebo" tutorial), so it passes through the ground and other objects. MoveIt
plans straight through it, and its self-collision matrix stays empty for the
link. MuJoCo discards visuals (`discardvisual`), so the body has no contact at
all. When a welded neighbour collides the body still makes contact, but
sensors will not see the visual-only part.

## How to fix
Add a `<collision>` with a simple shape (a box, cylinder or sphere around the
visual, or a simplified mesh). For a purely decorative part that must not
collide, move its `<visual>` into the link it is welded to, or suppress this
finding for the link.

`urdflint fix --unsafe-fixes` adds after each visual a `<collision>` with the same
`<origin>` and shape, when the link's body has no collision at all (warning) and every
visual of the link is a box, cylinder or sphere of valid size, in a plain URDF file. The
fix is unsafe because the link starts to make contact. A mesh visual is given a
collision only with `--write-meshes` (or `write_meshes = true` in `[rules.C001]`): the
fix then writes the mesh's convex hull as `<stem>_hull.obj` beside it (an existing file
is never overwritten) and the collision refers to it with the visual's `scale`. A
convex hull is what MuJoCo, PyBullet and Drake make of a collision mesh anyway, and OBJ
is the one format every target reads for collision (Drake refuses STL and Collada, C009).
xacro sources get no automatic fix (the values may be expressions of a macro's parameters).
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, Link, children
from urdflint.model.edits import CreateFile, InsertChild, Operation, Repair
from urdflint.model.finding import Severity
from urdflint.model.geometry import read_shape
from urdflint.model.schema import SPECS
from urdflint.model.structure import q, welded
from urdflint.model.values import has_xacro, parse_numbers, xml_attribute
from urdflint.sources.hulls import HullFile, hull_file

# The shapes copied into a collision, and how many positive numbers each attribute holds.
PRIMITIVES = {"box": {"size": 3}, "cylinder": {"radius": 1, "length": 1}, "sphere": {"radius": 1}}
HULL = "add a collision with each visual's shape (a mesh's convex hull, written beside it)"


@rule(
    "C001",
    "missing-collision",
    Severity.WARNING,
    fix="Add a <collision> with a simple shape that bounds the visual.",
    fixable="unsafe",
    options={"write_meshes": False},
)
def check(doc: Document, opts: dict[str, Any]) -> Iterator[Hit]:
    hulls = bool(opts["write_meshes"])
    for link in doc.links:
        if not link.visuals or link.collisions:
            continue
        colliding = None
        if link.name is not None and doc.link_map.get(link.name) is link:
            body = welded(doc.graph, link.name)
            colliding = next((n for n in body if doc.link_map[n].collisions), None)
        if colliding is None:
            yield Hit(
                link.element,
                f"link {q(link.name)} has a visual but no collision",
                repair=_repair(doc, link, hulls),
            )
        else:
            yield Hit(
                link.element,
                f"link {q(link.name)} has a visual but no collision "
                f"(it is welded to link {colliding!r}, which has one)",
                severity=Severity.INFO,
            )


def _repair(doc: Document, link: Link, hulls: bool) -> Repair | None:
    """A collision after each visual, with its origin and shape (primitives; meshes as their
    convex hull, written beside them, with ``hulls``)."""
    if doc.origin is not None:
        return None  # xacro: the values may be expressions of a macro's parameters
    operations: list[Operation] = []
    written: list[Operation] = []
    meshes = False
    for visual in link.visuals:
        shape = _shape(visual)
        if shape is not None and shape.tag == "mesh":
            meshes = True
            if not hulls:
                continue
            hull = _hull(doc, visual)
            if isinstance(hull, str):
                return Repair("unsafe", HULL, (), hull)
            written.append(CreateFile(str(hull.path), hull.text))
            shape = _hull_mesh(shape, hull.uri)
        xml = _collision(visual, shape)
        if xml is None:
            return None
        operations.append(InsertChild(link.element, xml, after=visual))
    if meshes and not hulls:
        return Repair("unsafe", HULL, (), "the visual is a mesh: --write-meshes writes its hull")
    description = HULL if meshes else "add a collision with the shape of each visual"
    return Repair("unsafe", description, tuple(operations + written))


def _shape(visual: etree._Element) -> etree._Element | None:
    geometry = visual.find("geometry")
    shapes = children(geometry) if geometry is not None else []
    return shapes[0] if len(shapes) == 1 else None


def _hull(doc: Document, visual: etree._Element) -> HullFile | str:
    shape = read_shape(visual)
    if shape is None or not (shape.filename or "").strip() or has_xacro(shape.filename or ""):
        return "the mesh's filename is missing or not a plain path"
    return hull_file(doc, shape)


def _hull_mesh(mesh: etree._Element, uri: str) -> etree._Element:
    """``<mesh filename="<hull>" scale="..."/>``: the visual's mesh pointing at its hull."""
    copy = etree.Element("mesh", filename=uri)
    if mesh.get("scale") is not None:
        copy.set("scale", mesh.get("scale") or "")
    return copy


def _collision(visual: etree._Element, shape: etree._Element | None) -> str | None:
    if shape is None or shape.tag not in (*PRIMITIVES, "mesh"):
        return None
    for attr, size in PRIMITIVES.get(str(shape.tag), {}).items():
        values = parse_numbers(shape.get(attr))
        if values is None or len(values) != size or min(values) <= 0:
            return None  # an invalid shape (C003) is not copied
    lines = ["<collision>"]
    origin = visual.find("origin")
    if origin is not None:
        for attr, kind in SPECS["origin"].attrs.items():
            values = parse_numbers(origin.get(attr))
            if origin.get(attr) is not None and (values is None or len(values) != kind.arity):
                return None  # an invalid origin (X004, X005) is not copied
        lines.append("  " + _empty(origin))
    lines += ["  <geometry>", "    " + _empty(shape), "  </geometry>", "</collision>"]
    return "\n".join(lines)


def _empty(el: etree._Element) -> str:
    """``<tag a="..."/>`` with the element's URDF attributes, in the order written."""
    known = SPECS[str(el.tag)].attrs
    attrs = "".join(f' {k}="{xml_attribute(v)}"' for k, v in el.attrib.items() if k in known)
    return f"<{el.tag}{attrs}/>"
