"""A `<mimic>` that a selected target does not enforce: the follower moves on its own there.

## What it does
Reports each valid `<mimic>` (a revolute, continuous or prismatic joint following another
one; J014 and S008 report the invalid ones) with what each selected target does with it.
Its severity is the worst consequence on the selected targets: a **warning** where a
simulator drops the relation (Gazebo Classic and Gazebo Sim when the file has `<gazebo>`
blocks, info in a file without any, like G002; PyBullet), info where the
consumer only needs to be told (Pinocchio builds the follower as a joint of its own unless
asked for mimic support), and nothing to report when every target enforces it (MuJoCo,
Drake, Isaac Sim, ROS).

A Gazebo mimic plugin that names the follower (`<mimicJoint>` of roboticsgroup's
`mimic_joint_plugin` and its forks), a `gazebo_ros2_control` / `gz_ros2_control` plugin
with the follower in a `<ros2_control>` block, or a `<transmission>` that drives the
follower (its own ros_control controller, or a `<passive_joint>` of PR2's gripper
transmission) counts as enforcing it in Gazebo.

## Why is this bad?
The follower of a gripper's mimic, a parallel linkage or a differential is a joint of its
own wherever the relation is dropped: it hangs under gravity or is pushed around by
contacts while the leader moves (moveit/moveit2 and Genesis#129, SAPIEN#68,
google-deepmind/mujoco#3527 and RobotLocomotion/drake#16181 collect such reports).
Observed on a two-finger gripper:
- sdformat 12.3 (Gazebo Classic and Gazebo Sim Fortress) converts the joint without its
  `<mimic>`: no SDF element carries it (Gazebo Classic needs a mimic plugin);
- PyBullet 3.2.7 loads two independent joints and no constraint (`getNumConstraints()` is
  0; a `JOINT_GEAR` constraint must be added by hand);
- Pinocchio 4.1 `buildModelFromUrdf` gives the follower its own coordinate (nq 2); with
  `mimic=True` it is a mimic joint (nq 1);
- MuJoCo 4.0 adds a joint equality constraint (`eq_type` joint, polycoef offset,
  multiplier), Drake 1.51 a coupler constraint; Isaac Sim 5.1's importer a PhysX mimic
  joint (`PhysxMimicJointAPI`, `parseMimic` on by default); robot_state_publisher and
  MoveIt's RobotModel apply it (KDL alone does not).

## How to fix
For Gazebo Classic, add a mimic plugin for the follower (e.g. roboticsgroup_upatras's
`libroboticsgroup_upatras_gazebo_mimic_joint_plugin.so` with `<joint>` and
`<mimicJoint>`), or drive the joints through `gazebo_ros2_control`, which enforces the
URDF's mimic joints. In PyBullet add a gear constraint
(`createConstraint(..., JOINT_GEAR, ...)` with `gearRatio = -multiplier`); in Pinocchio
build the model with `mimic=True`. Leave the `<mimic>` as it is: it is correct, the
finding tells you where it is not applied.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.effects import Consequence, Effect, ignored, kept
from urdflint.model.finding import Severity
from urdflint.model.structure import q
from urdflint.model.targets import LABELS, ordered

SINGLE = frozenset({"revolute", "continuous", "prismatic"})
ROS2_CONTROL_PLUGINS = ("gazebo_ros2_control", "gz_ros2_control", "ign_ros2_control")
FOLLOWER_TAGS = ("mimicJoint", "mimic_joint")

DROPPED_BY_SDFORMAT = "sdformat 12.3 converts the joint without its <mimic>"
MIMIC: dict[str, Effect] = {
    "gazebo-classic": ignored(DROPPED_BY_SDFORMAT + "; add a mimic plugin", Severity.WARNING),
    "gz-sim": ignored(DROPPED_BY_SDFORMAT + " (Fortress)", Severity.WARNING),
    "mujoco": kept("a joint equality constraint (multiplier and offset)", Severity.INFO),
    "drake": kept("a coupler constraint", Severity.INFO),
    "pybullet": ignored(
        "two independent joints, no constraint: add a JOINT_GEAR constraint", Severity.WARNING
    ),
    "isaac": kept("a PhysX mimic joint (parseMimic is on by default)", Severity.INFO),
    "pinocchio": ignored(
        "the follower is a joint of its own unless built with mimic=True", Severity.INFO
    ),
    "ros": kept("robot_state_publisher and MoveIt apply it", Severity.INFO),
}
# A file without any <gazebo> block is most likely not (yet) meant for Gazebo: info there.
NO_GAZEBO_BLOCKS: dict[str, Effect] = {
    **MIMIC,
    "gazebo-classic": ignored(DROPPED_BY_SDFORMAT + "; add a mimic plugin", Severity.INFO),
    "gz-sim": ignored(DROPPED_BY_SDFORMAT + " (Fortress)", Severity.INFO),
}
BY_PLUGIN = kept("a Gazebo plugin or transmission drives the follower", Severity.INFO)


@rule(
    "J017",
    "mimic-not-enforced",
    Severity.WARNING,
    fix="Keep the <mimic>; enforce it where it is dropped (a Gazebo mimic plugin or "
    "gazebo_ros2_control, a PyBullet gear constraint, Pinocchio's mimic=True).",
    effects={"": MIMIC},
    by_target=True,
)
def check(doc: Document) -> Iterator[Hit]:
    enforced = _gazebo_enforced(doc)
    for joint in doc.joints:
        mimic = joint.find("mimic")
        if mimic is None or joint.type not in SINGLE:
            continue
        leader = doc.joint_map.get((mimic.get("joint") or "").strip())
        if leader is None or leader is joint or leader.type not in SINGLE:
            continue  # S008, J014
        effects: Mapping[str, Effect] = MIMIC if doc.gazebo else NO_GAZEBO_BLOCKS
        if joint.name in enforced:
            effects = {**MIMIC, "gazebo-classic": BY_PLUGIN, "gz-sim": BY_PLUGIN}
        names = [
            LABELS[t]
            for t in ordered(doc.targets)
            if t in effects and effects[t].consequence is not Consequence.AS_WRITTEN
        ]
        if not names:
            continue
        where = names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]
        yield Hit(
            mimic,
            f"joint {q(joint.name)} mimics {q(leader.name)}, but {where} "
            f"{'does' if len(names) == 1 else 'do'} not enforce the mimic: "
            "the follower moves on its own there",
            effects=effects,
        )


def _gazebo_enforced(doc: Document) -> set[str]:
    """Followers Gazebo drives anyway: named by a mimic plugin, in a <ros2_control> block of a
    model that loads gazebo_ros2_control, or by a <transmission> (its own ros_control
    controller, or a passive joint of PR2's gripper transmission)."""
    found: set[str] = set()
    ros2_control = False
    for block in doc.gazebo:
        for plugin in block.iter("plugin"):
            filename = (plugin.get("filename") or "") + " " + (plugin.get("name") or "")
            ros2_control |= any(name in filename for name in ROS2_CONTROL_PLUGINS)
            for tag in FOLLOWER_TAGS:
                for el in plugin.iter(tag):
                    found.add((el.text or "").strip())
    if ros2_control:
        for block in doc.robot.iter("ros2_control"):
            found.update((j.get("name") or "").strip() for j in block.findall("joint"))
    for transmission in doc.transmissions:  # driven by ros_control (PR2's passive joints)
        for tag in ("joint", "passive_joint"):
            found.update((j.get("name") or "").strip() for j in transmission.iter(tag))
    return found
