"""An engine named by `--confirm` built a link with another mass or inertia than the URDF's.

## What it does
Compares each link's `<mass>` and the principal moments of its `<inertia>` (about its
centre of mass) with the body each engine built: MuJoCo's `body_mass` and
`body_inertia`, PyBullet's `getDynamicsInfo` mass and local inertia diagonal (loaded with
`URDF_USE_INERTIA_FROM_FILE`; without it PyBullet computes every inertia from the
collision shapes), Drake's `default_mass` and the principal moments of
`default_rotational_inertia`, Pinocchio's `model.inertias`. A difference of more than
1e-4 (relative) is reported on the link's `<inertial>`, or on the `<link>` when it has
none. A link without `<inertial>` counts as mass 0 and zero inertia.

Only links on a moving joint are compared (a fixed base has no dynamics). MuJoCo
(`fusestatic`) and Pinocchio merge a link on a `fixed` joint into its parent, so for
them a link with such a child is not compared either.

sdformat (Gazebo's URDF converter) lumps each link on a `fixed` joint into its parent
too, and its link then carries the combined mass and inertia. For sdformat each link on
a moving joint is compared with that combination, worked out from the file (masses
summed, inertias moved to the common centre of mass with the parallel-axis theorem, as
sdformat's `ReduceInertialToParent` does), so a lumped body is checked rather than
skipped; the message then names the links it combines. sdformat 12.3 never substitutes
an inertia: it refuses a link whose (combined) inertia is invalid, "A link named ... has
invalid inertia." (E001), for a negative mass or moment, a tensor that is not positive
definite or moments that break the triangle inequality; and it drops a link without mass
(E002). So an E004 for sdformat means its lumping disagrees with the file.

Observed with the engines this was written against:

- negative mass (`-1`, I002): PyBullet 3.2.7 and Pinocchio 4.1 keep it (not reported:
  it is what the file says); Drake 1.51 warns (E006) and uses mass 1 kg with principal
  moments 0.00154 kg·m²; MuJoCo 4.0 refuses the model (E001).
- moments that violate the triangle inequality (`ixx=1 iyy=1 izz=5`, I005): PyBullet
  warns and uses a zero inertia; Drake warns and uses mass 1 kg with principal moments
  0.00154 kg·m²; Pinocchio keeps the tensor; MuJoCo refuses the model (E001).
- no `<inertial>` on a moving link (I001): PyBullet uses mass 1 kg and unit inertia
  (with a warning, E006); Drake and Pinocchio use mass 0 (not reported: the file gives
  none); MuJoCo refuses the model (E001).

Without `--confirm` E004 does nothing.

## Why is this bad?
The simulated link is not the one described: the engine quietly substituted its own
mass or inertia, so the robot's dynamics (and any controller tuned on them) differ from
engine to engine and from the real robot.

## How to fix
Give the link an `<inertial>` with a positive mass and a physically valid inertia
tensor (principal moments that satisfy the triangle inequality), computed from its
geometry or CAD model.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from urdflint.rules.engines.common import label, outcomes

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import bodies
from urdflint.model.document import Document, Link
from urdflint.model.finding import Severity
from urdflint.model.inertia import eigenvalues as principal
from urdflint.model.values import parse_number

TOLERANCE = 1e-4  # sdformat lumps in floats: 1e-6 flagged identical tiny tensors
LUMPING = ("mujoco", "pinocchio")  # engines that merge fixed-joint links into the parent
TENSOR = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


def declared(link: Link) -> tuple[float, tuple[float, ...]] | None:
    """The link's mass and principal moments (ascending); ``None`` when malformed."""
    inertial = link.inertial
    if inertial is None:
        return 0.0, (0.0, 0.0, 0.0)
    mass = inertial.find("mass")
    inertia = inertial.find("inertia")
    value = parse_number(mass.get("value")) if mass is not None else 0.0
    parts = [parse_number(inertia.get(k, "0")) if inertia is not None else 0.0 for k in TENSOR]
    if value is None or any(p is None for p in parts):
        return None
    return value, eigenvalues(*(float(p or 0.0) for p in parts))


def combined(doc: Document, link: Link) -> tuple[float, tuple[float, ...]] | None:
    """The mass and principal moments of ``link`` with every link sdformat lumps into it;
    ``None`` when one of them is malformed or the total mass is not positive."""
    found = bodies(doc).inertia(link.name or "")
    return None if found is None else (found[0], tuple(principal(found[2])))


def lumps(doc: Document, link: Link) -> list[str]:
    """The other links sdformat merges into ``link``."""
    return [name for name, _, _ in bodies(doc).members(link.name or "")[1:]]


def eigenvalues(
    xx: float, xy: float, xz: float, yy: float, yz: float, zz: float
) -> tuple[float, ...]:
    """The eigenvalues of a symmetric 3x3 matrix, ascending (closed form, no numpy)."""
    off = xy * xy + xz * xz + yz * yz
    if off == 0.0:
        return tuple(sorted((xx, yy, zz)))
    q = (xx + yy + zz) / 3
    p = math.sqrt(((xx - q) ** 2 + (yy - q) ** 2 + (zz - q) ** 2 + 2 * off) / 6)
    b = [
        [(xx - q) / p, xy / p, xz / p],
        [xy / p, (yy - q) / p, yz / p],
        [xz / p, yz / p, (zz - q) / p],
    ]
    det = (b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1])
           - b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0])
           + b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0]))  # fmt: skip
    phi = math.acos(max(-1.0, min(1.0, det / 2))) / 3
    high = q + 2 * p * math.cos(phi)
    low = q + 2 * p * math.cos(phi + 2 * math.pi / 3)
    return tuple(sorted((low, 3 * q - high - low, high)))


def differs(a: float, b: float, scale: float) -> bool:
    return abs(a - b) > TOLERANCE * max(abs(a), abs(b), scale)


def compared(doc: Document, engine: str) -> list[Link]:
    """The links whose built body is the URDF link alone."""
    moving = {j.child for j in doc.joints if j.type not in (None, "fixed")}
    fixed = {j.parent for j in doc.joints if j.type == "fixed"}
    return [
        link
        for link in doc.links
        if link.name in moving and not (engine in LUMPING and link.name in fixed)
    ]


def describe(mass: float, moments: tuple[float, ...]) -> str:
    if all(m == 1.0 for m in moments):
        return f"mass {mass:g} kg and unit inertia"
    return f"mass {mass:g} kg and principal moments {' '.join(f'{m:.3g}' for m in moments)}"


@rule(
    "E004",
    "engine-replaced-inertia",
    Severity.WARNING,
    fix="Give the link a positive mass and a physically valid inertia tensor.",
)
def check(doc: Document) -> Iterator[Hit]:
    for outcome in outcomes(doc):
        if not outcome.built:
            continue
        for link in compared(doc, outcome.engine):
            merged = lumps(doc, link) if outcome.engine == "sdformat" else []
            wanted = combined(doc, link) if merged else declared(link)
            built = outcome.inertias.get(link.name or "")
            if wanted is None or built is None:
                continue
            scale = max([abs(m) for m in wanted[1] + built[1]] + [1e-12])
            mass_differs = differs(built[0], wanted[0], 1e-12)
            if not mass_differs and not any(
                differs(a, b, scale) for a, b in zip(sorted(built[1]), wanted[1], strict=True)
            ):
                continue
            given = "none" if link.inertial is None and not merged else describe(*wanted)
            if merged:
                given += f" with {', '.join(repr(m) for m in merged)} lumped in"
            yield Hit(
                link.inertial if link.inertial is not None else link.element,
                f"{label(outcome.engine)} uses {describe(*built)} for link {link.name!r} "
                f"(the URDF gives {given})",
                engine=outcome.engine,
            )
