"""An engine named by `--confirm` built a limited joint without its limits, or other ones.

## What it does
Compares the `lower` and `upper` of each `revolute` or `prismatic` joint's `<limit>` with
the position limits of the joint each engine built: MuJoCo's `jnt_limited` and
`jnt_range`, PyBullet's `getJointInfo` lower and upper limits (PyBullet treats
lower > upper as "no limit"), Drake's `position_lower_limits` and
`position_upper_limits` (infinite: no limit), Pinocchio's `lowerPositionLimit` and
`upperPositionLimit`, and the `<limit>` of the joint's axis in the model sdformat
converted (its "no limit" defaults, ±1e16, count as none). A joint built without limits,
or with limits that differ from the file's by more than 1e-9 (relative), is reported on
its `<limit>` (at `lower`).

With inverted limits (`lower="1" upper="-1"`) MuJoCo 4.0 and PyBullet 3.2.7 build an
unlimited joint, Drake 1.51 aborts (`Joint(): condition '(pos_lower_limits.array() <=
pos_upper_limits.array()).all()' failed`, E005) and Pinocchio 4.1 keeps the inverted range
as given (not reported: it is what the file says); sdformat 12.3 swaps the two, with a
warning (E006: "urdf2sdf: revolute joint [elbow] with limits: lowStop[1] > highStop[-1],
switching the two."), and builds [-1, 1]. J009 reports the inverted range itself.

Without `--confirm` E003 does nothing.

## Why is this bad?
The simulated joint moves where the file says it cannot: a policy or planner tuned in
simulation drives the real joint into its hard stops, or the engines disagree with one
another about the same file.

## How to fix
Give the joint a `<limit>` with `lower` <= `upper` in radians (revolute) or metres
(prismatic); use a `continuous` joint for one that really has no limits.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.engines.common import label, outcomes

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, Joint
from urdflint.model.finding import Severity
from urdflint.model.values import parse_number

TOLERANCE = 1e-9


def declared(joint: Joint) -> tuple[float, float] | None:
    """The joint's ``(lower, upper)`` when it gives both as valid numbers (J001 and J002
    report a missing or malformed one)."""
    limit = joint.find("limit")
    if joint.type not in ("revolute", "prismatic") or limit is None:
        return None
    lower = parse_number(limit.get("lower"))
    upper = parse_number(limit.get("upper"))
    return None if lower is None or upper is None else (lower, upper)


def differs(a: float, b: float) -> bool:
    return abs(a - b) > TOLERANCE * max(abs(a), abs(b), 1.0)


def describe(lower: float | None, upper: float | None) -> str:
    if lower is None and upper is None:
        return "without limits"
    shown = [f"{v:g}" if v is not None else "unbounded" for v in (lower, upper)]
    return f"with limits [{shown[0]}, {shown[1]}]"


@rule(
    "E003",
    "engine-unlimited-joint",
    Severity.WARNING,
    fix="Give the joint lower <= upper, or make it continuous if it has no limits.",
)
def check(doc: Document) -> Iterator[Hit]:
    for outcome in outcomes(doc):
        if not outcome.built:
            continue
        for joint in doc.joints:
            wanted = declared(joint)
            built = outcome.limits.get(joint.name or "")
            if wanted is None or built is None:
                continue
            _, lower, upper = built
            same = lower is not None and upper is not None
            if same and not (differs(lower, wanted[0]) or differs(upper, wanted[1])):
                continue
            yield Hit(
                joint.find("limit"),
                f"{label(outcome.engine)} built joint {joint.name!r} {describe(lower, upper)} "
                f"(the URDF gives lower={wanted[0]:g} upper={wanted[1]:g})",
                attribute="lower",
                engine=outcome.engine,
            )
