"""What each target does with a joint's effort limit (the effects of D001 and D002).

Observed here, with a 1 kg pendulum 0.5 m from its axis (4.905 N·m to hold it level) and
``effort="1"``: Drake 1.51.1 clamps the net actuation to -1 and the arm falls (a
``<transmission>`` makes the actuator; without one Drake makes none); MuJoCo 4.0.0 makes no
actuator, but sets the joint's ``actuatorfrcrange`` to [-1, 1], and a motor added to the
joint (``MjSpec``) falls the same way; PyBullet 3.2.7 reports 1 as ``jointMaxForce`` in
``getJointInfo`` and holds the arm with ``POSITION_CONTROL`` or ``TORQUE_CONTROL``: the
force passed to ``setJointMotorControl2`` is not clamped.

From source: Gazebo Classic's ``Joint::CheckAndTruncateForce`` (``gazebo/physics/Joint.cc``)
clamps every ``SetForce`` to ``±effortLimit``; Gazebo Sim's DART plugin
(``gz-physics`` ``dartsim/src/SDFFeatures.cc``) makes the SDF ``<effort>``, which sdformat's
URDF converter writes from the ``<limit>``, the joint's force limits; Isaac Sim's URDF
importer sets each joint drive's ``maxForce`` to the effort (``UrdfImporter.cpp``).
"""

from __future__ import annotations

from urdflint.model.effects import Effect, ignored, kept
from urdflint.model.finding import Severity

INFO = Severity.INFO
WARNING = Severity.WARNING
SAGS = "the joint cannot hold what it carries and sags"

CANNOT_HOLD: dict[str, Effect] = {
    "gazebo-classic": kept(
        f"Joint::CheckAndTruncateForce clamps every force commanded to ±effort: {SAGS}",
        WARNING,
    ),
    "gz-sim": kept(f"the effort becomes the joint's force limits in DART: {SAGS}", WARNING),
    "drake": kept(
        "with a <transmission>, MultibodyPlant clamps the actuation to the effort "
        "(Drake 1.51.1: the arm falls)",
        WARNING,
    ),
    "mujoco": kept(
        "the import adds no actuator, but the effort becomes the joint's actuatorfrcrange, "
        "which clamps any actuator added to it (MuJoCo 4.0.0: the arm falls)",
        WARNING,
    ),
    "pybullet": ignored(
        "getJointInfo reports it as jointMaxForce; a motor uses the force passed to "
        "setJointMotorControl2, unclamped",
        INFO,
    ),
    "isaac": kept(f"the importer sets the joint drive's maxForce to the effort: {SAGS}", WARNING),
    "pinocchio": ignored("model.effortLimit holds it; nothing enforces it", INFO),
    "ros": kept(
        "ros_control's effort saturation (joint_limits) clamps commands to it; the real "
        "robot's hardware (a counterbalance spring, a brake) may hold what the URDF cannot "
        "say; KDL and MoveIt ignore it",
        INFO,
    ),
}

GAZEBO_WEIGHTLESS = ignored(
    "the <gazebo> blocks turn gravity off for every link it carries: Gazebo sees no load",
    INFO,
)

NEVER_CLAMPS = "a limit this large never acts: nothing protects the joint or its controller"

PLACEHOLDER: dict[str, Effect] = {
    "gazebo-classic": kept(f"clamps forces to ±effort; {NEVER_CLAMPS}", INFO),
    "gz-sim": kept(f"the effort becomes DART's force limits; {NEVER_CLAMPS}", INFO),
    "drake": kept(f"the actuator's effort limit (with a <transmission>); {NEVER_CLAMPS}", INFO),
    "mujoco": kept(f"the joint's actuatorfrcrange; {NEVER_CLAMPS}", INFO),
    "isaac": kept(f"the joint drive's maxForce; {NEVER_CLAMPS}", INFO),
    "ros": kept("controllers and limiters take it as what the actuator can do", INFO),
}
