"""A moving joint's effort or velocity limit is negative or zero.

## What it does
Checks `effort` and `velocity` in the `<limit>` of `revolute`, `continuous` and
`prismatic` joints:

- a negative value is an error;
- a zero value is a warning, except on a joint with `<mimic>`, which is driven
  by the joint it mimics.

## Why is this bad?
A negative limit has no meaning in URDF. Pinocchio (4.1) refuses the model
("Some components of min_effort are greater than max_effort", and the same for
velocity), and a negative velocity makes Drake abort the whole process
(`set_velocity_limits(): condition '(lower_limits.array() <=
upper_limits.array()).all()' failed`). urdfdom 6 rejects it in files with
`version="1.2"`. MuJoCo silently uses the absolute value (an effort of -1
becomes the force range -1..1). The value often comes from SDF, where `-1`
means "unlimited"; URDF has no such convention, so the intent is lost.

A zero limit loads everywhere but means different things:

- Gazebo Classic clamps every force commanded to the joint to ±0, and Gazebo
  Sim (DART) sets the joint's force limits to [0, 0]. No controller can drive
  the joint: an arm with `effort="0"` collapses under gravity.
- ros_control's `joint_limits_interface` and MoveIt read `velocity="0"` as "must
  not move", so trajectories cannot be timed.
- MuJoCo reads `effort="0"` as "no force limit".

A passive joint is the one case where a zero effort is intended. Zero limits on
`<mimic>` joints are not reported: the joint they mimic moves them.

## How to fix
Write the actuator's real peak torque or force (N·m or N) and speed (rad/s or
m/s), from the data sheet. For an unknown value, write a generous positive
estimate rather than 0 or -1. If the joint is passive on purpose, suppress J010
on it with a reason.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.values import fmt


@rule(
    "J010",
    "non-positive-effort-or-velocity",
    Severity.ERROR,
    fix="Write the actuator's real, positive effort and velocity limits.",
    effects={"negative": K.NEGATIVE_EFFORT, "zero": K.ZERO_EFFORT_OR_VELOCITY},
)
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        if joint.type not in J.ACTUATED:
            continue
        lim = J.limit(joint)
        if lim is None:
            continue
        _, effort_unit, velocity_unit = J.units(joint.type)
        values = (("effort", lim.effort, effort_unit), ("velocity", lim.velocity, velocity_unit))
        negative = [(a, v, u) for a, v, u in values if v is not None and v < 0]
        zero = [(a, v, u) for a, v, u in values if v is not None and v == 0]
        if not negative and (not zero or J.is_mimic(joint)):
            continue
        bad = negative + ([] if J.is_mimic(joint) else zero)
        listed = " and ".join(f"{a} {fmt(v + 0.0)} {u}" for a, v, u in bad)
        if negative:
            yield Hit(
                lim.element,
                f"{J.label(joint)} has {listed}; a limit cannot be negative",
                variant="negative",
            )
        else:
            why = (
                "so no controller can drive it in Gazebo"
                if any(a == "effort" for a, _, _ in bad)
                else "so ros_control and MoveIt will not move it"
            )
            yield Hit(
                lim.element,
                f"{J.label(joint)} has {listed}, {why}",
                fix="Write the real limits; suppress J010 with a reason if the joint is passive.",
                severity=Severity.WARNING,
                variant="zero",
            )
