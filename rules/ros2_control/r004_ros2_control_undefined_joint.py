"""A `<ros2_control>` joint is not a joint of the URDF, or is a fixed joint.

## What it does
Checks the `name` of every `<joint>` of a top-level `<ros2_control>` block against
the robot's `<joint>` elements, and reports a name that is not defined and a joint
whose URDF type is `fixed`. `<sensor>` and `<gpio>` names are not checked: the parser
does not look them up in the URDF (a sensor's name is the prefix of its interfaces,
often a link or a Gazebo sensor name, but nothing requires that).

## Why is this bad?
Since Jazzy, `parse_control_resources_from_urdf` (hardware_interface
`component_parser.cpp`) looks every ros2_control joint up with `urdf::Model::getJoint`
and throws "Joint 'J' not found in URDF", and for a fixed joint "Joint 'J' is of type
'fixed'. Fixed joints do not make sense in ros2_control.": the controller manager
loads no hardware at all. On Humble the parser does not check, but
gazebo_ros2_control and gz_ros2_control skip a joint that is not in the simulated
model ("Skipping joint in the URDF named 'J' which is not in the gazebo model"), so
its controllers command nothing and the joint does not move. A renamed joint, or a
xacro `prefix` passed to the robot macro but not to the ros2_control macro, is the
usual cause.

## How to fix
Use the joint's exact name (with the same prefix as the robot macro), remove the
`<joint>` of a joint that was deleted, and do not list fixed joints: a fixed joint
has nothing to command or measure (publish its frame through robot_state_publisher).
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import ros2_control as R
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import did_you_mean
from urdflint.model.values import has_xacro


@rule(
    "R004",
    "ros2-control-undefined-joint",
    Severity.ERROR,
    fix="Name an existing, movable joint of the URDF, or remove the <joint> from the block.",
)
def check(doc: Document) -> Iterator[Hit]:
    for block in R.blocks(doc):
        for joint in block.joints:
            name = joint.name
            if name is None or has_xacro(name):
                continue  # R003 reports a missing name
            urdf = doc.joint_map.get(name)
            if urdf is None:
                yield Hit(
                    joint.element,
                    f"{block.label} controls joint {name!r}, which is not a joint of the URDF "
                    '(ros2_control >= Jazzy throws "Joint not found in URDF"; Gazebo skips it)',
                    attribute="name",
                    fix=did_you_mean(name, doc.joint_map, "joint"),
                )
            elif urdf.type == "fixed":
                yield Hit(
                    joint.element,
                    f"{block.label} controls joint {name!r}, which is a fixed joint: "
                    'ros2_control >= Jazzy refuses it ("Fixed joints do not make sense in '
                    'ros2_control") and there is nothing to command',
                    attribute="name",
                    fix="Remove the fixed joint from the <ros2_control> block, or give it a "
                    "movable type.",
                )
