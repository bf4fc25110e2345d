"""An interface name is a misspelling of a standard one (`Position`, `velocty`, ROS 1 names).

## What it does
Compares the `name` of every `<command_interface>` and `<state_interface>` of a
`<joint>` in a top-level `<ros2_control>` block with the standard names of
hardware_interface (`hardware_interface_type_values.hpp`: `position`, `velocity`,
`effort`, `acceleration`, and the newer `torque`, `force`, `current`,
`temperature` and gain names). Reports a name that differs from a standard one
only in case or by one or two letters (`Position`, `positon`, `effrot`), and ROS 1
interface class names (`hardware_interface/PositionJointInterface`). Any other
custom name is legal (hardware plugins may export what they like) and is not
reported.

## Why is this bad?
ros2_control matches interfaces by their exact name, `<joint>/<interface>`. The
standard controllers claim `joint/position`, `joint/velocity` or `joint/effort`
(joint_trajectory_controller, forward_command_controller,
diff_drive_controller), so they fail to activate when the hardware exports
`joint/Position`; joint_state_broadcaster publishes only the interfaces named
`position`, `velocity` and `effort` in `/joint_states`, so the joint's state is
missing there, and robot_state_publisher and MoveIt do not see the joint move.
The simulators' hardware (gz_ros2_control, gazebo_ros2_control) and
mock_components know only the standard names and ignore the interface.

## How to fix
Write the standard name in lower case: `position`, `velocity`, `effort` or
`acceleration`. The ROS 1 `hardware_interface/PositionJointInterface` becomes a
`<command_interface name="position"/>`.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import ros2_control as R
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.values import has_xacro

ROS1 = {
    "positionjointinterface": "position",
    "velocityjointinterface": "velocity",
    "effortjointinterface": "effort",
    "jointstateinterface": "position",
}


@rule(
    "R008",
    "misspelt-ros2-control-interface",
    Severity.WARNING,
    fix="Use the standard interface name: position, velocity, effort or acceleration.",
)
def check(doc: Document) -> Iterator[Hit]:
    for block in R.blocks(doc):
        for joint in block.joints:
            for interface in joint.interfaces:
                name = interface.name
                if not name or name in R.KNOWN or has_xacro(name):
                    continue
                meant = standard_for(name)
                if meant is None:
                    continue
                yield Hit(
                    interface.element,
                    f"{interface.kind} interface {name!r} of joint {joint.name!r} looks like a "
                    f"misspelling of {meant!r}: controllers and joint_state_broadcaster look "
                    "for the exact name",
                    attribute="name",
                    fix=f'Write name="{meant}".',
                )


def standard_for(name: str) -> str | None:
    """The standard interface ``name`` was probably meant to be, or ``None``."""
    lowered = name.strip().lower()
    tail = lowered.rsplit("/", 1)[-1]
    if tail in ROS1:
        return ROS1[tail]
    if lowered in R.KNOWN:
        return lowered
    for known in sorted(R.KNOWN):
        close = len(known) >= 5 and abs(len(known) - len(lowered)) <= 2
        if close and _distance(lowered, known) <= 2:
            return known
    return None


def _distance(a: str, b: str) -> int:
    """Optimal string alignment distance (a swap of two neighbours counts once)."""
    rows = [list(range(len(b) + 1))]
    for i in range(1, len(a) + 1):
        row = [i] + [0] * len(b)
        for j in range(1, len(b) + 1):
            cost = 0 if a[i - 1] == b[j - 1] else 1
            row[j] = min(rows[i - 1][j] + 1, row[j - 1] + 1, rows[i - 1][j - 1] + cost)
            if i > 1 and j > 1 and a[i - 1] == b[j - 2] and a[i - 2] == b[j - 1]:
                row[j] = min(row[j], rows[i - 2][j - 2] + 1)
        rows.append(row)
    return rows[-1][-1]
