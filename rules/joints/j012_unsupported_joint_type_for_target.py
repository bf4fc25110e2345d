"""A `planar` or `floating` joint, which Gazebo's URDF converter drops.

## What it does
Reports `planar` joints (error) and `floating` joints (warning) when the targets
include Gazebo Classic or Gazebo Sim. These are the only targets so far, so the
rule currently always applies.

## Why is this bad?
Gazebo reads URDF through sdformat's converter (`parser_urdf.cc`,
`CreateJoint`). The converter maps `floating` and `planar` to no SDF joint type
and writes no joint at all, with no message. The child link stays in the model
unattached, as a free body, and the joint's `<origin>` is not applied to it
(gazebosim/sdformat#1282, open):

- **planar**: the link was meant to move in a plane (x, y and yaw). In Gazebo
  it has all six degrees of freedom and falls or drifts out of the plane. The
  model loads, but it behaves like a different robot, so this is an error.
- **floating**: six degrees of freedom were meant, and a free body has them, so
  the motion is right. But the link starts at the parent's frame instead of the
  joint's origin, and no joint exists for plugins, controllers or joint states
  to address.

Other consumers differ: MuJoCo builds both types (three joints for planar, a
free joint for floating), Drake supports planar but leaves a floating child as
a free body with a warning, and KDL and `robot_state_publisher` treat both as
fixed.

## How to fix
For planar motion in Gazebo, replace the joint with two `prismatic` joints and
one `continuous` joint through intermediate massless links (give each a small
`<inertial>`), or drive the base with a planar-move plugin. For a floating
body, remove the joint and spawn the link as a separate model, or keep the
joint and accept that Gazebo places the child at the parent's origin.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model import targets
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.targets import gazebo_label

GAZEBO_TARGETS = frozenset({"gazebo-classic", "gz-sim"})


@rule(
    "J012",
    "unsupported-joint-type-for-target",
    Severity.ERROR,
    fix="Replace the joint with supported joints (prismatic/continuous chain) or a Gazebo plugin.",
    targets=targets.GAZEBO,
)
def check(doc: Document) -> Iterator[Hit]:
    if not doc.targets & GAZEBO_TARGETS:
        return
    gazebo = gazebo_label(doc.targets & GAZEBO_TARGETS)
    for joint in doc.joints:
        if joint.type == "planar":
            yield Hit(
                joint.element,
                f"{J.label(joint)} is dropped by {gazebo}'s URDF converter; link "
                f"'{joint.child}' becomes a free 6-DOF body instead of moving in a plane",
            )
        elif joint.type == "floating":
            yield Hit(
                joint.element,
                f"{J.label(joint)} is dropped by {gazebo}'s URDF converter; link "
                f"'{joint.child}' becomes a free body placed without the joint's <origin>",
                fix="Spawn the floating link as a model of its own, or remove the joint.",
                severity=Severity.WARNING,
            )
