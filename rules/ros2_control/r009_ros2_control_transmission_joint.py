"""A `<transmission>` inside `<ros2_control>` names a joint its block does not declare.

## What it does
For every `<transmission>` of a top-level `<ros2_control>` block, checks that each
of its `<joint name>`s is also a `<joint>` of the same block, and that a
transmission of a `type="actuator"` block has exactly one `<joint>`. Robot-level
`<transmission>` elements (the ROS 1 form) are not compared with the blocks:
ros2_control does not read them, so a disagreement there has no effect.

## Why is this bad?
`auto_fill_transmission_interfaces` (hardware_interface `component_parser.cpp`)
copies each transmission joint's interfaces from the block's `<joint>` of that name
and throws "Transmission 'T' declared joint 'J' is not available in component 'H'"
when there is none; for an actuator block it throws "There should be exactly one
joint defined in this component but found N". The controller manager then loads no
hardware. This is the usual result of moving a joint to another block, or of a
xacro prefix applied to the joint but not to its transmission.

## How to fix
Declare the joint (with its interfaces) in the same `<ros2_control>` block as the
transmission, or move the transmission into the block that declares the joint.
Give an actuator block's transmission exactly one joint.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import ros2_control as R
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity
from urdflint.model.structure import did_you_mean
from urdflint.model.values import has_xacro


@rule(
    "R009",
    "ros2-control-transmission-joint",
    Severity.ERROR,
    fix="Declare the joint in the same <ros2_control> block as its transmission.",
)
def check(doc: Document) -> Iterator[Hit]:
    for block in R.blocks(doc):
        names = [j.name for j in block.joints]
        for transmission in block.transmissions:
            label = f"transmission {R.stripped(transmission)!r} of {block.label}"
            joints = children(transmission, "joint")
            for joint in joints:
                name = R.stripped(joint)
                if name is None or has_xacro(name) or name in names:
                    continue  # R003 reports a missing name
                yield Hit(
                    joint,
                    f"{label} names joint {name!r}, which is not a <joint> of the block: the "
                    'parser throws "declared joint is not available in component"',
                    attribute="name",
                    fix=did_you_mean(name, names, "joint")
                    or f"Add <joint name={name!r}> with its interfaces to the block.",
                )
            if block.type == "actuator" and len(joints) != 1:
                yield Hit(
                    transmission,
                    f"{label} has {len(joints)} <joint>s; the transmission of an actuator block "
                    'needs exactly one (the parser throws "There should be exactly one joint")',
                    fix='Give it one joint, or make the block type="system".',
                )
