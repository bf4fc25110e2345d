"""The full inertia tensor, products of inertia included, is not positive definite.

## What it does
For tensors whose diagonal is positive (I003 covers the others), computes the
principal moments (the eigenvalues of the full 3×3 tensor) and reports:

- a negative principal moment (below -1e-6 × the largest), always;
- a zero principal moment (within 1e-6 × the largest, or below 1e-15 kg·m²,
  MuJoCo's mjMINVAL), unless the body engines simulate (the link plus the links
  fixed to it) has a valid inertia anyway, or the link carries under 1% of that
  body's mass (then the heavier links are the ones reported).

## Why is this bad?
Large products of inertia (`ixy`, `ixz`, `iyz`) can make a tensor with a
positive diagonal non-physical. sdformat (gz-math `IsNearPositive`) rejects it
("A link named X has invalid inertia"), MuJoCo refuses it ("positive
eigenvalues"), Drake substitutes a made-up inertia with a warning, and PyBullet
zeroes it when told to read the file's inertia. Pinocchio loads it as it is and
the dynamics become meaningless. A typical cause is a tensor exported about the
wrong point or in the wrong frame, or with the products' signs flipped.

## How to fix
Re-export the tensor about the centre of mass, in the `<inertial><origin>`
frame. Check the sign convention: URDF's `ixy` is the tensor entry, the negated
product integral (some CAD tools print the product `∫xy dm` instead).
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
    "I004",
    "inertia-not-positive-definite",
    Severity.ERROR,
    fix="Re-export the tensor about the centre of mass, in the inertial origin frame.",
)
def check(doc: Document) -> Iterator[Hit]:
    b = bodies(doc)
    for name, inertial in b.inertials.items():
        if inertial is None or inertial.tensor is None or min(inertial.tensor[:3]) <= 0:
            continue
        moments = principal_moments(inertial.tensor)
        tol = tolerance(moments)
        listed = ", ".join(fmt(m) for m in moments)
        if moments[0] < -tol:
            yield Hit(
                inertial.inertia_element,
                f"link '{name}' has an inertia tensor that is not positive definite "
                f"(principal moments {listed} kg·m²)",
            )
        elif moments[0] <= tol and not (inertial.mass and inertial.mass > 0 and b.excused(name)):
            yield Hit(
                inertial.inertia_element,
                f"link '{name}' has a singular inertia tensor (principal moments {listed} kg·m²)",
            )
