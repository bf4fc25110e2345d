"""A `<ros2_control>` block is not a direct child of `<robot>` (e.g. inside `<gazebo>`).

## What it does
Reports every `<ros2_control>` element that is nested somewhere below `<robot>`
instead of being one of its children: inside a `<gazebo>` extension (the usual
mistake, ros2_control#1602), a `<link>`, a `<joint>` or a `<transmission>`. A
`<ros2_control>` inside another `<ros2_control>` is R003's (the parser throws
"invalid tag name").

## Why is this bad?
hardware_interface's parser (`parse_control_resources_from_urdf` in
`component_parser.cpp`) takes only `robot->FirstChildElement("ros2_control")` and its
`NextSiblingElement("ros2_control")` siblings: a nested block is never read. When it
is the only block, the controller manager (and gazebo_ros2_control / gz_ros2_control,
which parse the same `robot_description`) fails with "no 'ros2_control' tag found in
the URDF" and no controller starts; when there are other blocks, the joints of the
nested one have no hardware, their interfaces do not exist, and controllers that
claim them fail to activate, so the robot does not move. Unlike Gazebo
`<plugin>` parameters, `<ros2_control>` is never meant to sit inside `<gazebo>`:
the Gazebo plugins read it from the URDF root.

## How to fix
Move the `<ros2_control>` block out of the enclosing element so that it is a
direct child of `<robot>` (in xacro, call the ros2_control macro at the top level
of the robot, not inside a `<gazebo>` block).
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import ros2_control as R
from urdflint.model.document import Document, local_tag
from urdflint.model.finding import Severity


@rule(
    "R001",
    "misplaced-ros2-control",
    Severity.ERROR,
    fix="Move the <ros2_control> block out so that it is a direct child of <robot>.",
)
def check(doc: Document) -> Iterator[Hit]:
    top = R.blocks(doc)
    for el in R.misplaced(doc):
        parent = el.getparent()
        if parent is None or local_tag(parent) == R.TAG:
            continue  # R003: the parser throws "invalid tag name 'ros2_control'"
        block = R.block(el)
        where = f"<{local_tag(parent)}>"
        if top:
            effect = "ros2_control never reads it, so its joints get no hardware interfaces"
        else:
            effect = (
                "ros2_control never reads it and finds no <ros2_control> at the top level "
                "(\"no 'ros2_control' tag found in the URDF\")"
            )
        yield Hit(el, f"{block.label} is inside {where}, not directly in <robot>: {effect}")
