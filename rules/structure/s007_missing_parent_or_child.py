"""A joint lacks its `<parent>` or `<child>` element, or its `link` attribute.

## What it does
Reports a `<joint>` with no `<parent>` or no `<child>` element (on the joint),
and a `<parent>`/`<child>` element whose `link` attribute is missing or empty
(on that element).

## Why is this bad?
urdfdom refuses the model ("Failed to build tree: Joint [X] is missing a
parent and/or child link specification."), and with it ROS, `check_urdf`,
Gazebo's URDF converter and Pinocchio. PyBullet ("parent link or child link
is empty for joint"), MuJoCo ("missing element: 'child'") and Drake ("joint
'X' doesn't have a child node!") refuse it too, and yourdfpy fails with an
`AttributeError`. A joint that connects nothing also leaves its child as an
extra root link.

## How to fix
Add `<parent link="..."/>` and `<child link="..."/>` naming the two links the
joint connects.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import q


@rule(
    "S007",
    "missing-parent-or-child",
    Severity.ERROR,
    fix='Add <parent link=".."/> and <child link=".."/> to the joint.',
)
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        for role in ("parent", "child"):
            element = joint.find(role)
            if element is None:
                yield Hit(joint.element, f"joint {q(joint.name)} has no <{role}> element")
            elif not (element.get("link") or "").strip():
                yield Hit(element, f"<{role}> of joint {q(joint.name)} has no link name")
