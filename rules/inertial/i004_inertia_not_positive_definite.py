"""The full inertia tensor, products of inertia included, is not positive definite.

## What it does
For tensors whose diagonal is positive (I003 covers the others), computes the
principal moments (the eigenvalues of the full 3×3 tensor) and reports:

- a negative principal moment (below -1e-6 × the largest), always: an
  **error**, or a **warning** on a link welded by a fixed joint when the only
  targets are Gazebo's and the lumped body (the link plus the links fixed to
  it) is still valid, since Gazebo sums the welded link into that body before
  checking it (MuJoCo checks every link first; Drake and PyBullet keep welded
  links as bodies);
- a zero principal moment (within 1e-6 × the largest, or below 1e-15 kg·m²,
  MuJoCo's mjMINVAL), possible but degenerate, unless the link has no mass, or,
  when no selected target refuses it, the body engines simulate has a valid
  inertia anyway or the link carries under 1% of that body's mass (then the
  heavier links are the ones reported). MuJoCo refuses it on a welded link too:
  it checks every body before fusing welded ones (observed on anymal_c's hatch,
  whose moments and products are all 0.001: principal moments 0, 0, 0.003).

## Why is this bad?
Large products of inertia (`ixy`, `ixz`, `iyz`) can make a tensor with a
positive diagonal non-physical. sdformat's DOM (gz-math `MassMatrix3::IsValid`)
reports it ("A link named X has invalid inertia"). Observed on a moving link:
MuJoCo 4.0 refuses both a negative and a zero principal moment ("inertia must
have positive eigenvalues"); Drake 1.51 warns that a negative one "did not pass
the test CouldBePhysicallyValid()" and substitutes a made-up inertia (a zero one
it accepts; on a welded link both only warn); PyBullet 3.2.7 with
`URDF_USE_INERTIA_FROM_FILE` sets a tensor with a negative principal moment to
zero ("Bad inertia tensor properties"). Pinocchio
loads it as it is and the dynamics become meaningless. A typical cause is a
tensor exported about the wrong point or in the wrong frame, or with the
products' signs flipped.

## How to fix
Re-export the tensor about the centre of mass, in the `<inertial><origin>`
frame. Check the sign convention: URDF's `ixy` is the tensor entry, the negated
product integral (some CAD tools print the product `∫xy dm` instead).

`urdflint fix --unsafe-fixes` writes the tensor of the link's collision
geometry at the declared mass, as for I005 (about its centroid in the link's
axes; the declared centre of mass is kept). A link without usable collision
geometry gets MuJoCo's balance when the principal moments also break A + B >= C
(all three set to their average, which keeps their sum and loses the axes); a
singular tensor that keeps the inequality (a rod) has no automatic fix there.
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
    "I004",
    "inertia-not-positive-definite",
    Severity.ERROR,
    fix="Re-export the tensor about the centre of mass, in the inertial origin frame.",
    effects=single(K.BAD_TENSOR),
    fixable="unsafe",
)
def check(doc: Document) -> Iterator[Hit]:
    b = bodies(doc)
    for name, inertial in b.inertials.items():
        if inertial is None or inertial.tensor is None or min(inertial.tensor[:3]) <= 0:
            continue
        moments = principal_moments(inertial.tensor)
        tol = tolerance(moments)
        listed = ", ".join(fmt(m) for m in moments) if moments[0] <= tol else ""
        if moments[0] < -tol:
            severity = impossible_severity(doc, name)
            effects = L.impossible(doc, name, K.BAD_TENSOR)
            yield Hit(
                inertial.inertia_element,
                f"link '{name}' has an inertia tensor that is not positive definite "
                f"(principal moments {listed} kg·m²)" + L.welded_note(doc, name, severity, effects),
                severity=severity,
                effects=effects,
                repair=refit.repair_moments(doc, name, inertial),
            )
        elif moments[0] <= tol:
            severity = L.degenerate_severity(doc, name, inertial.tensor)
            if severity is None:
                continue
            effects = L.degenerate(doc, name, inertial.tensor)
            yield Hit(
                inertial.inertia_element,
                f"link '{name}' has a singular inertia tensor (principal moments {listed} kg·m²)"
                + L.welded_note(doc, name, severity, effects),
                severity=severity,
                effects=effects,
                repair=refit.repair_moments(doc, name, inertial),
            )
