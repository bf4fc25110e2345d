"""A joint lacks the `<limit>` data urdfdom needs, or leaves its range to defaults.

## What it does
Reports three cases:

- a `revolute` or `prismatic` joint without `<limit>` (error);
- a `<limit>`, on a joint of any type, without `effort` or without `velocity`
  (error): urdfdom parses every `<limit>` it finds and demands both, even on
  `continuous` and `fixed` joints;
- a `revolute` or `prismatic` `<limit>` without `lower` or `upper` (warning):
  the model loads, but the missing bound silently becomes 0.

## Why is this bad?
urdfdom refuses the whole model in the first two cases ("Joint [X] is of type
REVOLUTE but it does not specify limits", "joint limit: no effort", "joint
limit: no velocity"), and with it ROS (`robot_state_publisher`, MoveIt),
Pinocchio, kdl_parser and Gazebo, whose URDF converter calls urdfdom.

A missing `lower` or `upper` defaults to 0 in urdfdom, so a `<limit>` with
neither bound locks the joint at 0 in ROS, MoveIt and Gazebo, while PyBullet
defaults to `lower=0 upper=-1`, which it reads as "no limit", and MuJoCo makes
a joint with one bound or none unlimited. The same file gives a locked joint in one
tool and a free one in another. It is a warning, not an error, because every
parser still loads the model.

## How to fix
Write the complete element:
`<limit lower="-1.57" upper="1.57" effort="30" velocity="2"/>` (rad, N·m and
rad/s; m, N and m/s for prismatic joints). A joint that turns without bounds
should be `continuous`, which needs no `lower`/`upper`.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.values import fmt


@rule(
    "J001",
    "missing-limit",
    Severity.ERROR,
    fix='Add <limit lower=".." upper=".." effort=".." velocity=".."/> with all four attributes.',
    effects={"no-limit": K.NO_LIMIT, "no-effort-or-velocity": K.NO_EFFORT_OR_VELOCITY},
)
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        lim = J.limit(joint)
        if lim is None:
            if joint.type in J.BOUNDED:
                yield Hit(
                    joint.element,
                    f"{J.label(joint)} has no <limit>; urdfdom refuses the model",
                    variant="no-limit",
                )
            continue
        missing = [a for a in ("effort", "velocity") if not lim.has(a)]
        if missing:
            yield Hit(
                lim.element,
                f"<limit> of {J.label(joint)} has no {' and no '.join(missing)}; "
                "urdfdom refuses the model",
                fix="Add both effort and velocity: urdfdom requires them on every <limit>.",
                variant="no-effort-or-velocity",
            )
        if joint.type in J.BOUNDED:
            bounds = [a for a in ("lower", "upper") if not lim.has(a)]
            if bounds:
                lower = 0.0 if not lim.has("lower") else lim.lower
                upper = 0.0 if not lim.has("upper") else lim.upper
                shown = (
                    f"[{fmt(lower)}, {fmt(upper)}]"
                    if lower is not None and upper is not None
                    else "0 for the missing bound"
                )
                yield Hit(
                    lim.element,
                    f"<limit> of {J.label(joint)} has no {' and no '.join(bounds)}; "
                    f"urdfdom uses {shown}" + (", a locked joint" if lower == upper else ""),
                    fix="Write both lower and upper, or make an unbounded joint continuous.",
                    severity=Severity.WARNING,
                )
