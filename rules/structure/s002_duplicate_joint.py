"""Two `<joint>` elements share a name.

## What it does
Reports every `<joint>` whose `name` was already used by an earlier joint, and
names the line of the first definition.

## Why is this bad?
urdfdom refuses the whole model with "joint 'X' is not unique", and with it
ROS, `check_urdf`, Gazebo's URDF converter and Pinocchio; Drake refuses it
too ("already contains a frame named 'X_parent'") and PyBullet crashes with
a segmentation fault. MuJoCo and yourdfpy load it without a word, with two
joints of the same name, so controllers, transmissions and `<mimic>`
elements address an arbitrary one.

## How to fix
Give each joint a unique name (and update transmissions, mimic references and
controller configurations), or delete the copy.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.effects import single
from urdflint.model.finding import Severity
from urdflint.model.structure import q, written_at


@rule(
    "S002",
    "duplicate-joint",
    Severity.ERROR,
    fix="Rename or remove one of the two joints.",
    effects=single(K.DUPLICATE_JOINT),
)
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        first = doc.joint_map.get(joint.name) if joint.name is not None else None
        if first is not None and first is not joint:
            yield Hit(
                joint.element,
                f"joint {q(joint.name)} is defined again "
                f"(first defined on {written_at(doc, first.element)})",
            )
