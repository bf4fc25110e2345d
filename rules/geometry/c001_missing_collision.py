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
fix is unsafe because the link starts to make contact. Meshes get no automatic fix (a
collision mesh should be simpler than the visual one), nor do xacro sources (the values
may be expressions).
"""

from __future__ import annotations

from collections.abc import Iterator
from xml.sax.saxutils import quoteattr

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, Link, children
from urdflint.model.edits import InsertChild, Repair
from urdflint.model.finding import Severity
from urdflint.model.schema import SPECS
from urdflint.model.structure import q, welded
from urdflint.model.values import parse_numbers

# The shapes copied into a collision, and how many positive numbers each attribute holds.
PRIMITIVES = {"box": {"size": 3}, "cylinder": {"radius": 1, "length": 1}, "sphere": {"radius": 1}}


@rule(
    "C001",
    "missing-collision",
    Severity.WARNING,
    fix="Add a <collision> with a simple shape that bounds the visual.",
    fixable="unsafe",
)
def check(doc: Document) -> Iterator[Hit]:
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
                repair=_repair(doc, link),
            )
        else:
            yield Hit(
                link.element,
                f"link {q(link.name)} has a visual but no collision "
                f"(it is welded to link {colliding!r}, which has one)",
                severity=Severity.INFO,
            )


def _repair(doc: Document, link: Link) -> Repair | None:
    """A collision after each visual, with its origin and shape (primitives only)."""
    if doc.origin is not None:
        return None  # xacro: the values may be expressions of a macro's parameters
    operations = []
    for visual in link.visuals:
        xml = _collision(visual)
        if xml is None:
            return None
        operations.append(InsertChild(link.element, xml, after=visual))
    description = "add a collision with the shape of each visual"
    return Repair("unsafe", description, tuple(operations))


def _collision(visual: etree._Element) -> str | None:
    geometry = visual.find("geometry")
    shapes = children(geometry) if geometry is not None else []
    if len(shapes) != 1 or shapes[0].tag not in PRIMITIVES:
        return None
    shape = shapes[0]
    for attr, size in PRIMITIVES[str(shape.tag)].items():
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
    attrs = "".join(f" {k}={quoteattr(v)}" for k, v in el.attrib.items() if k in known)
    return f"<{el.tag}{attrs}/>"
