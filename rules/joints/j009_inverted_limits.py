"""A joint's lower limit is above its upper limit, or the two are equal.

## What it does
On `revolute` and `prismatic` joints, compares `lower` and `upper` in `<limit>`
when both are written:

- `lower > upper` is an error;
- `lower == upper` is a warning: the joint cannot move.

Missing bounds are J001's, and bounds on continuous joints are J005's.

## Why is this bad?
Inverted limits describe an empty range, and every consumer handles that
differently, none of them well:

- Drake aborts the whole process (`pos_lower_limits <= pos_upper_limits` failed).
- MuJoCo silently makes the joint unlimited.
- Gazebo: sdformat swaps the two with the warning "lowStop > highStop, switching
  the two".
- Pinocchio and `check_urdf` accept the range as it is, so planners and IK then
  sample from an empty interval.

Equal bounds lock the joint in ROS, MoveIt and Gazebo, while MuJoCo (4.0)
warns "joint 'J' has equal lower and upper limits, limit ignored" and leaves
the joint free. A joint that must not move should
say so with `type="fixed"`. Equal bounds are a warning, not an error, because
ROS and Gazebo load the model.

## How to fix
Swap the values if they were written the wrong way round. For a locked joint,
use `type="fixed"`, or give the joint its real range.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model.document import Document
from urdflint.model.edits import Repair, SetAttribute
from urdflint.model.finding import Severity
from urdflint.model.values import fmt


@rule(
    "J009",
    "inverted-limits",
    Severity.ERROR,
    fix="Swap lower and upper so that lower < upper.",
    fixable="unsafe",
    effects={"inverted": K.INVERTED_LIMITS, "equal": K.EQUAL_LIMITS},
)
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        if joint.type not in J.BOUNDED:
            continue
        lim = J.limit(joint)
        if lim is None or lim.lower is None or lim.upper is None:
            continue
        unit = J.units(joint.type)[0]
        if lim.lower > lim.upper:
            yield Hit(
                lim.element,
                f"{J.label(joint)} has lower {fmt(lim.lower)} {unit} above upper "
                f"{fmt(lim.upper)} {unit}",
                attribute="lower",
                variant="inverted",
                repair=Repair(
                    "unsafe",
                    f"swap lower and upper to [{fmt(lim.upper)}, {fmt(lim.lower)}]",
                    (
                        SetAttribute(lim.element, "lower", lim.element.get("upper") or ""),
                        SetAttribute(lim.element, "upper", lim.element.get("lower") or ""),
                    ),
                ),
            )
        elif lim.lower == lim.upper:
            yield Hit(
                lim.element,
                f"{J.label(joint)} has lower = upper = {fmt(lim.lower)} {unit}, so it cannot move",
                fix='Use type="fixed" for a joint that must not move, or give it its real range.',
                severity=Severity.WARNING,
                variant="equal",
            )
