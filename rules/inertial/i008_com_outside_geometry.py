"""The centre of mass lies outside the link's collision geometry.

## What it does
When every `<collision>` and `<visual>` of a link is a box, cylinder, sphere
or capsule, builds their bounding box in the link frame (origins and rotations
applied) and reports an `<inertial><origin xyz>` outside it by more than a
margin of 10% of the box's largest side (at least 1 mm). Links with any mesh
are skipped: their primitives are often partial collision proxies (a sphere
for the elbow, a box for the motor) that say little about where the mass is.
Sensor frames negligible next to the body they are fixed to are skipped too.

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
`<inertial><origin>` against the `<collision><origin>`.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.document import Document
from urdflint.finding import Severity
from urdflint.inertia import bodies, primitive_box
from urdflint.registry import Hit, rule
from urdflint.values import fmt

MARGIN = 0.1
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
        box = primitive_box(doc.link_map[name].element, ("collision", "visual"))
        if box is None or b.negligible(name):
            continue
        lo, hi = box
        margin = max(MARGIN * max(hi[i] - lo[i] for i in range(3)), MIN_MARGIN)
        com = inertial.xyz
        if all(lo[i] - margin <= com[i] <= hi[i] + margin for i in range(3)):
            continue
        spans = ", ".join(f"{axis} {fmt(lo[i])}…{fmt(hi[i])}" for i, axis in enumerate("xyz"))
        yield Hit(
            inertial.origin if inertial.origin is not None else inertial.element,
            f"link '{name}' has its centre of mass at ({', '.join(fmt(v) for v in com)}) m, "
            f"outside its geometry ({spans} m)",
        )
