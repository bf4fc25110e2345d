"""A joint's `<dynamics>` or `<safety_controller>` lacks the attribute urdfdom requires.

## What it does
Reports, on joints of any type:

- a `<dynamics>` with neither `damping` nor `friction`;
- a `<safety_controller>` without `k_velocity`, the one attribute of that
  element with no default.

Only the first element of each kind is checked, the one urdfdom reads. The
other incomplete joint children have their own rules: `<limit>` without
`effort` or `velocity` is J001, `<mimic>` without `joint` is S008, and
`<axis>` without `xyz` is J007. Malformed numbers are X004's.

## Why is this bad?
urdfdom refuses the joint, and with it the whole model: "joint dynamics element
specified with no damping and no friction" and "joint safety: no k_velocity",
followed by "joint xml is not initialized correctly". `check_urdf`
(urdfdom 3.0.1 and 6.0.0) ends with "ERROR: Model Parsing the xml failed", and
ROS (`robot_state_publisher`, MoveIt), kdl_parser, Pinocchio ("does not
contain a valid URDF model") and Gazebo's URDF converter all fail to load the
robot. PyBullet also rejects an empty `<dynamics>` with the same message.
Tools with their own parser load the file, so the failure appears only once
the robot reaches ROS.

## How to fix
Give `<dynamics>` at least one of its values, e.g.
`<dynamics damping="0.1" friction="0"/>`, or delete the element when the
joint has neither. Give `<safety_controller>` its velocity gain
`k_velocity` (with `k_position`, `soft_lower_limit` and `soft_upper_limit` as
needed), or delete it: only ROS controllers use it.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model.document import Document
from urdflint.model.finding import Severity


@rule("J013", "incomplete-joint-element", Severity.ERROR)
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        dynamics = joint.find("dynamics")
        if dynamics is not None and all(dynamics.get(a) is None for a in ("damping", "friction")):
            yield Hit(
                dynamics,
                f"<dynamics> of {J.label(joint)} has neither damping nor friction; "
                "urdfdom refuses the model",
                fix='Write <dynamics damping=".." friction=".."/> or remove the element.',
            )
        safety = joint.find("safety_controller")
        if safety is not None and safety.get("k_velocity") is None:
            yield Hit(
                safety,
                f"<safety_controller> of {J.label(joint)} has no k_velocity; "
                "urdfdom refuses the model",
                fix='Add k_velocity="..", or remove the <safety_controller>.',
            )
