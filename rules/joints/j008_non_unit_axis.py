"""A moving joint's axis is not a unit vector.

## What it does
Reports the `<axis>` of a `revolute`, `continuous`, `prismatic` or `planar`
joint whose length differs from 1 by more than the `tolerance` option (default
`1e-3`). It gives the length and the normalised axis. The default tolerance
accepts unit vectors rounded to three decimals, such as `0.707 0.707 0`, whose
length is within 9e-4 of 1.

Zero axes are J007's.

## Why is this bad?
urdfdom passes the axis through as written. Gazebo (sdformat), MuJoCo, Drake,
Pinocchio, KDL and MoveIt normalise it, so the model works there. Code that uses
the axis as written does not: a prismatic joint computed as `axis * q` travels
`|axis|` times too far, and `Rotation.from_rotvec(axis * q)` turns by
`|axis| * q`. Such code is common in Python forward-kinematics helpers and in
exporters. An axis like `1 1 0` also hides whether a 45° axis was meant.

## How to fix
Write the normalised axis shown in the message (at least 6 significant digits,
e.g. `0.707107 0.707107 0`).
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model.document import Document
from urdflint.model.edits import Repair, SetAttribute
from urdflint.model.finding import Severity
from urdflint.model.values import fmt


@rule(
    "J008",
    "non-unit-axis",
    Severity.WARNING,
    options={"tolerance": 1e-3},
    fixable="safe",
    effects={"": K.NON_UNIT_AXIS, "prismatic": K.NON_UNIT_PRISMATIC},
)
def check(doc: Document, opts: dict[str, Any]) -> Iterator[Hit]:
    tolerance = float(opts["tolerance"])
    for joint in doc.joints:
        if joint.type not in J.AXIS_USED:
            continue
        el = joint.find("axis")
        vec = J.axis(joint)
        if el is None or vec is None:
            continue
        length = J.norm(vec)
        if length <= J.ZERO_NORM or abs(length - 1.0) <= tolerance:
            continue
        unit = J.fmt_vector(J.normalised(vec))
        yield Hit(
            el,
            f"{J.label(joint)} has axis {J.fmt_vector(vec)} of length {fmt(length)}; "
            f"normalised it is {unit}",
            fix=f'Write <axis xyz="{unit}"/>.',
            variant="prismatic" if joint.type == "prismatic" else "",
            repair=Repair(
                "safe", f"normalise the axis to {unit}", (SetAttribute(el, "xyz", unit),)
            ),
        )
