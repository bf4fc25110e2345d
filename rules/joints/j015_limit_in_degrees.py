"""A revolute joint's limits look like degrees written where URDF expects radians.

## What it does
Checks the `<limit>` of every `revolute` joint (not `continuous` or `prismatic`):

- `lower` or `upper` beyond ±4π (two full turns) and within ±1080: `upper="180"`
  is 28.6 turns in radians and half a turn in degrees. Values up to 4π are
  left alone, because real multi-turn joints go there (ABB wrists ±400°
  = ±6.98 rad, FANUC ±450° = ±7.85 rad, ANYmal's legs ±3π, Solo's ±10 rad),
  and so are values beyond ±1080 and powers of ten (`1e16`, `1000`):
  placeholders for "unbounded", not degrees;
- `velocity` that is a multiple of 15 between 60 and 1440 and not a power of
  ten (90, 180, 225, 360, 720): a speed from a data sheet in degrees per
  second. Real revolute joints in 2400 published URDFs stay under 53 rad/s, and
  the larger values there are the placeholders 100, 1000 and 10000, which are
  not reported.

The message gives the value converted from degrees. `urdflint fix
--unsafe-fixes` converts the bounds, except on joints named like wheels,
rollers, rotors and casters, which should rather be `continuous`.

## Why is this bad?
URDF angles are radians (REP 103), and no consumer converts: urdfdom, MoveIt,
Gazebo, MuJoCo (4.0 loads `lower="-90" upper="180"` as the range -90..180
rad), Drake, PyBullet and Isaac Sim all read `upper="180"` as 180 rad. A range of ±180 rad is no
range at all (the joint is practically unlimited, so planners and simulators
let it pass through its real hard stops), and a velocity limit of 180 rad/s
where the data sheet says 180°/s is 57 times too fast for trajectory timing in
MoveIt and for the velocity limits Gazebo and ros2_control enforce.

## How to fix
Convert to radians: multiply degrees by π/180 (`upper="${radians(180)}"` in
xacro). A joint that really turns more than two turns either way should be
`continuous` (no bounds) or keep its value with a suppression that says why.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model.document import Document, Joint
from urdflint.model.edits import Repair, SetAttribute
from urdflint.model.finding import Severity
from urdflint.model.values import fmt

TURNS = 4 * math.pi  # beyond two turns either way: not a plausible range in radians
MAX_DEGREES = 1080.0  # three turns in degrees; larger bounds are "unbounded" placeholders
SPINNING_RE = re.compile(r"wheel|roller|rotor|propeller|caster", re.I)  # no degrees repair
VELOCITY = (60.0, 1440.0)  # degrees per second written as rad/s (multiples of 15)


def placeholder(value: float) -> bool:
    """``100``, ``1000``, ``1e16``: a round power of ten used for 'unbounded'."""
    magnitude = abs(value)
    return magnitude >= 10 and math.log10(magnitude).is_integer()


def degree_bound(value: float | None) -> bool:
    return (
        value is not None
        and TURNS < abs(value) <= MAX_DEGREES
        and not placeholder(value)
        and math.isfinite(value)
    )


def degree_velocity(value: float | None) -> bool:
    return (
        value is not None
        and VELOCITY[0] <= value <= VELOCITY[1]
        and value % 15 == 0
        and not placeholder(value)
    )


@rule("J015", "limit-in-degrees", Severity.WARNING, fixable="unsafe")
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        if joint.type != "revolute":
            continue
        lim = J.limit(joint)
        if lim is None:
            continue
        bounds: list[tuple[str, float]] = []
        for attr, value in (("lower", lim.lower), ("upper", lim.upper)):
            if value is not None and degree_bound(value):
                bounds.append((attr, value))
        if bounds:
            yield _position(joint, lim, bounds)
        if degree_velocity(lim.velocity) and lim.velocity is not None:
            v = lim.velocity
            yield Hit(
                lim.element,
                f"{J.label(joint)} has velocity {fmt(v)} rad/s ({fmt(round(v * 30 / math.pi))} "
                f"rpm): degrees per second? {fmt(v)}°/s is {fmt(round(math.radians(v), 4))} rad/s",
                fix=f'Write velocity="{fmt(round(math.radians(v), 4))}" if the data sheet says '
                f"{fmt(v)}°/s.",
                attribute="velocity",
            )


def _position(joint: Joint, lim: J.Limit, bounds: list[tuple[str, float]]) -> Hit:
    said = " and ".join(f"{a} {fmt(v)}" for a, v in bounds)
    turns = max(abs(v) for _, v in bounds) / (2 * math.pi)
    converted = ", ".join(f"{a}={fmt(round(math.radians(v), 4))}" for a, v in bounds)
    return Hit(
        lim.element,
        f"{J.label(joint)} has {said} rad ({turns:.1f} turns): degrees (then {converted}), "
        "or a joint that turns freely and should be continuous",
        fix="Convert the bounds to radians, or make a joint that turns freely continuous.",
        attribute=bounds[0][0],
        repair=None
        if SPINNING_RE.search(f"{joint.name} {joint.child}")
        else Repair(
            "unsafe",
            f"convert {said} from degrees to radians",
            tuple(SetAttribute(lim.element, a, fmt(round(math.radians(v), 6))) for a, v in bounds),
        ),
    )
