"""An engine named by `--confirm` built the model without one of its links.

## What it does
Compares the links of the URDF that have a non-zero `<mass>`, or a parent joint, with
what each engine built: MuJoCo's bodies, PyBullet's links (the base and each joint's
child link), Drake's bodies (without its world body), Pinocchio's `BODY` frames and the
links of the model sdformat converted. A link that is not there is reported on its
`<link>`: its mass is lost, or (a link without mass) its joint went with it. For example
Drake makes a link named `world` its world body and ignores that link's `<inertial>`
(with a warning, E006); so does sdformat, silently.

MuJoCo's URDF import fuses bodies welded to their parent (`fusestatic`, the default
for URDF): a link on a `fixed` joint, or the root link, becomes part of its parent and
is not reported. Only the links on moving joints are compared for MuJoCo.

sdformat (Gazebo's URDF converter, `sdf::Root::Load`) lumps every link on a `fixed`
joint into its parent (unless the joint is kept by `<preserveFixedJoint>` or
`<disableFixedJointLumping>`, or the parent is `world`): its mass and geometry move into
the parent's link, and that is not reported. A lumped link is reported only when the
link it was lumped into is missing too. What sdformat 12.3 really drops, without a word
on the console: a link without `<inertial>` or with a zero mass (within 1e-6) that is not
lumped, together with its joint and every link below it. Each of them is reported.

Without `--confirm` E002 does nothing.

## Why is this bad?
The link's mass and inertia are gone, or were added to another body in a way the file
does not say: the simulated robot is lighter, or balanced differently, than the one
described, and controllers tuned on it misbehave on the real one. A link dropped with its
joint takes a degree of freedom, and what hangs below it, out of the simulation.

## How to fix
Connect the link to the tree with a joint the engine supports, or remove it if it is
not meant to be part of the robot; give a link on a moving joint an `<inertial>` with a
positive mass (sdformat). E006 and the static S and I rules often say why the engine
left it out.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from urdflint.rules.engines.common import label, outcomes

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import bodies
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


def lumped(doc: Document, name: str, kept: set[str]) -> bool:
    """sdformat merged link ``name`` into a link it kept (fixed-joint lumping)."""
    found = bodies(doc)
    return found.merged(name) and found.body_of(name) in kept


def lost(doc: Document, outcome: Any, link: Link) -> str | None:
    """What the engine lost with link ``link`` (``None``: it is there, or nothing is lost)."""
    name, engine, kept = link.name, outcome.engine, set(outcome.bodies)
    if name is None or name in kept:
        return None
    if engine == "mujoco" and not moving(doc, name):
        return None  # fused into its parent body (fusestatic), mass included
    if engine == "sdformat" and lumped(doc, name, kept):
        return None  # lumped into its parent link (fixed-joint reduction), mass included
    weight = mass(link)
    if weight is not None:
        return f"its {weight:g} kg are not in the model"
    joint = doc.graph.parent_joint(name)
    if joint is None or joint.name is None or joint.name in outcome.joints:
        return None
    return f"it has no mass, and its joint {joint.name!r} is not in the model either"


@rule(
    "E002",
    "engine-dropped-link",
    Severity.ERROR,
    fix="Give the link a mass and attach it with a joint the engine supports, or remove it.",
)
def check(doc: Document) -> Iterator[Hit]:
    for outcome in outcomes(doc):
        if not outcome.built:
            continue
        for link in doc.links:
            why = lost(doc, outcome, link)
            if why is not None:
                yield Hit(
                    link.element,
                    f"{label(outcome.engine)} built no body for link {link.name!r}: {why}",
                    engine=outcome.engine,
                )
