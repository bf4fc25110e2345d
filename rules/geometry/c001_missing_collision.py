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
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import q, welded


@rule(
    "C001",
    "missing-collision",
    Severity.WARNING,
    fix="Add a <collision> with a simple shape that bounds the visual.",
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
            yield Hit(link.element, f"link {q(link.name)} has a visual but no collision")
        else:
            yield Hit(
                link.element,
                f"link {q(link.name)} has a visual but no collision "
                f"(it is welded to link {colliding!r}, which has one)",
                severity=Severity.INFO,
            )
