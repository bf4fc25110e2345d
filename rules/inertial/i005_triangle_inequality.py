"""The principal moments of inertia break the triangle inequality A + B ≥ C.

## What it does
For positive-definite tensors (I003 and I004 cover the others), computes the
three principal moments A ≤ B ≤ C from the full tensor and reports A + B < C,
with a relative slack of 1e-6 × C for rounding.

## Why is this bad?
For any real mass distribution each principal moment is at most the sum of the
other two, so such a tensor describes no physical body. A positive-definite
check does not catch it, which is why it survives most validators (Talos
grippers, Gepetto/example-robot-data#130; Galbot, galbot_s1_description#5).
sdformat/gz-math (`ValidMoments`) reject it ("A link named X has invalid
inertia"), MuJoCo refuses it ("inertia must satisfy A + B >= C; use
'balanceinertia' to fix"), Drake warns that the moments "do not satisfy the
triangle inequality" and substitutes another inertia, Simbody and Genesis
refuse it too.

## How to fix
Recompute the tensor from the geometry and the mass (CAD, Drake's
`fix_inertia`), or balance it (MuJoCo's `balanceinertia` sets each violating
moment to the mean). A slightly violated thin plate usually only needs more
digits in the values.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import bodies
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.inertia import principal_moments, tolerance
from urdflint.model.values import fmt


@rule(
    "I005",
    "triangle-inequality",
    Severity.ERROR,
    fix="Recompute the tensor from the geometry and mass, or balance the moments.",
)
def check(doc: Document) -> Iterator[Hit]:
    for name, inertial in bodies(doc).inertials.items():
        if inertial is None or inertial.tensor is None or min(inertial.tensor[:3]) <= 0:
            continue
        moments = principal_moments(inertial.tensor)
        a, b, c = moments
        tol = tolerance(moments)
        if a > tol and a + b < c - tol:
            yield Hit(
                inertial.inertia_element,
                f"link '{name}' has principal moments {fmt(a)}, {fmt(b)} and {fmt(c)} kg·m², "
                f"and {fmt(a)} + {fmt(b)} < {fmt(c)}",
            )
