"""How deep two placed collision shapes interpenetrate (the narrow phase of C013).

With ``coal`` (hpp-fcl, installed with Pinocchio) the depth is coal's signed distance
between the exact shapes: boxes, spheres, cylinders and capsules as such, meshes as their
convex hull (what MuJoCo, PyBullet and Drake collide with). Without coal a numpy
fallback is exact for sphere-sphere, sphere-box and box-box (the separating-axis test over
the 15 axes of two boxes: the smallest overlap is the penetration depth) and treats
cylinders, capsules and meshes as their oriented bounding boxes, which may overstate the
overlap: such a depth is marked ``approximate``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cache
from typing import Any

import numpy as np

EXACT_FALLBACK = frozenset({"box", "sphere"})


@dataclass(eq=False)
class Placed:
    """One ``<collision>`` placed in the world frame.

    ``rotation``/``center`` are the collision frame in the world; ``half`` the half sizes
    of its bounding box in that frame (about ``box_center``, also in that frame);
    ``points`` a mesh's convex-hull vertices in the collision frame.
    """

    link: str
    owner: Any  # the <collision> element
    kind: str  # box, sphere, cylinder, capsule, mesh
    rotation: np.ndarray
    center: np.ndarray
    half: np.ndarray
    radius: float = 0.0
    length: float = 0.0
    points: np.ndarray | None = None
    box_center: np.ndarray = field(default_factory=lambda: np.zeros(3))
    key: Any = None  # what identifies the mesh (one coal object per mesh and scale)

    @property
    def lo(self) -> np.ndarray:
        return self.world_box()[0]

    @property
    def hi(self) -> np.ndarray:
        return self.world_box()[1]

    def world_box(self) -> tuple[np.ndarray, np.ndarray]:
        """The world axis-aligned bounding box (exact for meshes: from the hull's points)."""
        if self.points is not None:
            world = self.points @ self.rotation.T + self.center
            return world.min(axis=0), world.max(axis=0)
        middle = self.rotation @ self.box_center + self.center
        reach = np.abs(self.rotation) @ self.half
        return middle - reach, middle + reach


@cache
def coal_available() -> bool:
    """Whether coal imports here (it is looked up, and imported, at most once per run)."""
    try:
        import coal  # noqa: F401
    except Exception:  # ImportError, or a broken binary wheel
        return False
    return True


class CoalDepth:
    """Penetration depths from coal, one coal geometry per placed shape (meshes shared)."""

    def __init__(self) -> None:
        import coal

        self.coal = coal
        self.request = coal.DistanceRequest()
        self.hulls: dict[Any, Any] = {}

    def geometry(self, shape: Placed) -> Any:
        coal = self.coal
        if shape.kind == "box":
            return coal.Box(*(2.0 * shape.half))
        if shape.kind == "sphere":
            return coal.Sphere(shape.radius)
        if shape.kind == "cylinder":
            return coal.Cylinder(shape.radius, shape.length)
        if shape.kind == "capsule":
            return coal.Capsule(shape.radius, shape.length)
        found = self.hulls.get(shape.key)
        if found is None:
            points = coal.StdVec_Vec3s()
            points.extend(list(np.asarray(shape.points, dtype=float)))
            found = self.hulls[shape.key] = coal.ConvexBase.convexHull(points, False, "")
        return found

    def __call__(self, a: Placed, b: Placed) -> tuple[float, bool]:
        coal = self.coal
        ta = coal.Transform3s(a.rotation, a.center)
        tb = coal.Transform3s(b.rotation, b.center)
        result = coal.DistanceResult()
        distance = coal.distance(self.geometry(a), ta, self.geometry(b), tb, self.request, result)
        return max(0.0, -float(distance)), False


def numpy_depth(a: Placed, b: Placed) -> tuple[float, bool]:
    """Penetration depth without coal, and whether it is approximate (a bounding box)."""
    approximate = a.kind not in EXACT_FALLBACK or b.kind not in EXACT_FALLBACK
    if a.kind == "sphere" and b.kind == "sphere":
        gap = float(np.linalg.norm(a.center - b.center))
        return max(0.0, a.radius + b.radius - gap), False
    if a.kind == "sphere":
        return _sphere_box(a, b), approximate
    if b.kind == "sphere":
        return _sphere_box(b, a), approximate
    return _box_box(a, b), approximate


def _box_frame(shape: Placed) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Centre, axes (columns) and half sizes of the shape's oriented bounding box."""
    center = shape.rotation @ shape.box_center + shape.center
    return center, shape.rotation, shape.half


def _sphere_box(sphere: Placed, box: Placed) -> float:
    center, axes, half = _box_frame(box)
    local = axes.T @ (sphere.center - center)
    outside = np.maximum(np.abs(local) - half, 0.0)
    if outside.any():
        return max(0.0, sphere.radius - float(np.linalg.norm(outside)))
    return sphere.radius + float(np.min(half - np.abs(local)))


def _box_box(a: Placed, b: Placed) -> float:
    """The smallest overlap of the two boxes' projections over the 15 separating axes."""
    ca, ra, ha = _box_frame(a)
    cb, rb, hb = _box_frame(b)
    axes = [ra[:, i] for i in range(3)] + [rb[:, i] for i in range(3)]
    for i in range(3):
        for j in range(3):
            cross = np.cross(ra[:, i], rb[:, j])
            norm = float(np.linalg.norm(cross))
            if norm > 1e-9:
                axes.append(cross / norm)
    depth = np.inf
    gap = cb - ca
    for axis in axes:
        reach = float(np.abs(ra.T @ axis) @ ha + np.abs(rb.T @ axis) @ hb)
        overlap = reach - abs(float(gap @ axis))
        if overlap <= 0:
            return 0.0
        depth = min(depth, overlap)
    return float(depth)


def depth_function() -> tuple[Callable[[Placed, Placed], tuple[float, bool]], str]:
    """The narrow phase of this run and its name (``coal`` or ``numpy``)."""
    if coal_available():
        return CoalDepth(), "coal"
    return numpy_depth, "numpy"
