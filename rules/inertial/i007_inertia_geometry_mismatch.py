"""The inertia is far (10× or more) from that of the link's collision shape at the same mass.

## What it does
For a link whose only `<collision>` is a box, cylinder, sphere, capsule or
mesh, computes the inertia of that solid at the declared mass and compares
the sum of the principal moments (the trace, which does not depend on
orientation and is not fooled by a thin rod's near-zero moment) with the
declared tensor's. A ratio beyond `max-ratio` (default 10) either way is
reported.

A mesh is loaded with trimesh (when installed) after its `scale`. When it is
watertight and consistently oriented it is taken as a solid of uniform
density; otherwise its convex hull is, and the message says so. Meshes that
C004-C006 report (missing, unreadable, not in metres) are skipped, since
their own finding explains the mismatch.

Links with several collisions, invalid tensors (I003–I005), collision shapes
implausibly dense for the mass (a token 1 mm sphere, a small pad standing for
a large part) and sensor frames negligible next to the body they are fixed
to are skipped.

## Why is this bad?
Unit slips are the usual cause: a tensor in g·mm² or kg·mm² is 10⁶× too large,
one in kg·cm² 10⁴×, a mass in grams 1000×. Every engine accepts such values
without a word (Gazebo, MuJoCo, Drake, PyBullet, Pinocchio), and the link then
behaves like a flywheel or like a feather: sluggish joints, controllers that
need absurd gains, or jitter and explosions.

A factor of 10 is deliberately loose. A mesh-based estimate is crude: CAD
exports are often hollow shells (whose convex hull over-fills them), a link's
mass is rarely uniform (motors, gearboxes), and a collision mesh may cover
only part of the link. Those errors stay within a factor of about 3; unit
slips are factors of 100 to a million.

## How to fix
Check the units of the tensor (kg·m²) and of the mass (kg). If the collision
shape is only a rough stand-in, compute the tensor from the real geometry, or
raise `max-ratio` for this rule:

```toml
[rules.I007]
max-ratio = 20
```

`urdflint fix --unsafe-fixes` writes the tensor of the collision shape at the
declared mass (about its centroid in the link's axes, so the origin's `rpy`
becomes `0 0 0`). The declared centre of mass is kept, since the rule compares
only the moments. Use it when the shape is a fair stand-in for the part.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

from urdflint.rules.inertial import refit

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import bodies
from urdflint.model.document import Document
from urdflint.model.edits import Repair
from urdflint.model.finding import Severity
from urdflint.model.geometry import shapes
from urdflint.model.inertia import (
    PLACEHOLDER,
    judge,
    meshes_readable,
    primitive_moments,
    principal_moments,
    times,
)
from urdflint.model.values import fmt

MAX_DENSITY = 1e5  # kg/m^3, five times osmium's


@rule(
    "I007",
    "inertia-geometry-mismatch",
    Severity.WARNING,
    fix="Check the units (kg, kg·m²) and recompute the tensor from the geometry.",
    options={"max-ratio": 10.0},
    fixable="unsafe",
)
def check(doc: Document, opts: dict[str, Any]) -> Iterator[Hit]:
    limit = float(opts["max-ratio"])
    b = bodies(doc)
    readable: bool | None = None
    for name, inertial in b.inertials.items():
        if inertial is None or inertial.tensor is None or not inertial.mass or inertial.mass <= 0:
            continue
        link = doc.link_map[name]
        found = shapes(link.element, "collision")
        if len(link.collisions) != 1 or len(found) != 1:
            continue
        shape = found[0]
        declared = principal_moments(inertial.tensor)
        if judge(declared) != "valid" or inertial.tensor == PLACEHOLDER:
            continue  # invalid tensors are I003-I005's, the tutorial's placeholder I006's
        if shape.kind == "mesh":
            if readable is None:
                readable = meshes_readable()
            solid = _mesh_solid(doc, shape, inertial.mass) if readable else None
            if solid is None:
                continue
            expected_sum, density_volume, what, note = solid
        else:
            expected = primitive_moments(shape, inertial.mass)
            if expected is None:
                continue
            expected_sum, density_volume, what, note = (
                sum(expected),
                volume(shape),
                f"a solid {_describe(shape)}",
                "",
            )
        ratio = sum(declared) / expected_sum
        if ratio > limit and inertial.mass / density_volume > MAX_DENSITY:
            continue  # a token collision (a 1 mm sphere), not the body's shape
        if (ratio > limit or ratio < 1 / limit) and not b.negligible(name):
            factor, way = (ratio, "more") if ratio > 1 else (1 / ratio, "less")
            yield Hit(
                inertial.inertia_element,
                f"link '{name}' has {times(factor)}× {way} inertia than {what} "
                f"of {fmt(inertial.mass)} kg (moments summing to {fmt(sum(declared))} instead of "
                f"{fmt(expected_sum)} kg·m²{note})",
                repair=_repair(doc, name, inertial),
            )


def _repair(doc: Document, name: str, inertial: Any) -> Repair | None:
    """The tensor of the collision shape at the declared mass (none without a usable one)."""
    estimate = refit.estimate_at_mass(doc, name, inertial)
    if estimate is None:
        return None
    text, operations = refit.refit(inertial, estimate, "I007 compares only the moments")
    return Repair("unsafe", text, tuple(operations)) if operations else None


def _mesh_solid(doc: Document, shape: Any, mass: float) -> tuple[float, float, str, str] | None:
    """``(trace at mass, volume, description, note)`` of a collision mesh read as a solid."""
    from urdflint.sources.meshes import MeshRef, load, suspicious_size

    info = load(doc, MeshRef(None, "collision", shape))
    if info is None or info.error is not None or suspicious_size(info):
        return None  # C004, C005 and C006 report those
    solid = info.solid()
    if solid is None:
        return None
    tensor = solid.inertia(mass)
    trace = tensor[0][0] + tensor[1][1] + tensor[2][2]
    if not trace > 0:
        return None
    uri = (shape.filename or "").strip()
    if solid.kind == "mesh":
        return trace, solid.volume, f"its collision mesh {uri!r} as a solid", ""
    note = "; the mesh is not watertight, so its convex hull stands in"
    return trace, solid.volume, f"the convex hull of its collision mesh {uri!r}", note


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
