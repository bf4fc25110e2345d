"""The inertia is far (10× or more) from that of the link's collision primitive at the same mass.

## What it does
For a link whose only `<collision>` is a box, cylinder, sphere or capsule,
computes the inertia of that solid at the declared mass and compares the sum
of the principal moments (the trace, which does not depend on orientation and
is not fooled by a thin rod's near-zero moment) with the declared tensor's.
A ratio beyond `max-ratio` (default 10) either way is reported.

Links with meshes or several collisions, invalid tensors (I003–I005) and
sensor frames that are negligible next to the body they are fixed to are
skipped.

## Why is this bad?
Unit slips are the usual cause: a tensor in g·mm² or kg·mm² is 10⁶× too large,
one in kg·cm² 10⁴×, a mass in grams 1000×. Every engine accepts such values
without a word (Gazebo, MuJoCo, Drake, PyBullet, Pinocchio), and the link then
behaves like a flywheel or like a feather: sluggish joints, controllers that
need absurd gains, or jitter and explosions.

## How to fix
Check the units of the tensor (kg·m²) and of the mass (kg). If the collision
shape is only a rough stand-in, compute the tensor from the real geometry, or
raise `max-ratio` for this rule:

```toml
[rules.I007]
max-ratio = 20
```
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

from urdflint.document import Document
from urdflint.finding import Severity
from urdflint.geometry import shapes
from urdflint.inertia import PLACEHOLDER, bodies, judge, primitive_moments, principal_moments, times
from urdflint.registry import Hit, rule
from urdflint.values import fmt

MAX_DENSITY = 1e5  # kg/m^3, five times osmium's


@rule(
    "I007",
    "inertia-geometry-mismatch",
    Severity.WARNING,
    fix="Check the units (kg, kg·m²) and recompute the tensor from the geometry.",
    options={"max-ratio": 10.0},
)
def check(doc: Document, opts: dict[str, Any]) -> Iterator[Hit]:
    limit = float(opts["max-ratio"])
    b = bodies(doc)
    for name, inertial in b.inertials.items():
        if inertial is None or inertial.tensor is None or not inertial.mass or inertial.mass <= 0:
            continue
        link = doc.link_map[name]
        found = shapes(link.element, "collision")
        if len(link.collisions) != 1 or len(found) != 1:
            continue
        shape = found[0]
        expected = primitive_moments(shape, inertial.mass)
        declared = principal_moments(inertial.tensor)
        if expected is None or judge(declared) != "valid" or inertial.tensor == PLACEHOLDER:
            continue  # invalid tensors are I003-I005's, the tutorial's placeholder I006's
        ratio = sum(declared) / sum(expected)
        if ratio > limit and inertial.mass / volume(shape) > MAX_DENSITY:
            continue  # a token collision (a 1 mm sphere), not the body's shape
        if (ratio > limit or ratio < 1 / limit) and not b.negligible(name):
            factor, way = (ratio, "more") if ratio > 1 else (1 / ratio, "less")
            yield Hit(
                inertial.inertia_element,
                f"link '{name}' has {times(factor)}× {way} inertia than a solid {_describe(shape)} "
                f"of {fmt(inertial.mass)} kg (moments summing to {fmt(sum(declared))} instead of "
                f"{fmt(sum(expected))} kg·m²)",
            )


def volume(shape: Any) -> float:
    r, h = shape.radius or 0.0, shape.length or 0.0
    if shape.kind == "box":
        return shape.size[0] * shape.size[1] * shape.size[2]
    if shape.kind == "sphere":
        return 4 / 3 * math.pi * r**3
    return math.pi * r * r * h + (4 / 3 * math.pi * r**3 if shape.kind == "capsule" else 0.0)


def _describe(shape: Any) -> str:
    if shape.kind == "box":
        return "box " + " × ".join(fmt(v) for v in shape.size) + " m"
    if shape.kind == "sphere":
        return f"sphere of radius {fmt(shape.radius)} m"
    return f"{shape.kind} of radius {fmt(shape.radius)} m and length {fmt(shape.length)} m"
