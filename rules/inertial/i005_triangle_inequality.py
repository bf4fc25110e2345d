"""The principal moments of inertia break the triangle inequality A + B ≥ C.

## What it does
For positive-definite tensors (I003 and I004 cover the others), computes the
three principal moments A ≤ B ≤ C from the full tensor and reports A + B < C,
with a relative slack of 1e-6 × C for rounding.

Such a tensor is always reported: an **error**, or a **warning** on a link
welded by a fixed joint when the only targets are Gazebo's and the lumped body
(the link plus the links fixed to it) is still valid. Gazebo sums the welded
link into that body before checking it; MuJoCo checks every link before fusing
static bodies, and Drake and PyBullet keep welded links as bodies, so for them
it stays an error.

## Why is this bad?
For any real mass distribution each principal moment is at most the sum of the
other two, so such a tensor describes no physical body. A positive-definite
check does not catch it, which is why it survives most validators (Talos
grippers, Gepetto/example-robot-data#130; Galbot, galbot_s1_description#5).
sdformat's DOM (gz-math `ValidMoments`) reports it ("A link named X has invalid
inertia"). Observed, even on a link welded to a valid body: MuJoCo 4.0 refuses
the model ("inertia must satisfy A + B >= C; use 'balanceinertia' to fix",
naming the welded link); Drake 1.51 warns that the moments "do not satisfy the
triangle inequality" and substitutes another inertia; PyBullet 3.2.7 with
`URDF_USE_INERTIA_FROM_FILE` sets it to zero ("Bad inertia tensor properties,
setting inertia to zero for link"). Pinocchio 4.1 loads it as written.

## How to fix
Recompute the tensor from the geometry and the mass (CAD, Drake's
`fix_inertia`), or balance it (MuJoCo's `balanceinertia` sets all three
principal moments to their mean). A slightly violated thin plate usually only
needs more digits in the values.

`urdflint fix --unsafe-fixes` writes the tensor of the link's collision
geometry at the declared mass (about its centroid in the link's axes, so the
origin's `rpy` becomes `0 0 0`; the declared centre of mass is kept). A link
without usable collision geometry gets MuJoCo's balance instead: the three
principal moments set to their average, which keeps their sum and loses the
axes.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K
from urdflint.rules import lumping as L
from urdflint.rules.inertial import refit

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import bodies, impossible_severity
from urdflint.model.document import Document
from urdflint.model.effects import single
from urdflint.model.finding import Severity
from urdflint.model.inertia import principal_moments, tolerance
from urdflint.model.values import fmt


@rule(
    "I005",
    "triangle-inequality",
    Severity.ERROR,
    fix="Recompute the tensor from the geometry and mass, or balance the moments.",
    effects=single(K.BAD_TENSOR),
    fixable="unsafe",
)
def check(doc: Document) -> Iterator[Hit]:
    for name, inertial in bodies(doc).inertials.items():
        if inertial is None or inertial.tensor is None or min(inertial.tensor[:3]) <= 0:
            continue
        moments = principal_moments(inertial.tensor)
        a, b, c = moments
        tol = tolerance(moments)
        if a > tol and a + b < c - tol:
            severity = impossible_severity(doc, name)
            effects = L.impossible(doc, name, K.BAD_TENSOR)
            yield Hit(
                inertial.inertia_element,
                f"link '{name}' has principal moments {fmt(a)}, {fmt(b)} and {fmt(c)} kg·m², "
                f"and {fmt(a)} + {fmt(b)} < {fmt(c)}" + L.welded_note(doc, name, severity, effects),
                severity=severity,
                effects=effects,
                repair=refit.repair_moments(doc, name, inertial),
            )
