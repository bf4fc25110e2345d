"""The inertia tensor is a placeholder: the tutorial's identity, or a copy on a very different mass.

## What it does
Reports two kinds of made-up tensors:

- the identity tensor (`ixx = iyy = izz = 1`, no products) on a link too small
  or too light to have it: a body whose moments sum to 3 kg·m² needs mass
  farther than √(1.5 / m) metres from its centre of mass, which is compared
  with the size of the link's primitive geometry (0.5 m when it has none);
- the very same tensor written on links whose masses differ more than tenfold
  (the tensor cannot be right for both).

Tensors of sensor and tool frames that are negligible next to the body they are
fixed to are not compared.

## Why is this bad?
The identity tensor is SDF's default `<inertia>`, and the ROS URDF tutorial
once advised it ("If unsure what to put, the identity matrix is a good
default"; answers.gazebosim.org, "The inertia matrix explained": "the identity
matrix is a particularly bad choice"), so it is copied into many robots. On a
5 cm, 100 g link it is off by more than 10,000×: the link reacts like a
flywheel, joints feel sluggish, controllers tuned in simulation fail on the
robot. Every engine loads it without a word, since it is a valid tensor. A
tensor pasted from another link is wrong by at least the mass ratio.

## How to fix
Compute each link's tensor from its geometry and mass (CAD, or the formula of
a matching primitive, or Drake's `fix_inertia`).

`urdflint fix --unsafe-fixes` writes the tensor of the link's collision
geometry at the declared mass (about its centroid in the link's axes, so the
origin's `rpy` becomes `0 0 0`; the declared centre of mass is kept). Links
without usable collision geometry get no fix.
"""

from __future__ import annotations

import math
import statistics
from collections.abc import Iterator

from urdflint.rules.inertial import refit

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import Bodies, bodies
from urdflint.model.document import Document
from urdflint.model.edits import Repair
from urdflint.model.finding import Severity
from urdflint.model.inertia import PLACEHOLDER, primitive_box, times
from urdflint.model.values import fmt

DEFAULT_SIZE = 0.5  # metres, when the link has no primitive geometry
MASS_RATIO = 10.0


@rule(
    "I006",
    "placeholder-inertia",
    Severity.WARNING,
    fix="Compute the tensor from the link's geometry and mass.",
    fixable="unsafe",
)
def check(doc: Document) -> Iterator[Hit]:
    b = bodies(doc)
    groups: dict[tuple[float, ...], list[tuple[str, float]]] = {}
    for name, inertial in b.inertials.items():
        if inertial is None or inertial.tensor is None or not inertial.mass or inertial.mass <= 0:
            continue
        if inertial.tensor == PLACEHOLDER:
            reach = math.sqrt(1.5 / inertial.mass)
            size = _size(doc, name, inertial.xyz)
            if reach > size:
                needed, spans = fmt(round(reach, 2)), fmt(round(size, 2))
                yield Hit(
                    inertial.inertia_element,
                    f"link '{name}' has the placeholder inertia ixx = iyy = izz = 1 kg·m², "
                    f"which at {fmt(inertial.mass)} kg needs mass at least {needed} m "
                    f"from the centre of mass, but the link reaches {spans} m",
                    repair=_repair(doc, name, "only the tensor is a placeholder"),
                )
                continue
        if any(inertial.tensor) and not b.negligible(name):
            groups.setdefault(inertial.tensor, []).append((name, inertial.mass))
    for members in groups.values():
        yield from _copies(b, members)


def _copies(b: Bodies, members: list[tuple[str, float]]) -> Iterator[Hit]:
    """Links whose mass is over 10x from the group's median (both links of a pair)."""
    if len(members) < 2:
        return
    median = statistics.median(m for _, m in members)
    typical = min(members, key=lambda m: abs(math.log(m[1] / median)))
    for name, mass in members:
        other, other_mass = (
            typical if len(members) > 2 else next(m for m in members if m[0] != name)
        )
        ratio = max(other_mass / mass, mass / other_mass)
        if ratio > MASS_RATIO and (
            len(members) == 2 or max(mass / median, median / mass) > MASS_RATIO
        ):
            inertial = b.inertials[name]
            assert inertial is not None
            yield Hit(
                inertial.inertia_element,
                f"link '{name}' ({fmt(mass)} kg) has the same inertia tensor as link '{other}' "
                f"({fmt(other_mass)} kg), whose mass is {times(ratio)}× "
                f"{'smaller' if other_mass < mass else 'larger'}",
                repair=_repair(b.doc, name, "only the tensor is a copy"),
            )


def _repair(doc: Document, name: str, kept: str) -> Repair | None:
    """The tensor of the link's collision geometry at its declared mass (none without one)."""
    inertial = bodies(doc).inertials[name]
    estimate = refit.estimate_at_mass(doc, name, inertial) if inertial is not None else None
    if inertial is None or estimate is None:
        return None
    text, operations = refit.refit(inertial, estimate, kept)
    return Repair("unsafe", text, tuple(operations)) if operations else None


def _size(doc: Document, name: str, com: tuple[float, ...] | None) -> float:
    """Farthest distance from the centre of mass to a corner of the link's primitive geometry."""
    link = doc.link_map[name].element
    box = primitive_box(link, ("collision",)) or primitive_box(link, ("visual",))
    if box is None or com is None:
        return DEFAULT_SIZE
    lo, hi = box
    return math.sqrt(sum(max(abs(lo[i] - com[i]), abs(hi[i] - com[i])) ** 2 for i in range(3)))
