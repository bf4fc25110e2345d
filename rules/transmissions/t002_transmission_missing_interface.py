"""A ros_control transmission has a joint without `<hardwareInterface>`, or no `<actuator>`.

## What it does
For transmissions in the ros_control form (those with a `<type>` child such
as `transmission_interface/SimpleTransmission`), reports each `<joint>` that
has no non-empty `<hardwareInterface>`, and a transmission with no
`<actuator>`. Legacy pr2_mechanism_model transmissions, which carry their
type in a `type` attribute and never had hardware interfaces, are not
checked. A `<hardwareInterface>` given only inside the `<actuator>` (the ROS
Hydro layout) is reported as info.

## Why is this bad?
`gazebo_ros_control` skips the joint ("does not specify any hardware
interface. Not adding it to the robot hardware simulation"), so its
controllers fail to start and the joint stays limp in simulation;
urdf_parser_py reports "no hardwareInterface defined" and "no actuator
defined". The Hydro layout still loads, with a deprecation warning asking to
move the interface into `<joint>`.

## How to fix
Add the interface the joint's controllers command, e.g.
`<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>`
inside `<joint>`, and an `<actuator name="..._motor">` with its
`<mechanicalReduction>`.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity
from urdflint.model.structure import q

HW = "hardwareInterface"


def _interfaces(element: etree._Element) -> list[str]:
    return [t for t in ((h.text or "").strip() for h in children(element, HW)) if t]


@rule("T002", "transmission-missing-interface", Severity.WARNING)
def check(doc: Document) -> Iterator[Hit]:
    for transmission in doc.transmissions:
        if transmission.find("type") is None:
            continue  # legacy pr2_mechanism_model transmission
        label = transmission.get("name")
        actuators = children(transmission, "actuator")
        if not actuators:
            yield Hit(
                transmission,
                f"transmission {q(label)} has no <actuator>",
                fix='Add <actuator name=".."> with a <mechanicalReduction>.',
            )
        on_actuator = [i for a in actuators for i in _interfaces(a)]
        for joint in children(transmission, "joint"):
            if _interfaces(joint):
                continue
            name = joint.get("name")
            if on_actuator:
                yield Hit(
                    joint,
                    f"joint {q(name)} of transmission {q(label)} has its hardwareInterface "
                    "only on the actuator",
                    fix=f"Move <hardwareInterface>{on_actuator[0]}</hardwareInterface> "
                    "into <joint>.",
                    severity=Severity.INFO,
                )
            else:
                yield Hit(
                    joint,
                    f"joint {q(name)} of transmission {q(label)} has no <hardwareInterface>",
                    fix="Add e.g. <hardwareInterface>hardware_interface/EffortJointInterface"
                    "</hardwareInterface> inside <joint>.",
                )
