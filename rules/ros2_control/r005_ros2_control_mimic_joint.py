"""A mimic joint in `<ros2_control>` that ros2_control (Jazzy and later) refuses.

## What it does
For every `<joint>` of a top-level `<ros2_control>` block whose URDF joint has a
`<mimic>` (and whose `mimic` attribute is not `false`), reports:

- a `<command_interface>`: a mimic joint follows its leader and cannot be commanded;
- a leader (the `<mimic joint="...">`) that is not a `<joint>` of the same block.

Also reports `mimic="true"` on a joint without `<mimic>` in the URDF, and a `mimic`
attribute that is neither `true` nor `false`.

## Why is this bad?
Since Jazzy, `parse_control_resources_from_urdf` (hardware_interface
`component_parser.cpp`) registers every URDF mimic joint listed in a block as a
`MimicJoint` of that block, unless the ros2_control joint says `mimic="false"`, and
throws:

- "Joint 'J' has mimic attribute not set to false: Activated mimic joints cannot
  have command interfaces."
- "Mimic joint 'L' not found in <ros2_control> tag" when the leader is not in the
  same block;
- "Joint 'J' has no mimic information in the URDF" for `mimic="true"` on an ordinary
  joint, and `parse_bool` throws for a value other than true/false.

Any of these stops the controller manager from loading the hardware. Humble's
parser ignores `<mimic>` (gazebo_ros2_control read a `<param name="mimic">`), so
descriptions written for Humble hit this when moved to Jazzy.

## How to fix
Give a mimic joint state interfaces only (the hardware, e.g. mock_components or
gz_ros2_control, computes it from the leader), and list its leader in the same block;
or, when the hardware really drives the joint on its own, write
`<joint name="..." mimic="false">`.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import ros2_control as R
from urdflint.model.document import Document
from urdflint.model.finding import Severity


@rule(
    "R005",
    "ros2-control-mimic-joint",
    Severity.ERROR,
    fix="Give the mimic joint state interfaces only and list its leader in the same block, "
    'or write mimic="false".',
)
def check(doc: Document) -> Iterator[Hit]:
    for block in R.blocks(doc):
        names = {j.name for j in block.joints}
        for joint in block.joints:
            urdf = doc.joint_map.get(joint.name or "")
            if urdf is None:
                continue  # R004
            raw = joint.element.get("mimic")
            flag = raw.strip().lower() if raw is not None else None
            mimic = urdf.find("mimic")
            label = f"joint {joint.name!r} of {block.label}"
            if flag is not None and flag not in ("true", "false"):
                yield Hit(
                    joint.element,
                    f"{label} has mimic={raw!r}: ros2_control reads only true or false and throws",
                    attribute="mimic",
                )
            elif mimic is None:
                if flag == "true":
                    yield Hit(
                        joint.element,
                        f'{label} has mimic="true" but no <mimic> in the URDF: ros2_control '
                        'throws "has no mimic information in the URDF"',
                        attribute="mimic",
                        fix='Remove mimic="true", or add the <mimic> to the URDF joint.',
                    )
            elif flag != "false":
                yield from _mimic(joint, label, mimic.get("joint"), names)


def _mimic(
    joint: R.Component, label: str, leader: str | None, names: set[str | None]
) -> Iterator[Hit]:
    for interface in joint.commands:
        yield Hit(
            interface.element,
            f"{label} mimics {leader!r} in the URDF but has command interface "
            f'{interface.name!r}: ros2_control >= Jazzy throws "Activated mimic joints cannot '
            'have command interfaces"',
            fix="Remove the command interfaces of the mimic joint (command its leader), or "
            'write mimic="false" on the <joint> if the hardware drives it itself.',
        )
    if leader is not None and leader.strip() not in names:
        yield Hit(
            joint.element,
            f"{label} mimics {leader!r}, which is not a <joint> of the same block: "
            f"ros2_control >= Jazzy throws \"Mimic joint '{leader}' not found in <ros2_control> "
            'tag"',
            fix=f'Add <joint name={leader!r}> to this block, or write mimic="false".',
        )
