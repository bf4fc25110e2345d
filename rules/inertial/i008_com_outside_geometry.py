"""The centre of mass lies outside the link's collision geometry.

## What it does
Builds the bounding box, in the link frame (origins and rotations applied),
of every `<collision>` and `<visual>` of a link and reports an
`<inertial><origin xyz>` outside it by more than a margin: 10% of the box's
largest side for primitives, 25% when a mesh is involved (at least 1 mm).
Boxes, cylinders, spheres and capsules count as they are; a mesh counts with
the bounding box of the loaded file after its `scale` (with trimesh installed;
without it, links with meshes are skipped). A link is skipped when one of its
shapes cannot be read: a missing or unreadable mesh (C004, C005) or one whose
size says it is not in metres (C006).

Using every visual and collision together keeps partial collision proxies (a
sphere for the elbow, a box for the motor) from raising false alarms: the
visual mesh covers the whole part. The wider margin for meshes allows for
parts a visual mesh leaves out although they carry mass (motors, cables,
electronics inside another link's shell). A centre of mass that lies in the
geometry of a link welded to this one by fixed joints (the rigid body the
simulators build) is accepted: descriptions often put a whole assembly's mass
on one of its links. Sensor frames negligible next to the body they are fixed
to are skipped too.

## Why is this bad?
A centre of mass outside the body is almost always a frame mistake: the
inertial origin written in the joint or parent frame instead of the link
frame, a sign flip, or a unit slip (millimetres for metres). Gravity then
pulls on the wrong point: gravity-compensation torques, the robot's balance
and its support polygon are all wrong, in every simulator, without warning.
(A hollow or bent part can have its centre of mass outside its material, but
not outside its bounding box.)

## How to fix
Express the centre of mass in the link frame, in metres. Check the
`<inertial><origin>` against the `<collision><origin>` and against where the
mesh sits in that frame.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import Bodies, bodies
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity
from urdflint.model.inertia import Vec, apply, geometry_box, has_mesh, transform_box
from urdflint.model.values import fmt

MARGIN = 0.1
MESH_MARGIN = 0.25  # a mesh's box often leaves out parts that carry mass (motors, cables)
MIN_MARGIN = 0.001  # metres


@rule(
    "I008",
    "com-outside-geometry",
    Severity.WARNING,
    fix="Express the centre of mass in the link frame, in metres.",
)
def check(doc: Document) -> Iterator[Hit]:
    b = bodies(doc)
    for name, inertial in b.inertials.items():
        if inertial is None or inertial.xyz is None or not inertial.mass or inertial.mass <= 0:
            continue
        link = doc.link_map[name].element
        box = geometry_box(doc, link, TAGS)
        if box is None or b.negligible(name):
            continue
        com = inertial.xyz
        if _inside(com, box, has_mesh(link, TAGS)):
            continue
        if _inside_body(doc, b, name, com):
            continue  # the link carries the mass of links welded to it (a dummy-mass pattern)
        lo, hi = box
        spans = ", ".join(f"{axis} {fmt(lo[i])}…{fmt(hi[i])}" for i, axis in enumerate("xyz"))
        yield Hit(
            inertial.origin if inertial.origin is not None else inertial.element,
            f"link '{name}' has its centre of mass at ({', '.join(fmt(v) for v in com)}) m, "
            f"outside its geometry ({spans} m)",
        )


TAGS = ("collision", "visual")


def _inside(point: Vec, box: tuple[Vec, Vec], meshes: bool) -> bool:
    lo, hi = box
    share = MESH_MARGIN if meshes else MARGIN
    margin = max(share * max(hi[i] - lo[i] for i in range(3)), MIN_MARGIN)
    return all(lo[i] - margin <= point[i] <= hi[i] + margin for i in range(3))


def _inside_body(doc: Document, b: Bodies, name: str, com: Vec) -> bool:
    """Whether the COM lies within the geometry of the rigid body the link is welded into."""
    body = b.body_of(name)
    members = b.members(body)
    if len(members) < 2:
        return False
    placed = next(((rot, pos) for n, rot, pos in members if n == name), None)
    box = body_box(doc, body, TAGS)
    if placed is None or box is None:
        return False
    rot, pos = placed
    if rot is None or pos is None:
        return False
    moved = apply(rot, com)
    point = (moved[0] + pos[0], moved[1] + pos[1], moved[2] + pos[2])
    meshes = any(has_mesh(doc.link_map[n].element, TAGS) for n, _, _ in members)
    return _inside(point, box, meshes)


def body_box(
    doc: Document, body: str, tags: tuple[str, ...] = ("collision", "visual")
) -> tuple[Vec, Vec] | None:
    """Union box, in the body's frame, of the geometry of every link lumped into ``body``.

    Links without any visual or collision add nothing; ``None`` when one member's
    geometry cannot be read or its origin is unreadable.
    """
    b = bodies(doc)
    boxes: list[tuple[Vec, Vec]] = []
    for name, rot, pos in b.members(body):
        link = doc.link_map.get(name)
        if link is None or not any(children(link.element, tag) for tag in tags):
            continue
        box = geometry_box(doc, link.element, tags)
        if box is None or rot is None or pos is None:
            return None
        boxes.append(transform_box(box, rot, pos))
    if not boxes:
        return None
    lo = tuple(min(x[0][i] for x in boxes) for i in range(3))
    hi = tuple(max(x[1][i] for x in boxes) for i in range(3))
    return lo, hi  # type: ignore[return-value]
