"""A mass or principal moment is so small that engines treat it as zero.

## What it does
Reports, on links with an `<inertial>`:

- a mass above 0 but at most 1e-6 kg, under a Gazebo target, judged like a zero
  mass (I002): sdformat before 9.10.1 (Gazebo Classic) and 12.7.2 (Gazebo Sim)
  compares masses with a tolerance of 1e-6 and drops such a link, its joint and
  its subtree when nothing fixed to it has more mass;
- a principal moment above 0 but below 1e-12 kg·m², when the body engines
  simulate (the link plus the links fixed to it) has no larger moment.

The common placeholders for sensor frames (1e-5 kg, 1e-6 kg·m²) are above both
thresholds, and tiny values on frames fixed to a real body are not reported:
they are lumped into that body.

## Why is this bad?
- sdformat before 9.10.1, 12.7.2 and 13.5.0 tests `math::equal(mass, 0.0)`,
  whose tolerance is 1e-6: "if you decrease [mass] to 1e-6, the link is
  silently omitted" (gazebosim/sdformat#199). Later versions test `mass <= 0`
  and keep such a link, which then moves like a speck of dust.
- MuJoCo refuses moving bodies whose mass or inertia is below mjMINVAL
  (1e-15); ODE and Bullet become unstable with moments many orders of
  magnitude below their neighbours'.

## How to fix
Give the link its real mass and inertia. For a frame, use a fixed joint (and a
massless link, or the usual 1e-5 kg / 1e-6 kg·m² placeholder).
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import GAZEBO_MASSLESS, LUMPING, bodies, gazebo_verdict, selected
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.inertia import TINY_MOMENT, judge, principal_moments
from urdflint.model.values import fmt


@rule(
    "I010",
    "tiny-inertial",
    Severity.WARNING,
    fix="Give the link its real mass and inertia.",
    effects={"mass": K.TINY_MASS, "merged": {}},
)
def check(doc: Document) -> Iterator[Hit]:
    b = bodies(doc)
    for name, inertial in b.inertials.items():
        if inertial is None or inertial.mass is None or inertial.mass <= 0:
            continue
        if inertial.mass <= GAZEBO_MASSLESS:
            verdict = gazebo_verdict(doc, name) if selected(doc) & LUMPING else None
            if verdict is not None and verdict.severity > Severity.INFO:
                yield Hit(
                    inertial.mass_element,
                    f"link '{name}' has mass {fmt(inertial.mass)} kg, which sdformat before "
                    f"9.10.1 and 12.7.2 counts as zero, so {verdict.consequence}",
                    severity=verdict.severity,
                    variant="mass" if verdict.kind == "drop" else "merged",
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
