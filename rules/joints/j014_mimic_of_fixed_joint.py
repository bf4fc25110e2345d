"""A `<mimic>` joins a joint with one degree of freedom to a fixed (or planar, floating) one.

## What it does
Reports the `<mimic>` element of a joint when the leader it names is `fixed`
(no degree of freedom) or `floating`/`planar` (several) while the follower is
`revolute`, `continuous` or `prismatic`, and the other way round (a fixed
follower of a moving leader). Only those three types have the single
coordinate a mimic relation (`follower = multiplier * leader + offset`)
needs. A mimic between two joints that both lack it is reported too, except
between two `fixed` joints: nothing moves on either side (a hand welded
rigid keeps its mimic elements, as eve_r3's qb hand does), and Drake ignores
it with a warning. Two `planar` joints are a warning: Drake and MuJoCo load
the model and drop the relation. A leader that is missing or of an unknown
type is left to S008 and S006.

## Why is this bad?
urdfdom (`check_urdf`), Pinocchio (which builds a follower as an independent
joint unless asked for mimic support) and PyBullet load the model without a
word, but the follower does not follow:
- Drake refuses the model when the two sides differ: "Joint 'follower' which
  has 1 DOF cannot mimic joint 'leader' which has 0 DOF" (3 DOF for a planar
  leader; "which has 0 DOF cannot mimic joint ... which has 1 DOF" for a fixed
  follower). A floating leader, which Drake turns into a free body, gives
  "mimic element specifies joint 'leader' which does not exist". Two joints
  with the same number of degrees of freedom other than one are accepted with
  "Drake only supports the mimic element for single-dof joints ... The mimic
  element will be ignored."
- MuJoCo drops the constraint ("<mimic> on joint 'follower' ignored; mimic
  requires revolute, continuous, or prismatic joints"), so a moving follower
  moves freely; a fixed follower is fused away with its mimic.
- yourdfpy warns that the leader "is not actuated" and holds the follower at
  the offset.
A mimic of a fixed joint is usually left over from turning a moving joint
into a fixed one (a gripper finger welded for a demo) while its followers
still point at it. A moving follower of a fixed (or floating, planar) leader
is an error: the follower moves freely in every consumer. A fixed follower
of a moving leader is a warning: nothing is lost (the follower cannot move
anyway) except in Drake, which refuses the model; reduced models made by
welding the joints of a full robot (e.g. example-robot-data's
talos_reduced) carry such mimics.

## How to fix
Point the mimic at the moving joint that drives the follower, or remove the
`<mimic>` element when the follower should move on its own (or is meant to be
fixed too).
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import q

DOF = {"fixed": 0, "floating": 6, "planar": 3}  # the types that are not one coordinate
SINGLE = frozenset({"revolute", "continuous", "prismatic"})


def _dof(kind: str) -> str:
    count = DOF[kind]
    return "no degree of freedom" if count == 0 else f"{count} degrees of freedom"


@rule(
    "J014",
    "mimic-of-fixed-joint",
    Severity.ERROR,
    fix="Point the mimic at a revolute, continuous or prismatic joint, or remove it.",
    effects={"": K.MIMIC_DOF, "ignored": {}, "floating": K.MIMIC_OF_FLOATING},
)
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        mimic = joint.find("mimic")
        if mimic is None:
            continue
        target = (mimic.get("joint") or "").strip()
        leader = doc.joint_map.get(target) if target and target != joint.name else None
        if leader is None or joint.type is None or leader.type is None:
            continue  # S008, S006
        hit = _judge(joint.type, leader.type, q(joint.name), repr(target))
        if hit is not None:
            message, severity = hit
            variant = "ignored" if message.endswith("the mimic is ignored") else ""
            variant = "floating" if joint.type == "floating" else variant
            yield Hit(mimic, message, severity=severity, attribute="joint", variant=variant)


def _judge(follower: str, leader: str, name: str, target: str) -> tuple[str, Severity] | None:
    """The message (and severity) for a mimic between joints of these types, if any."""
    known = SINGLE | DOF.keys()
    if follower not in known or leader not in known:
        return None  # S006
    if follower in SINGLE and leader in SINGLE:
        return None
    if follower in SINGLE:
        return (
            f"joint {name} mimics {leader} joint {target}, which has {_dof(leader)}",
            Severity.ERROR,
        )
    if leader in SINGLE:  # a welded follower: it cannot move anyway; only Drake refuses
        return (
            f"{follower} joint {name} mimics joint {target} but has {_dof(follower)};"
            " Drake refuses the model, the others drop the mimic",
            Severity.WARNING if follower == "fixed" else Severity.ERROR,
        )
    if follower == leader == "fixed":
        return None  # nothing moves on either side; Drake ignores it with a warning
    message = (
        f"{follower} joint {name} ({_dof(follower)}) mimics {leader} joint {target} "
        f"({_dof(leader)})"
    )
    if follower == leader == "planar":
        return message + "; the mimic is ignored", Severity.WARNING
    if follower == "fixed":  # cannot move anyway: only Drake minds
        return message + "; Drake refuses the model, the others drop the mimic", Severity.WARNING
    return message, Severity.ERROR
