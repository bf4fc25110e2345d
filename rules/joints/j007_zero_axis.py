"""A moving joint's axis is the zero vector.

## What it does
Reports `<axis xyz="0 0 0">`, and an `<axis>` without `xyz` (urdfdom then keeps a
zero vector), on `revolute`, `continuous`, `prismatic` and `planar` joints, the
types whose axis is used. A joint without any `<axis>` is not reported: its axis
defaults to `1 0 0`.

## Why is this bad?
A zero axis defines no direction of motion. urdfdom and `check_urdf` accept it
silently, but the consumers fail:

- Gazebo: sdformat rejects the model with "The norm of the xyz vector cannot be
  zero".
- Drake: "Joint 'J' axis is zero. Don't do that."
- MuJoCo: "axis too small in joint".
- Pinocchio loads it silently, and the joint never moves.

Zero axes on fixed joints are harmless and are left to J006.

## How to fix
Set the direction of motion in the joint frame, e.g. `<axis xyz="0 0 1"/>`. If
the joint is not meant to move, make it `fixed`.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model.document import Document
from urdflint.model.effects import single
from urdflint.model.finding import Severity


@rule(
    "J007",
    "zero-axis",
    Severity.ERROR,
    fix='Give the direction of motion, e.g. <axis xyz="0 0 1"/>, or make the joint fixed.',
    effects=single(K.ZERO_AXIS),
)
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        if joint.type not in J.AXIS_USED:
            continue
        el = joint.find("axis")
        vec = J.axis(joint)
        if el is None or vec is None or J.norm(vec) > J.ZERO_NORM:
            continue
        if el.get("xyz") is None:
            message = f"{J.label(joint)} has an <axis> without xyz, which urdfdom reads as 0 0 0"
        else:
            message = f"{J.label(joint)} has the zero axis {J.fmt_vector(vec)}"
        yield Hit(el, message, attribute="xyz")
