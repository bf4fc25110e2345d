"""A joint has a `<safety_controller>`, which the simulators ignore.

## What it does
Reports the `<safety_controller>` of a `<joint>` (the first: a repeated one is X015's).

## Why is this bad?
`<safety_controller>` (soft limits `soft_lower_limit`/`soft_upper_limit` and the
gains `k_position`/`k_velocity`) is read by urdfdom and used by ROS only: ros_control's
`joint_limits_interface` soft-limit handles and the PR2 controllers, and MoveIt
takes the soft limits as the joint's bounds when they are present. The Gazebo
tutorial "Using a URDF in Gazebo" states that `<safety_controller>` is ignored.
sdformat's URDF converter drops it, so Gazebo Classic and Gazebo Sim enforce only
`<limit>`. MuJoCo skips it, and Drake warns "The tag 'safety_controller' ... will
be ignored". A simulated robot can therefore go past soft limits that the real
robot's controllers respect.

This finding is informational.

## How to fix
Nothing needs to change if the soft limits are for the real robot's controllers.
If the simulated joint must also stop at the soft limits, narrow `<limit
lower/upper>` to match them. Suppress J003 in the configuration when the
difference is intended.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model.document import Document
from urdflint.model.effects import single
from urdflint.model.finding import Severity


@rule(
    "J003",
    "safety-controller-ignored",
    Severity.INFO,
    fix="If simulation must respect the soft limits, narrow <limit lower/upper> to them.",
    effects=single(K.SAFETY_CONTROLLER),
)
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        el = joint.find("safety_controller")
        if el is not None:
            yield Hit(
                el,
                f"{J.label(joint)} has a <safety_controller>, which Gazebo, MuJoCo and Drake "
                "ignore; only ROS controllers and MoveIt use its soft limits",
            )
