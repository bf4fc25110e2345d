"""A `planar` or `floating` joint, which a selected target drops, converts or refuses.

## What it does
Reports `planar` and `floating` joints for the selected targets that do not build
them as written; the severity is that of the worst consequence among them (see
"What each target does" below): an error for Gazebo (the model is refused), Isaac Sim
(no planar joint) and MuJoCo (a floating joint below a moving body); a warning for
PyBullet (a floating joint becomes fixed) and ROS (KDL makes both fixed). MuJoCo, Drake
and Pinocchio build a planar joint; Drake leaves a floating child as a free body with a
warning (info).

## Why is this bad?
Gazebo reads URDF through sdformat's converter (`parser_urdf.cc`, `CreateJoint`). The
converter maps `floating` and `planar` to no SDF joint type and writes no joint at all,
so the joint's `<origin>` is lost (gazebosim/sdformat#1282, open). sdformat 12.3
(observed, Gazebo Fortress) then refuses the converted model: the child link's pose is
written relative to the joint that was not written ("relative_to name[J] specified by
link with name[L] does not match a nested model, link, joint, or frame name").

- MuJoCo builds a planar joint (three joints) and a floating joint as a free joint, but
  only on a body at the top level: below a moving body it refuses the model ("free joint
  can only be used on top level"); a body welded to the static root counts as top level.
- PyBullet 3.2.7 builds a floating joint as a fixed one ("joint unsupported, creating a
  fixed joint instead"): the body meant to be free is welded.
- Drake builds a planar joint; for a floating one it warns ("not supported by
  MultibodyPlant. Leaving 'L' as a free body"), which is what a floating joint means.
- Isaac Sim's importer (source, v5.1) has no planar joint (its README says so; the import
  fails on a null joint prim) and drops floating joints, leaving a free body.
- kdl_parser converts both to fixed joints ("Converting unknown joint type of joint 'J'
  into a fixed joint"), so `robot_state_publisher` never moves them; MoveIt builds both
  as multi-DOF joints.

## How to fix
For planar motion, replace the joint with two `prismatic` joints and one `continuous`
joint through intermediate links (give each a small `<inertial>`), or drive the base with
a planar-move plugin. For a floating body, remove the joint and spawn the link as a
separate model.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model import targets
from urdflint.model.document import Document, Joint
from urdflint.model.effects import Effect, refused
from urdflint.model.finding import Severity

FIXES = {
    "planar": "Replace the joint with two prismatic joints and a continuous one through "
    "intermediate links (each with a small <inertial>), or drive the base with a plugin.",
    "floating": "Spawn the floating link as a model of its own, or remove the joint.",
}


@rule(
    "J012",
    "unsupported-joint-type-for-target",
    Severity.ERROR,
    fix=FIXES["planar"],
    effects={"planar": K.PLANAR, "floating": {**K.FLOATING, "mujoco": K.FLOATING_MUJOCO}},
    by_target=True,
)
def check(doc: Document) -> Iterator[Hit]:
    chosen = targets.ordered(doc.targets)
    for joint in doc.joints:
        if joint.type not in FIXES:
            continue
        table = effects(doc, joint)
        found = {t: table[t] for t in chosen if t in table}
        if not found:
            continue
        yield Hit(
            joint.element,
            f"{J.label(joint)}: " + "; ".join(_sentences(found)),
            fix=FIXES[joint.type],
            variant=joint.type,
            effects=found,
        )


def effects(doc: Document, joint: Joint) -> dict[str, Effect]:
    """What each target does with the planar or floating ``joint``: MuJoCo accepts a free
    joint only on a body of the top level (a child of the static root or world)."""
    table = dict(K.PLANAR if joint.type == "planar" else K.FLOATING)
    drake = _drake(doc, joint)
    if drake is not None:
        table["drake"] = drake
    if joint.type == "planar":
        return table
    link, seen = joint.parent, set()
    while link is not None and link not in seen:  # up through fixed joints: MuJoCo fuses them
        seen.add(link)
        above = doc.graph.parent_joint(link)
        if above is None or above.type != "fixed":
            break
        link = above.parent
    if link is None or doc.graph.parent_joint(link) is not None:
        table["mujoco"] = K.FLOATING_MUJOCO
    return table


def _sentences(found: dict[str, Effect]) -> list[str]:
    """``Gazebo Classic and Gazebo Sim: the converter writes no joint...`` (targets with the
    same detail share a sentence)."""
    by_detail: dict[str, list[str]] = {}
    for target, effect in found.items():
        text = effect.detail or effect.consequence.phrase
        by_detail.setdefault(text, []).append(targets.LABELS[target])
    return [f"{' and '.join(labels)}: {text}" for text, labels in by_detail.items()]


def _drake(doc: Document, joint: Joint) -> Effect | None:
    """Drake (observed, 1.51) refuses an actuated planar or floating joint (a <transmission>
    names it: "AddJointActuator ... this joint has 3 degrees of freedom", or "Transmission
    specifies joint ... which does not exist" for a floating one, which it does not build),
    and a planar joint's <dynamics damping> given as one number ("Expected 3 values")."""
    named = {
        (j.get("name") or "").strip()
        for t in doc.robot.iter("transmission")
        for j in t.iter("joint")
    }
    if joint.name in named:
        return refused("a <transmission> drives it: Drake cannot add its actuator")
    dynamics = joint.find("dynamics")
    damping = (dynamics.get("damping") or "").split() if dynamics is not None else []
    if joint.type == "planar" and len(damping) == 1:
        return refused('"Expected 3 values for attribute damping": one per planar DOF')
    return None
