"""The robot's centre of mass is not where it is expected.

## What it does
When an expected centre of mass is configured (`[tool.urdflint.expect]
com = [x, y, z]`, `com-tolerance = 0.01` in metres; or
`--expect-com X,Y,Z` / `--expect-com X,Y,Z±TOL`), computes the centre of mass of
the whole robot with Pinocchio. The root link and the links welded to it are
included (see P002). The COM is in the root link's frame, at the neutral
configuration (every joint at 0) or at the positions given with
`--q joint=value` or `[tool.urdflint.expect.q]`. Mimic joints follow their
leader. The finding states both points, the tolerance and the distance.

It also reports a `--q`/`expect.q` entry that cannot be applied: a joint the
model does not have (with a did-you-mean), a fixed joint, a mimic joint (set its
leader) or a floating or planar joint (several coordinates). And it reports a
COM that cannot be computed because a link has negative mass or the total is
not positive: Pinocchio 4.1 returns NaN for a zero total, and for negative
masses a weighted average with negative weights, a point that means nothing.

## Why is this bad?
The centre of mass decides whether a legged robot stands, how a mobile base tips
over and what gravity compensation an arm needs. It moves when a link's mass or
inertial origin is edited, or when an origin's sign flips. Nothing fails loudly.
A CI gate on it catches such a regression on the commit that caused it.

## How to fix
Find the link whose mass or `<inertial><origin>` changed and correct it, or
update the expected COM if the robot really changed. Spell the joints in `--q`
as the URDF does.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.values import fmt


def point(v: tuple[float, ...]) -> str:
    return "(" + ", ".join(fmt(x + 0.0) for x in v) + ")"


@rule(
    "P004",
    "expected-com",
    Severity.ERROR,
    needs=("pinocchio",),
    fix="Correct the link whose mass or inertial origin changed (urdflint info), or update "
    "expect.com if the robot really changed.",
)
def check(doc: Document) -> Iterator[Hit]:
    from urdflint.engine.physics import unverifiable

    expect = doc.settings.expect
    physics = doc.physics if (expect.com is not None or expect.q) else None
    if physics is None:
        return
    if not physics.built:
        why = unverifiable(doc, physics) if expect.com is not None else None
        if why:
            yield Hit(None, f"the expected centre of mass cannot be checked: {why}")
        return
    for problem in physics.q_problems:
        yield Hit(
            problem.element, problem.message, fix=problem.fix or "Spell the joint as the URDF does."
        )
    if expect.com is None:
        return
    if physics.com is None:
        yield Hit(
            None,
            f"the expected centre of mass cannot be checked: {physics.com_problem}",
            fix="Give every link a positive mass (I002).",
        )
        return
    distance = math.dist(physics.com, expect.com)
    if distance <= expect.com_tolerance * (1 + 1e-12) + 1e-15:
        return
    where = (
        "at " + ", ".join(f"{k}={fmt(v)}" for k, v in sorted(physics.q.items()))
        if physics.q
        else "at the neutral configuration"
    )
    yield Hit(
        None,
        f"the centre of mass is at {point(physics.com)} m in the frame of root link "
        f"'{physics.root}' {where}, expected {point(expect.com)} m ± "
        f"{fmt(expect.com_tolerance)} m: {fmt(distance)} m away",
    )
