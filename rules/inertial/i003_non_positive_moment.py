"""A diagonal moment of inertia (`ixx`, `iyy` or `izz`) is zero or negative.

## What it does
Reports links whose `<inertia>` has `ixx`, `iyy` or `izz` at or below zero:

- a negative moment always (no rigid body has one; values within 1e-15 kg·m²
  of zero count as rounding noise);
- a zero moment when the tensor is also impossible (for example `ixx > 0` with
  `iyy = izz = 0` breaks the triangle inequality), or when the rigid body that
  engines simulate (the link plus the links fixed to it) is left without a
  valid inertia and the link carries at least 1% of that body's mass.

Links without mass (I001, I002) are not judged here, and a point mass on a frame
fixed to a body with a real inertia (a tool or sensor frame) is accepted: Gazebo,
Pinocchio and MuJoCo lump it into that body.

## Why is this bad?
The Gazebo tutorial warns that a zero principal moment "could lead to infinite
acceleration under any finite torque application". sdformat (gz-math
`MassMatrix3::IsValid`) rejects negative moments and triangle violations ("A
link named X has invalid inertia"), MuJoCo refuses moving bodies whose inertia
is below mjMINVAL, Drake replaces the inertia with a made-up one, and PyBullet
(with `URDF_USE_INERTIA_FROM_FILE`) prints "Bad inertia tensor properties,
setting inertia to zero".

## How to fix
Use the tensor computed by your CAD tool, or the formula of a matching
primitive (a solid box of sides x, y, z: `ixx = m (y² + z²) / 12`, and so on).
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import bodies
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.inertia import COMPONENTS, ZERO_MOMENT, judge, principal_moments
from urdflint.model.values import fmt


@rule(
    "I003",
    "non-positive-moment",
    Severity.ERROR,
    fix="Use the real inertia tensor (CAD, or the formula of a matching primitive).",
)
def check(doc: Document) -> Iterator[Hit]:
    b = bodies(doc)
    for name, inertial in b.inertials.items():
        if inertial is None or inertial.tensor is None:
            continue
        bad = [(k, v) for k, v in zip(COMPONENTS[:3], inertial.tensor[:3], strict=True) if v <= 0]
        if not bad:
            continue
        if all(v >= -ZERO_MOMENT for _, v in bad):  # zeros (and rounding noise), no real negative
            if inertial.mass is None or inertial.mass <= 0:
                continue
            if judge(principal_moments(inertial.tensor)) != "impossible" and b.excused(name):
                continue
        parts = [f"{k} = {fmt(v)}" for k, v in bad]
        listed = parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + " and " + parts[-1]
        yield Hit(inertial.inertia_element, f"link '{name}' has {listed} kg·m²")
