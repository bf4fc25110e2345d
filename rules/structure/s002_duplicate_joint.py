"""Two `<joint>` elements share a name.

## What it does
Reports every `<joint>` whose `name` was already used by an earlier joint, and
names the line of the first definition.

## Why is this bad?
urdfdom (and with it ROS, `check_urdf`, sdformat/Gazebo and Pinocchio) refuses
the whole model with "joint 'X' is not unique"; yourdfpy reports
"Duplicate joint X found". Parsers that accept it keep only one of the two, so
controllers, transmissions and `<mimic>` elements address an arbitrary one.

## How to fix
Give each joint a unique name (and update transmissions, mimic references and
controller configurations), or delete the copy.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import q


@rule("S002", "duplicate-joint", Severity.ERROR, fix="Rename or remove one of the two joints.")
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        first = doc.joint_map.get(joint.name) if joint.name is not None else None
        if first is not None and first is not joint:
            yield Hit(
                joint.element,
                f"joint {q(joint.name)} is defined again "
                f"(first defined on line {first.element.sourceline})",
            )
