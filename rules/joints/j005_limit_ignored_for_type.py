"""A `<limit>`, or its `lower`/`upper`, is ignored for this type of joint.

## What it does
Reports:

- `lower` or `upper` on a `continuous` joint (warning when the range is
  narrower than one full turn, which suggests the author wanted a bounded
  joint; info otherwise). `effort` and `velocity` on a continuous joint are
  used, and urdfdom requires them whenever `<limit>` is present, so they are
  never reported;
- any `<limit>` on a `floating` or `planar` joint (warning);
- any `<limit>` on a `fixed` joint (info: the joint does not move, so nothing is
  lost, but the values are dead).

## Why is this bad?
urdfdom parses the `<limit>` of every joint, but no consumer applies bounds to a
continuous joint: ROS, MoveIt, Gazebo (sdformat writes no bounds for
continuous joints), MuJoCo and Pinocchio all treat it as unbounded. A
continuous joint with `lower="-0.38" upper="0"` spins freely in simulation,
although the file reads as if it were bounded.

A floating or planar joint has several degrees of freedom that one `<limit>`
cannot describe. sdformat drops these joints altogether (see J012), and MoveIt
ignores the limit. A fixed joint never moves, so its `<limit>` usually means
that the joint was once movable, or that the author expected it to move.

## How to fix
For a joint that must stay within bounds, make it `revolute` (and keep
`lower`/`upper`). For a joint that really turns freely, delete `lower` and
`upper` and keep `effort` and `velocity`. On fixed, floating and planar joints,
delete the `<limit>`.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model.document import Document
from urdflint.model.edits import RemoveAttribute, RemoveElement, Repair
from urdflint.model.finding import Severity
from urdflint.model.values import fmt


@rule(
    "J005",
    "limit-ignored-for-type",
    Severity.WARNING,
    fix="Make the joint revolute if it must stay within bounds, else delete the ignored values.",
    fixable="safe",
)
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        lim = J.limit(joint)
        if lim is None:
            continue
        if joint.type == "continuous":
            written = [a for a in ("lower", "upper") if lim.has(a)]
            if not written:
                continue
            values = " and ".join(
                f"{a} {fmt(v)}" if (v := getattr(lim, a)) is not None else a for a in written
            )
            wide = (
                lim.lower is not None
                and lim.upper is not None
                and lim.upper - lim.lower >= 2 * math.pi
            )
            yield Hit(
                lim.element,
                f"{J.label(joint)} has {values} in <limit>, which are ignored: "
                "a continuous joint has no position bounds",
                fix="Make the joint revolute to enforce the bounds, or delete lower and upper.",
                severity=Severity.INFO if wide else None,
                repair=Repair(
                    "safe",
                    "delete the ignored lower and upper",
                    tuple(RemoveAttribute(lim.element, a) for a in written),
                ),
            )
        elif joint.type in J.LIMIT_IGNORED:
            yield Hit(
                lim.element,
                f"{J.label(joint)} has a <limit>, which is ignored for {joint.type} joints",
                fix="Delete the <limit>, or change the joint type if it is meant to move.",
                severity=Severity.INFO if joint.type == "fixed" else None,
                repair=Repair("safe", "delete the ignored <limit>", (RemoveElement(lim.element),)),
            )
