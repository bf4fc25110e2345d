"""A link's mass is zero or negative.

## What it does
Reports `<mass value>` below zero and mass zero where a target loses the link.

A negative mass is always reported: an **error**, or a **warning** on a link
welded to its parent by a fixed joint when the only targets are Gazebo's and
the lumped body (the link plus the links fixed to it) still has a positive
mass and a valid inertia. Gazebo sums the welded link into that body before
anything checks it; MuJoCo, Drake and PyBullet keep (or check) the link on its
own, so for them it stays an error.

A zero mass is judged like a missing `<inertial>` (I001): for Gazebo, an error
when the link hangs from a movable joint and nothing fixed to it has mass, a
warning for a massless link kept apart from its parent, and info for a merged
link with geometry; for MuJoCo, an error on a moving link (MuJoCo infers a mass
from geometry only for links *without* `<inertial>`). A zero mass on a pure
frame under a fixed joint (a common way to write "this is only a frame") is not
reported, and a massless root link is I013's.

## Why is this bad?
- Negative mass is not physical. sdformat since 9.10.1, 12.7.2 and 13.5.0
  drops such a link like a massless one ("has a mass value of less than or
  equal to zero"); older sdformat keeps it and its DOM reports "A link named X
  has invalid inertia" (gz-math `MassMatrix3::IsValid`). Observed: MuJoCo 4.0
  refuses a moving link with negative mass ("mass and inertia of moving bodies
  must be larger than mjMINVAL") and silently ignores it on a welded link;
  Drake 1.51 warns ("condition 'mass > 0' failed") and substitutes a made-up
  inertia; PyBullet 3.2.7 and Pinocchio 4.1 load it as written, so the total
  mass and the centre of mass come out wrong (NaN when the masses cancel).
- Zero mass makes Gazebo drop the link, its joint and its subtree (silently
  before sdformat 9.10.1, 12.7.2 and 13.5.0; "has a mass value of less than or
  equal to zero" after), makes MuJoCo refuse a moving link, and gives Pinocchio
  a singular mass matrix (`aba` returns NaN).

## How to fix
Write the link's real mass in kilograms. A link that is only a frame should
hang from a `fixed` joint.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K
from urdflint.rules import lumping as L

from urdflint.engine.registry import Hit, rule
from urdflint.model import massless
from urdflint.model.bodies import bodies, impossible_severity
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.values import fmt


@rule(
    "I002",
    "non-positive-mass",
    Severity.ERROR,
    fix="Write the link's real mass in kilograms.",
    effects={"negative": K.NEGATIVE_MASS, "zero": K.ZERO_MASS},
)
def check(doc: Document) -> Iterator[Hit]:
    for name, inertial in bodies(doc).inertials.items():
        if inertial is None or inertial.mass is None or inertial.mass > 0:
            continue
        if inertial.mass < 0:
            severity = impossible_severity(doc, name)
            message = f"link '{name}' has mass {fmt(inertial.mass)} kg"
            message += L.welded_note(doc, name, severity)
            yield Hit(
                inertial.mass_element,
                message,
                attribute="value",
                severity=severity,
                variant="negative",
                effects=L.impossible(doc, name, K.NEGATIVE_MASS),
            )
            continue
        verdict = massless.verdict(doc, name)
        if verdict is not None:
            yield Hit(
                inertial.mass_element,
                f"link '{name}' has mass 0 kg, so {verdict.consequence}",
                severity=verdict.severity,
                attribute="value",
                effects=massless.effects(doc, name, declared=True),
                variant="zero",
            )
