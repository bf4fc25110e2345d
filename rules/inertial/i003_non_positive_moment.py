"""A diagonal moment of inertia (`ixx`, `iyy` or `izz`) is zero or negative.

## What it does
Reports links whose `<inertia>` has `ixx`, `iyy` or `izz` at or below zero:

- a negative moment, or zeros that make the tensor impossible (for example
  `ixx > 0` with `iyy = izz = 0` breaks the triangle inequality), always;
  values within 1e-15 kg·m² of zero count as rounding noise;
- zeros that describe a possible but degenerate body (a point mass, a thin
  rod) when a selected target refuses them (MuJoCo: a rod even on a welded link,
  since it checks every body before fusing welded ones; a point mass on a moving
  link), or when the rigid body that engines simulate (the link plus the links
  fixed to it) is left without a valid inertia and the link carries at least 1%
  of that body's mass, or when the link's own mass is negative (I002 reports the
  mass, this rule the tensor: both problems in one run).

Impossible tensors are an **error**, or a **warning** on a link welded by a
fixed joint when the only targets are Gazebo's and the lumped body is still
valid: Gazebo sums the welded link into that body before checking it. MuJoCo
checks every link first, and Drake and PyBullet keep welded links as bodies, so
for them it stays an error. Links without mass (I001, I002) are not judged for
zeros, and a point mass on a frame fixed to a body with a real inertia (a tool
or sensor frame) is accepted: Gazebo, Pinocchio, MuJoCo and Drake load it. Zeros
that keep A + B >= C are loaded as written by sdformat, Drake and PyBullet
(observed), so the effects line names MuJoCo alone as refusing.

## Why is this bad?
The Gazebo tutorial warns that a zero principal moment "could lead to infinite
acceleration under any finite torque application". sdformat's DOM (gz-math
`MassMatrix3::IsValid`) reports negative moments and triangle violations ("A
link named X has invalid inertia"). Observed with a moving link: MuJoCo 4.0
refuses any zero moment ("inertia must have positive eigenvalues", or "mass and
inertia of moving bodies must be larger than mjMINVAL" for an all-zero tensor);
Drake 1.51 replaces an impossible tensor with a made-up one (with a warning)
but accepts zeros; PyBullet 3.2.7 with `URDF_USE_INERTIA_FROM_FILE` prints "Bad
inertia tensor properties, setting inertia to zero" for impossible tensors and
keeps zeros as written; Pinocchio loads everything as written.

## How to fix
Use the tensor computed by your CAD tool, or the formula of a matching
primitive (a solid box of sides x, y, z: `ixx = m (y² + z²) / 12`, and so on).
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K
from urdflint.rules import lumping as L

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import bodies, impossible_severity
from urdflint.model.document import Document
from urdflint.model.effects import single
from urdflint.model.finding import Severity
from urdflint.model.inertia import COMPONENTS, ZERO_MOMENT, judge, principal_moments
from urdflint.model.values import fmt


@rule(
    "I003",
    "non-positive-moment",
    Severity.ERROR,
    fix="Use the real inertia tensor (CAD, or the formula of a matching primitive).",
    effects=single(K.BAD_TENSOR),
)
def check(doc: Document) -> Iterator[Hit]:
    b = bodies(doc)
    for name, inertial in b.inertials.items():
        if inertial is None or inertial.tensor is None:
            continue
        bad = [(k, v) for k, v in zip(COMPONENTS[:3], inertial.tensor[:3], strict=True) if v <= 0]
        if not bad:
            continue
        negative = any(v < -ZERO_MOMENT for _, v in bad)
        impossible = negative or judge(principal_moments(inertial.tensor)) == "impossible"
        if impossible:
            severity = impossible_severity(doc, name)
            effects = L.impossible(doc, name, K.BAD_TENSOR)
        else:  # a point mass or a rod
            found = L.degenerate_severity(doc, name, inertial.tensor)
            if found is None:
                continue
            severity, effects = found, L.degenerate(doc, name, inertial.tensor)
        parts = [f"{k} = {fmt(v)}" for k, v in bad]
        listed = parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + " and " + parts[-1]
        message = f"link '{name}' has {listed} kg·m²" + L.welded_note(doc, name, severity, effects)
        yield Hit(inertial.inertia_element, message, severity=severity, effects=effects)
