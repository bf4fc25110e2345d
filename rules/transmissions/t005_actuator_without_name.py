"""A transmission's `<actuator>` has no name.

## What it does
Reports an `<actuator>` (and WristTransmission's `<leftActuator>` and
`<rightActuator>`) of a robot-level `<transmission>` whose `name` attribute is
missing or empty, and likewise an `<actuator>` of a `<transmission>` inside a
`<ros2_control>` block.

## Why is this bad?
The actuator name is how the hardware interface finds the motor. ros_control's
`TransmissionParser` (used by gazebo_ros_control and ROS 1 robot drivers) drops
the whole transmission: "No name attribute specified for actuator." then
"Failed to load actuators for transmission", or, for `name=""`, "Empty name
attribute specified for actuator." (the actuator is skipped, and a transmission
left without actuators is dropped). pr2_mechanism_model refuses it ("could not
find actuator named"), and ros2_control's component parser throws "no attribute
'name' in 'actuator' tag", so the controller manager loads no hardware at all.
Drake refuses the model ("Transmission is missing an actuator name."). urdfdom
ignores transmissions, so `check_urdf` says nothing.

## How to fix
Name the motor: `<actuator name="shoulder_motor">`. The name must match the
actuator your hardware interface exposes; for gazebo_ros_control any unique
name works.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity
from urdflint.model.structure import ACTUATOR_TAGS, q


@rule(
    "T005",
    "actuator-without-name",
    Severity.ERROR,
    fix='Add name="..." to the actuator (the motor the hardware interface drives).',
)
def check(doc: Document) -> Iterator[Hit]:
    for transmission in doc.transmissions:
        label = f"transmission {q(transmission.get('name'))}"
        for el in children(transmission):
            if el.tag in ACTUATOR_TAGS and not (el.get("name") or "").strip():
                state = "an empty name" if el.get("name") is not None else "no name"
                yield Hit(el, f"<{el.tag}> of {label} has {state}")
    for block in children(doc.robot, "ros2_control"):
        for transmission in children(block, "transmission"):
            label = f"ros2_control transmission {q(transmission.get('name'))}"
            for el in children(transmission, "actuator"):
                if not (el.get("name") or "").strip():
                    state = "an empty name" if el.get("name") is not None else "no name"
                    yield Hit(el, f"<actuator> of {label} has {state}")
