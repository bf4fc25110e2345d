"""`base_footprint` is not where REP 120 puts it: level, on the floor below `base_link`.

## What it does
Runs with `profile = "mobile"` or `"humanoid"` (and never without a profile), for each
`base_footprint` link (prefixes allowed) with a `base_link` of the same prefix.

- mobile: reports the joint that attaches `base_footprint` when the two frames are
  joined through a moving joint, when `base_footprint` is rotated with respect to
  `base_link`, or when it lies above `base_link`;
- humanoid: reports a `base_footprint` welded to `base_link` by fixed joints.

## Why is this bad?
REP 120 (section "base_footprint") defines `base_footprint` as the robot's position
on the floor: zero roll and pitch, and the yaw of `base_link`. On a mobile base, which
stands level on its wheels, that is a frame below `base_link` with the same
orientation, rigidly attached: REP 120 (section "Frame Authorities") notes that the
transform is rigid on most mobile bases. Planners and costmaps that project the robot
on the ground through `base_footprint` see it tilted or floating otherwise.

On a humanoid the same section says the transform is *not* rigid and is broadcast by
an external node (the walking controller's estimate of the feet). A fixed
`base_footprint` in the URDF is published by robot_state_publisher as well and
conflicts with that node.

## How to fix
Mobile: attach `base_footprint` with a fixed joint whose origin is
`xyz="0 0 -h" rpy="0 0 0"` from `base_link` (or `xyz="0 0 h"` with `base_footprint` as
parent), `h` being the height of `base_link` above the floor. Humanoid: remove
`base_footprint` from the URDF and publish it from the walking or state-estimation
node.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.conventions.common import HUMANOID, MOBILE, active

from urdflint.engine.registry import Hit, rule
from urdflint.model import conventions as N
from urdflint.model.document import Document, Joint
from urdflint.model.finding import Severity
from urdflint.model.inertia import IDENTITY
from urdflint.model.structure import q
from urdflint.model.values import fmt


@rule(
    "N003",
    "base-footprint-frame",
    Severity.INFO,
    fix="Attach base_footprint to base_link with a fixed joint, level and below it (mobile), "
    "or leave it to the walking controller (humanoid).",
)
def check(doc: Document) -> Iterator[Hit]:
    profile = active(doc, MOBILE, HUMANOID)
    if profile is None:
        return
    for prefix in N.prefixes(doc, "base_footprint"):
        footprint, base = prefix + "base_footprint", prefix + "base_link"
        if base not in doc.link_map or footprint not in doc.link_map:
            continue
        joint = _between(doc, base, footprint)
        anchor = joint.element if joint is not None else doc.link_map[footprint].element
        judge = _humanoid if profile == HUMANOID else _mobile
        problem = judge(doc, base, footprint)
        if problem is not None:
            yield Hit(anchor, problem)


def _between(doc: Document, base: str, footprint: str) -> Joint | None:
    """The joint on the way from ``footprint`` towards ``base`` (its parent joint, or the
    child joint that leads to ``base`` when ``footprint`` is above it)."""
    graph = doc.graph
    for joint in graph.child_joints.get(footprint, []):
        if joint.child is not None and (joint.child == base or base in graph.subtree(joint.child)):
            return joint
    return graph.parent_joint(footprint)


def _humanoid(doc: Document, base: str, footprint: str) -> str | None:
    if N.relative(doc, base, footprint) is None:
        return None
    return (
        f"REP 120 (Frame Authorities): on a humanoid base_link -> base_footprint is not rigid "
        f"and is broadcast by an external node; this URDF welds {q(footprint)} to {q(base)}"
    )


def _mobile(doc: Document, base: str, footprint: str) -> str | None:
    if N.relative(doc, base, footprint, rigid=False) is None:
        return None  # not in one tree, or a malformed origin (other rules)
    pose = N.relative(doc, base, footprint)
    if pose is None:
        return (
            f"REP 120 (Frame Authorities): base_link -> base_footprint is rigid on a mobile "
            f"base; here {q(footprint)} moves with respect to {q(base)}"
        )
    problems = []
    if N.angle(IDENTITY, pose[0]) > N.ANGLE_TOL:
        rpy = N.fmt_angles(N.rpy_of(pose[0]))
        problems.append(f'rotated rpy="{rpy}" from {q(base)}')
    if pose[1][2] > N.LENGTH_TOL:
        problems.append(f"{fmt(pose[1][2])} m above {q(base)}")
    if not problems:
        return None
    return (
        "REP 120 (base_footprint): base_footprint is the robot's position on the floor, "
        f"level and below base_link; here {q(footprint)} is {' and '.join(problems)}"
    )
