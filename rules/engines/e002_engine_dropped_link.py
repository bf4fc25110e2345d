"""An engine named by `--confirm` built the model without a link that has mass.

## What it does
Compares the links of the URDF that have a non-zero `<mass>` with what each engine
built: MuJoCo's bodies, PyBullet's links (the base and each joint's child link),
Drake's bodies (without its world body) and Pinocchio's `BODY` frames. A link that is
not there is reported on its `<link>`. For example Drake makes a link named `world` its
world body and ignores that link's `<inertial>` (with a warning, E006).

MuJoCo's URDF import fuses bodies welded to their parent (`fusestatic`, the default
for URDF): a link on a `fixed` joint, or the root link, becomes part of its parent and
is not reported. Only the links on moving joints are compared for MuJoCo.

Without `--confirm` E002 does nothing.

## Why is this bad?
The link's mass and inertia are gone, or were added to another body in a way the file
does not say: the simulated robot is lighter, or balanced differently, than the one
described, and controllers tuned on it misbehave on the real one.

## How to fix
Connect the link to the tree with a joint the engine supports, or remove it if it is
not meant to be part of the robot. E006 and the static S rules often say why the
engine left it out.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.engines.common import label, outcomes

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, Link
from urdflint.model.finding import Severity
from urdflint.model.values import parse_number


def mass(link: Link) -> float | None:
    inertial = link.inertial
    element = inertial.find("mass") if inertial is not None else None
    value = parse_number(element.get("value") or "") if element is not None else None
    return value if value else None


def moving(doc: Document, name: str) -> bool:
    return any(j.child == name and j.type not in (None, "fixed") for j in doc.joints)


@rule(
    "E002",
    "engine-dropped-link",
    Severity.ERROR,
    fix="Attach the link to the tree with a joint the engine supports, or remove it.",
)
def check(doc: Document) -> Iterator[Hit]:
    for outcome in outcomes(doc):
        if not outcome.built:
            continue
        kept = set(outcome.bodies)
        for link in doc.links:
            weight = mass(link)
            if link.name is None or link.name in kept or weight is None:
                continue
            if outcome.engine == "mujoco" and not moving(doc, link.name):
                continue  # fused into its parent body (fusestatic), mass included
            yield Hit(
                link.element,
                f"{label(outcome.engine)} built no body for link {link.name!r}: "
                f"its {weight:g} kg are not in the model",
            )
