"""A joint has no `type`, or a type URDF does not know.

## What it does
Reports a `<joint>` whose `type` attribute is missing or is not one of
`revolute`, `continuous`, `prismatic`, `fixed`, `floating` and `planar`
(case matters), and suggests the closest valid type.

## Why is this bad?
urdfdom refuses the model ("Joint [X] has no known type [Y]", or "joint [X]
has no type"), and with it ROS, `check_urdf`, sdformat/Gazebo and Pinocchio;
Drake, MuJoCo, PyBullet and yourdfpy also refuse it. Types from other formats
(`ball`, `spherical`, `hinge`, `slide`, `screw`, `universal`) are not URDF.

## How to fix
Use one of the six URDF joint types. A ball joint has no URDF equivalent:
chain three revolute joints through two massless links, or use SDF.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import JOINT_TYPES, closest, q

FIX = "Use one of: " + ", ".join(JOINT_TYPES) + "."


@rule("S006", "invalid-joint-type", Severity.ERROR, fix=FIX)
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        kind = joint.type
        if kind in JOINT_TYPES:
            continue
        if kind is None or not kind.strip():
            yield Hit(joint.element, f"joint {q(joint.name)} has no type")
            continue
        match = closest(kind.strip(), JOINT_TYPES)
        fix = f"Did you mean type '{match}'?" if match else None
        yield Hit(joint.element, f"joint {q(joint.name)} has unknown type {kind!r}", fix=fix)
