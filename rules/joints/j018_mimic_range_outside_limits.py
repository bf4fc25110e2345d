"""A mimic maps its leader's range outside the follower's own limits, or freezes the follower.

## What it does
For a `<mimic>` between two joints with limits (revolute or prismatic; S008, J014 and
J017 handle the rest), maps the leader's `[lower, upper]` through
`follower = multiplier * leader + offset` and reports when the result leaves the
follower's own `[lower, upper]` by more than 1% of the follower's range (a warning),
usually a multiplier with the wrong sign or an offset in degrees. A multiplier of 0 is
reported too: the follower is frozen at the offset whatever the leader does.

## Why is this bad?
Where the mimic is enforced, the relation and the follower's limit fight each other as
soon as the leader leaves the part of its range that the follower can follow: MuJoCo's
joint equality constraint and the follower's limit are both active and the solver
splits the difference (the follower's links jitter, the leader stops short), Drake's
coupler constraint does the same, and Isaac Sim's importer replaces the follower's
limits by the mapped leader range plus 20% (so the URDF's limits are silently lost
there). MoveIt computes the follower from the leader and then rejects the state as out
of bounds (`satisfiesBounds` fails for the follower), so a motion planned to the
leader's limit is invalid. Typical causes: a gripper finger that closes the other way
(`multiplier="1"` where the axis was flipped, -1 was meant), or an offset written in
degrees.

## How to fix
Make the mapped range lie inside the follower's limits: flip the sign of `multiplier`
(or of the follower's `<axis>`), correct the `offset`, or widen the follower's limits to
the range it really travels.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, Joint
from urdflint.model.finding import Severity
from urdflint.model.structure import q
from urdflint.model.values import fmt, parse_number

LIMITED = frozenset({"revolute", "prismatic"})
SLACK = 0.01  # of the follower's range


@rule(
    "J018",
    "mimic-range-outside-limits",
    Severity.WARNING,
    fix="Make multiplier * leader range + offset lie inside the follower's limits "
    "(check the multiplier's sign and the offset's unit).",
)
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        mimic = joint.find("mimic")
        if mimic is None or joint.type not in LIMITED:
            continue
        leader = doc.joint_map.get((mimic.get("joint") or "").strip())
        if leader is None or leader is joint or leader.type not in LIMITED:
            continue
        multiplier = _attribute(mimic, "multiplier", 1.0)
        offset = _attribute(mimic, "offset", 0.0)
        if multiplier is None or offset is None:
            continue  # X004
        if multiplier == 0:
            yield Hit(
                mimic,
                f"joint {q(joint.name)} mimics {q(leader.name)} with multiplier 0: it stays "
                f"at the offset {fmt(offset)} whatever {q(leader.name)} does",
                attribute="multiplier",
            )
            continue
        message = _outside(joint, leader, multiplier, offset)
        if message is not None:
            yield Hit(mimic, message, attribute="multiplier")


def _outside(joint: Joint, leader: Joint, multiplier: float, offset: float) -> str | None:
    own, theirs = _limits(joint), _limits(leader)
    if own is None or theirs is None:
        return None
    a, b = sorted((multiplier * theirs[0] + offset, multiplier * theirs[1] + offset))
    slack = SLACK * (own[1] - own[0])
    if a >= own[0] - slack and b <= own[1] + slack:
        return None
    return (
        f"joint {q(joint.name)} mimics {q(leader.name)} (multiplier {fmt(multiplier)}, "
        f"offset {fmt(offset)}): the leader's range [{fmt(theirs[0])}, {fmt(theirs[1])}] "
        f"maps to [{fmt(a)}, {fmt(b)}], outside the follower's limits "
        f"[{fmt(own[0])}, {fmt(own[1])}]"
    )


def _limits(joint: Joint) -> tuple[float, float] | None:
    limit = joint.find("limit")
    if limit is None:
        return None
    lower, upper = parse_number(limit.get("lower", "0")), parse_number(limit.get("upper", "0"))
    if lower is None or upper is None or not lower < upper:
        return None  # X004, J009
    return lower, upper


def _attribute(el: object, name: str, default: float) -> float | None:
    text = el.get(name)  # type: ignore[attr-defined]
    return default if text is None else parse_number(text)
