"""A joint's `<dynamics friction>` is applied by some consumers and ignored by others.

## What it does
Reports a non-zero `friction` in the `<dynamics>` of a `revolute`, `continuous`
or `prismatic` joint when the targets include `gazebo-classic`. With only the
`gz-sim` target it reports nothing.

## Why is this bad?
Joint friction (Coulomb friction, N·m or N) is one of the values where the
consumers of a URDF disagree:

- Gazebo Classic 4 and earlier use only `damping`; the tutorial "Using a URDF in
  Gazebo" notes that friction is used only from Gazebo 5 on.
- Gazebo Sim applies it. sdformat's converter writes both `damping` and
  `friction` into the SDF `<axis><dynamics>`, and gz-physics' DART plugin sets
  them as the joint's Coulomb friction.
- Drake ignores it with a warning ("MultibodyPlant does not currently support
  non-zero joint friction").
- MuJoCo turns it into the joint's `frictionloss`.

A joint tuned to hold its position by friction in one simulator can drift in
another. This finding is informational: the value is valid, but the behaviour
depends on the consumer.

## How to fix
Nothing needs to change when the Gazebo version and physics engine you use apply
joint friction. If you also target an older Gazebo or Drake, do not rely on
friction alone to hold a joint: add `damping`, or a controller. Suppress J004 in
the configuration, or select only the `gz-sim` target.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.values import fmt, number


@rule(
    "J004",
    "dynamics-friction-ignored",
    Severity.INFO,
    fix="Do not rely on joint friction alone to hold a joint; add damping or a controller.",
    targets=("gazebo-classic",),
)
def check(doc: Document) -> Iterator[Hit]:
    if "gazebo-classic" not in doc.targets:
        return
    for joint in doc.joints:
        if joint.type not in J.ACTUATED:
            continue
        dynamics = joint.find("dynamics")
        friction = number(dynamics, "friction")
        if friction is None or friction == 0:
            continue
        unit = J.units(joint.type)[1]
        yield Hit(
            dynamics,
            f"{J.label(joint)} has dynamics friction {fmt(friction)} {unit}, which Gazebo Classic "
            "before version 5 and Drake ignore",
        )
