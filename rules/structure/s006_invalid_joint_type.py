"""A joint has no `type`, or a type URDF does not know.

## What it does
Reports a `<joint>` whose `type` attribute is missing or is not one of
`revolute`, `continuous`, `prismatic`, `fixed`, `floating` and `planar`
(case matters), and suggests the closest valid type.

`spherical` is a MuJoCo extension of URDF: when MuJoCo is the only target, a
`spherical` joint is an info note (other tools still refuse the file); with
any Gazebo target it is an error like any unknown type.

## Why is this bad?
urdfdom refuses the model ("Joint [X] has no known type [Y]", or "joint [X]
has no type, check to see if it's a reference."), and with it ROS,
`check_urdf`, sdformat/Gazebo and Pinocchio. Drake ("Joint 'X' has
unrecognized type: 'Y'", "joint 'X' is missing type attribute"), MuJoCo
("invalid joint type in URDF joint definition") and PyBullet ("has unknown
type") refuse it too; PyBullet crashes with a segmentation fault when the
type is missing. yourdfpy loads the file and only its `validate()` fails.
Types from other formats (`ball`, `hinge`, `slide`, `screw`, `universal`)
are not URDF.

The exception is `spherical`: MuJoCo's URDF importer builds a ball joint
from it (`mjJNT_BALL`, 4 position coordinates) and PyBullet a
`JOINT_SPHERICAL`, while urdfdom, Drake and Gazebo refuse the model.

## How to fix
Use one of the six URDF joint types. A ball joint has no URDF equivalent:
chain three revolute joints through two massless links, or use SDF; keep
`spherical` only for a model that is loaded by MuJoCo (or PyBullet) alone.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import JOINT_TYPES, closest, q

FIX = "Use one of: " + ", ".join(JOINT_TYPES) + "."
MUJOCO_TYPES = frozenset({"spherical"})  # MuJoCo's URDF extension: a ball joint


@rule(
    "S006",
    "invalid-joint-type",
    Severity.ERROR,
    fix=FIX,
    effects={"": K.UNKNOWN_JOINT_TYPE, "mujoco-type": {}},
)
def check(doc: Document) -> Iterator[Hit]:
    mujoco_only = doc.targets == frozenset({"mujoco"})
    for joint in doc.joints:
        kind = joint.type
        if kind in JOINT_TYPES:
            continue
        if kind is None or not kind.strip():
            yield Hit(joint.element, f"joint {q(joint.name)} has no type", attribute="type")
            continue
        if mujoco_only and kind in MUJOCO_TYPES:
            yield Hit(
                joint.element,
                f"joint {q(joint.name)} has type {kind!r}, a MuJoCo extension (a ball joint) "
                "that urdfdom, ROS, Gazebo and Drake refuse",
                fix="Keep it only if the model is loaded by MuJoCo alone.",
                severity=Severity.INFO,
                attribute="type",
                variant="mujoco-type",
            )
            continue
        match = closest(kind.strip(), JOINT_TYPES)
        fix = f"Did you mean type '{match}'?" if match else None
        yield Hit(
            joint.element,
            f"joint {q(joint.name)} has unknown type {kind!r}",
            fix=fix,
            attribute="type",
        )
