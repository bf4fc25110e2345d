"""The robot's total mass is not the expected one.

## What it does
When an expected mass is configured (`[tool.urdflint.expect] mass = 12.3`,
`mass-tolerance = 0.02` as a fraction, default 2 %; or
`--expect-mass 12.3`, `--expect-mass 12.3±0.2` in kg, `--expect-mass 12.3±2%`),
compares it with the total mass of the Pinocchio model, the root link and the
links welded to it included (see P002). The finding states both values, the
tolerance and the difference. It is a robot-level finding.

## Why is this bad?
A mass that drifts is a silent regression: a link's `<mass>` edited by hand, a
xacro property with the wrong unit (grams for kilograms), or a macro that stops
including a part. Nothing else fails. Simulation, controllers tuned on the real
robot, and payload estimates all quietly use the wrong number. This rule lets a
CI job assert "this robot weighs 12.3 kg ± 2 %".

## How to fix
Find the link whose mass changed (`urdflint info model.urdf` lists every link's
mass) and correct it. If the robot really changed, update the expected mass.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.values import fmt


@rule(
    "P003",
    "expected-mass",
    Severity.ERROR,
    needs=("pinocchio",),
    fix="Correct the link whose mass changed (urdflint info lists them), or update "
    "expect.mass if the robot really changed.",
)
def check(doc: Document) -> Iterator[Hit]:
    from urdflint.engine.physics import unverifiable

    expect = doc.settings.expect
    if expect.mass is None:
        return
    physics = doc.physics
    if not physics.built:
        why = unverifiable(doc, physics)
        if why:
            yield Hit(None, f"the expected mass of {fmt(expect.mass)} kg cannot be checked: {why}")
        return
    band = expect.mass_band()
    diff = physics.mass - expect.mass
    if abs(diff) <= band * (1 + 1e-12) + 1e-12:
        return
    share = (
        "" if expect.mass_abs_tolerance is not None else f" ({fmt(expect.mass_tolerance * 100)} %)"
    )
    yield Hit(
        None,
        f"the total mass is {fmt(physics.mass)} kg, expected {fmt(expect.mass)} kg ± "
        f"{fmt(band)} kg{share}: {fmt(abs(diff))} kg too {'heavy' if diff > 0 else 'light'}",
    )
