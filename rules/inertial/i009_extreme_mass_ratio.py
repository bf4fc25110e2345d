"""A movable joint connects two bodies whose masses differ more than 1000-fold.

## What it does
For every movable joint, compares the mass of the body on each side (a link
plus the links fixed to it, as Gazebo, Pinocchio and MuJoCo lump them) and
reports a ratio above `max-ratio` (default 1000), in either direction: a heavy
body on a very light one, or a very light body on a heavy one.

## Why is this bad?
Maximal-coordinate engines, whose joints are constraints solved iteratively
(ODE in Gazebo Classic, Bullet's rigid bodies, PhysX), converge badly on
ill-conditioned systems: a 50 kg base driving a 5 g link through a joint gives
jitter, joints that drift apart or explode, and small time steps for nothing.
Engines in joint coordinates (MuJoCo, Drake, Bullet's multibodies, Pinocchio)
keep the joints exact, but their mass matrix is as ill-conditioned and their
contact solvers suffer the same way. A ratio like this
is also a frequent symptom of a unit slip (grams written as kilograms) or of a
placeholder mass on a small link.

## How to fix
Check both masses (kg). If a tiny link is only a frame, make its joint `fixed`
so that it is lumped into its parent; if a tiny moving part is real, consider
merging it with a neighbour or giving the joint more damping/armature. Raise
the threshold if needed:

```toml
[rules.I009]
max-ratio = 5000
```
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import GAZEBO_MASSLESS, MOVABLE, bodies
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.inertia import times
from urdflint.model.values import fmt


@rule(
    "I009",
    "extreme-mass-ratio",
    Severity.WARNING,
    fix="Check both masses (kg); make a frame-only link's joint fixed.",
    options={"max-ratio": 1000.0},
)
def check(doc: Document, opts: dict[str, Any]) -> Iterator[Hit]:
    limit = float(opts["max-ratio"])
    b = bodies(doc)
    for joint in doc.joints:
        if (
            joint.type not in MOVABLE
            or joint.parent not in doc.link_map
            or joint.child not in doc.link_map
        ):
            continue
        parent = b.body_of(joint.parent)  # type: ignore[arg-type]
        child = joint.child
        outer, inner = b.mass(parent), b.mass(child)  # type: ignore[arg-type]
        if outer is None or inner is None or min(outer, inner) <= GAZEBO_MASSLESS:
            continue
        ratio = max(outer / inner, inner / outer)
        if ratio > limit:
            yield Hit(
                joint.element,
                f"joint '{joint.name}' moves '{child}' ({fmt(inner)} kg) against '{parent}' "
                f"({fmt(outer)} kg), a mass ratio of {times(ratio)}",
            )
