"""`tool0`'s z axis does not point out of the flange.

## What it does
Runs with `profile = "industrial"` (and never without a profile). When a `tool0` and a
`flange` of the same prefix are joined by fixed joints, reports `tool0`'s parent joint
if `tool0`'s z axis is not `flange`'s x+ axis.

## Why is this bad?
The REP 199 draft orients `flange` as REP 103 requires, with x+ "pointing away from the
last link" (section "flange"), and makes `tool0` the controller's all-zeros tool
centre point, whose only expected difference from `flange` is the orientation
(section "tool0"). The controllers of the ROS-Industrial support packages (ABB,
Fanuc, KUKA, Universal Robots, Yaskawa Motoman) point the approach axis z+ of that TCP
out of the flange, as the mechanical interface frame of ISO 9787 does, and the
support packages join the two frames accordingly: `rpy="0 pi/2 0"` (KUKA),
`rpy="pi -pi/2 0"` (Fanuc), `rpy="pi/2 0 pi/2"` (Universal Robots). A `tool0` whose z
axis points elsewhere gives tool poses that do not match the teach pendant, and
end effectors attached to it point the wrong way. Often the culprit is `flange`
itself, left in the last link's orientation instead of x+ out of the flange.

The finding is informational: REP 199 is a draft.

## How to fix
Orient `flange` x+ out of the flange, and `tool0` with z+ along that axis
(`<origin rpy="0 ${pi/2} 0"/>` from `flange` for most arms).
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from urdflint.rules.conventions.common import INDUSTRIAL, active

from urdflint.engine.registry import Hit, rule
from urdflint.model import conventions as N
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import q


@rule(
    "N007",
    "tool0-orientation",
    Severity.INFO,
    fix='Point tool0 z+ along flange x+ (rpy="0 pi/2 0" from flange for most arms).',
)
def check(doc: Document) -> Iterator[Hit]:
    if active(doc, INDUSTRIAL) is None:
        return
    for prefix in N.prefixes(doc, "tool0"):
        flange, tool0 = prefix + "flange", prefix + "tool0"
        joint = doc.graph.parent_joint(tool0)
        pose = N.relative(doc, flange, tool0) if flange in doc.link_map else None
        if pose is None or joint is None:
            continue
        z = N.column(pose[0], 2)
        if z[0] >= math.cos(N.ANGLE_TOL):
            continue
        yield Hit(
            joint.element,
            f"REP 199 (draft, flange/tool0) points {q(tool0)}'s z+ out of the flange, along "
            f"{q(flange)}'s x+; here it points along {q(flange)}'s {N.fmt_axis(z)}",
        )
