"""A `<transmission>` drives a joint that does not exist, or names no joint at all.

## What it does
Checks every joint reference in a `<transmission>`: the `name` of `<joint>`
(ros_control), and of the legacy pr2_mechanism_model elements `<flexJoint>`,
`<rollJoint>` (WristTransmission), `<gap_joint>`, `<passive_joint>`
(PR2GripperTransmission) and `<simulated_actuated_joint>` (its `name` and
`passive_actuated_joint`). Reports the element whose joint is not defined or
whose name is missing, and a transmission with none of these elements.
`<actuator>`, `<leftActuator>` and `<rightActuator>` name motors, not joints,
and are not checked.

## Why is this bad?
`gazebo_ros_control` looks the joint up in the simulated model, fails
("This robot has a joint named X which is not in the gazebo model") and does
not start, so no controller runs; ros_control's transmission loader cannot
bind the transmission on the real robot either. Drake refuses the
model ("Transmission specifies joint 'J' which does not exist");
urdf_parser_py reports "no joint defined". urdfdom ignores transmissions, so
`check_urdf` says nothing. A renamed joint whose transmission was not
updated is the usual cause.

## How to fix
Correct the joint name (transmission names often lag behind a renamed joint
or a changed xacro `prefix`), or delete the transmission of a removed joint.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import did_you_mean, q, transmission_joint_refs


@rule(
    "T001",
    "transmission-undefined-joint",
    Severity.ERROR,
    fix="Name an existing joint, or remove the transmission.",
)
def check(doc: Document) -> Iterator[Hit]:
    for transmission in doc.transmissions:
        label = transmission.get("name")
        refs = list(transmission_joint_refs(transmission))
        if not refs:
            yield Hit(transmission, f"transmission {q(label)} names no joint")
        for element, attr, value in refs:
            name = (value or "").strip()
            tag = element.tag
            if not name:
                yield Hit(element, f"<{tag}> of transmission {q(label)} has no {attr} attribute")
            elif name not in doc.joint_map:
                yield Hit(
                    element,
                    f"transmission {q(label)} refers to joint {name!r}, which is not defined",
                    fix=did_you_mean(name, doc.joint_map, "joint"),
                )
