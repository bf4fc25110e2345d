"""A joint has a `<calibration>` element, which the simulators ignore.

## What it does
Reports the `<calibration>` of a `<joint>` (the first: a repeated one is X015's).

## Why is this bad?
`<calibration>` (the `rising`/`falling` reference positions) is read by urdfdom
and used only by robot-specific calibration controllers, such as the PR2's.
The Gazebo tutorial "Using a URDF in Gazebo" states that `<calibration>` is
ignored; sdformat's URDF converter drops it for Gazebo Classic and Gazebo Sim,
MuJoCo skips it, and Drake warns "The tag 'calibration' found as a child of
'joint' is currently unsupported and will be ignored". It does nothing in
simulation, so it should not be mistaken for a zero offset that is applied.

This finding is informational.

## How to fix
Keep it if your real robot's calibration controller reads it. Otherwise delete
it. To silence the finding for a robot that needs it, suppress J002 in the
configuration.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model.document import Document
from urdflint.model.effects import single
from urdflint.model.finding import Severity


@rule(
    "J002",
    "calibration-ignored",
    Severity.INFO,
    fix="Delete <calibration> unless a calibration controller on the real robot reads it.",
    effects=single(K.CALIBRATION),
)
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        el = joint.find("calibration")
        if el is not None:
            yield Hit(
                el,
                f"{J.label(joint)} has a <calibration>, which Gazebo, MuJoCo and Drake ignore",
            )
