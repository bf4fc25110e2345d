"""The robot declares transmissions or Gazebo ros2_control hardware but loads no control plugin.

## What it does
Flags a robot with `<transmission>` elements, or with a `<ros2_control>` block whose
hardware plugin is a Gazebo one (`gazebo_ros2_control/GazeboSystem`,
`gz_ros2_control/GazeboSimSystem`, `ign_ros2_control/IgnitionSystem`), when no
`<gazebo>` block loads a control plugin: `libgazebo_ros_control.so` (ROS 1),
`libgazebo_ros2_control.so` (ROS 2, Gazebo Classic), `gz_ros2_control-system` /
`libgz_ros2_control-system.so` / `libign_ros2_control-system.so` (Gazebo Sim), or a
derivative (`lib<robot>_gazebo_ros_control.so`, PR2's `libgazebo_ros_controller_manager.so`).

Severity: a warning when the file has `<gazebo>` blocks or Gazebo ros2_control hardware
(it is meant for Gazebo). Info when it has no `<gazebo>` element at all (description
packages for real hardware often keep their Gazebo extensions in a separate file), and
info when another model plugin that may actuate the joints itself is loaded (a
robot-specific controller plugin such as Atlas's `libAtlasV4Plugin.so`, or
`diff_drive`): the transmissions are then unused, but the robot may work as intended.

## Why is this bad?
Transmissions and `<ros2_control>` tags are only read by a controller manager. In
Gazebo that manager is started by the control plugin; without it the robot spawns,
`/joint_states` is never published, controllers fail to load ("Controller Spawner
couldn't find the expected controller_manager ROS interface") and the joints hang
limp under gravity.

## How to fix
Add the plugin for your stack in a `<gazebo>` block without `reference`, e.g.
`<plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"/>` (ROS 1) or
`<plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin">`
with its `<parameters>` (ROS 2 with Gazebo Sim).
"""

from __future__ import annotations

import re
from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model import targets
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity

CONTROL_PLUGIN = re.compile(
    r"gazebo_ros2?_control|gz_ros2_control|ign_ros2_control|ros_controller_manager", re.I
)
# Model plugins known not to actuate joints; any other model plugin may drive them itself.
PASSIVE_PLUGIN = re.compile(
    r"gazebo_ros_(p3d|f3d|imu|imu_sensor|force|ft_sensor|harness|joint_state_publisher|"
    r"bumper|hand_of_god|template)|LinkPlot3D|world_odometry|mimic_joint",
    re.I,
)
GAZEBO_HARDWARE = re.compile(r"^\s*(gazebo_ros2_control|gz_ros2_control|ign_ros2_control)/", re.I)


@rule(
    "G009",
    "missing-ros-control-plugin",
    Severity.WARNING,
    fix="Add the gazebo_ros_control (ROS 1) or gz_ros2_control (ROS 2) plugin in a <gazebo> block.",
    targets=targets.GAZEBO,
)
def check(doc: Document) -> Iterator[Hit]:
    hardware = _gazebo_hardware(doc.robot)
    if not doc.transmissions and hardware is None:
        return
    plugins = [p.get("filename") or "" for g in doc.gazebo for p in g.iter("plugin")]
    if any(CONTROL_PLUGIN.search(name) for name in plugins):
        return
    if hardware is not None:
        name = (hardware.text or "").strip()
        yield Hit(
            hardware,
            f"<ros2_control> uses the Gazebo hardware {name!r}, but no <gazebo> block loads "
            "the matching ros2_control plugin",
        )
        return
    count = len(doc.transmissions)
    plural = "s" if count != 1 else ""
    model_plugins = [
        p.get("filename") or ""
        for g in doc.gazebo
        if not g.get("reference")
        for p in children(g, "plugin")
    ]
    others = [name for name in model_plugins if name and not PASSIVE_PLUGIN.search(name)]
    if others:
        yield Hit(
            doc.transmissions[0],
            f"robot has {count} <transmission> element{plural} but no ros_control plugin; "
            f"its model plugin {others[0]!r} may drive the joints instead",
            severity=Severity.INFO,
        )
    elif doc.gazebo:
        yield Hit(
            doc.transmissions[0],
            f"robot has {count} <transmission> element{plural} and <gazebo> blocks but no "
            "gazebo_ros_control or gz_ros2_control plugin, so Gazebo starts no controllers",
        )
    else:
        yield Hit(
            doc.transmissions[0],
            f"robot has {count} <transmission> element{plural} but no Gazebo control plugin "
            "(fine if its Gazebo extensions live in another file)",
            severity=Severity.INFO,
        )


def _gazebo_hardware(robot: etree._Element) -> etree._Element | None:
    for block in children(robot, "ros2_control"):
        for hardware in children(block, "hardware"):
            for plugin in children(hardware, "plugin"):
                if GAZEBO_HARDWARE.match(plugin.text or ""):
                    return plugin
    return None
