"""A mass or principal moment is so small that engines treat it as zero.

## What it does
Reports, on links with an `<inertial>`:

- a mass above 0 but at most 1e-6 kg, judged like a zero mass (I002): Gazebo
  compares masses with a tolerance of 1e-6 and drops such a link, its joint and
  its subtree when nothing fixed to it has more mass;
- a principal moment above 0 but below 1e-12 kg·m², when the body engines
  simulate (the link plus the links fixed to it) has no larger moment.

The common placeholders for sensor frames (1e-5 kg, 1e-6 kg·m²) are above both
thresholds, and tiny values on frames fixed to a real body are not reported:
they are lumped into that body.

## Why is this bad?
- sdformat tests `math::equal(mass, 0.0)`, whose tolerance is 1e-6: "if you
  decrease [mass] to 1e-6, the link is silently omitted" (gazebosim/sdformat#199).
- MuJoCo refuses moving bodies whose mass or inertia is below mjMINVAL (1e-15);
  Pinocchio's ABA checker flags values below 1e-5; ODE and Bullet become
  unstable with moments many orders of magnitude below their neighbours'.

## How to fix
Give the link its real mass and inertia. For a frame, use a fixed joint (and a
massless link, or the usual 1e-5 kg / 1e-6 kg·m² placeholder).
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import GAZEBO_MASSLESS, bodies, massless_verdict
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.inertia import TINY_MOMENT, judge, principal_moments
from urdflint.model.values import fmt


@rule("I010", "tiny-inertial", Severity.WARNING, fix="Give the link its real mass and inertia.")
def check(doc: Document) -> Iterator[Hit]:
    b = bodies(doc)
    for name, inertial in b.inertials.items():
        if inertial is None or inertial.mass is None or inertial.mass <= 0:
            continue
        if inertial.mass <= GAZEBO_MASSLESS:
            verdict = massless_verdict(doc, name)
            if verdict is not None and verdict.severity > Severity.INFO:
                yield Hit(
                    inertial.mass_element,
                    f"link '{name}' has mass {fmt(inertial.mass)} kg, which Gazebo counts as zero, "
                    f"so {verdict.consequence}",
                    severity=verdict.severity,
                )
            continue
        if inertial.tensor is None:
            continue
        moments = principal_moments(inertial.tensor)
        smallest = moments[0]
        if judge(moments) != "valid" or smallest >= TINY_MOMENT or b.excused(name):
            continue
        yield Hit(
            inertial.inertia_element,
            f"link '{name}' has a principal moment of {fmt(smallest)} kg·m², "
            f"below {fmt(TINY_MOMENT)} kg·m²",
        )
