"""Collision geometry of two links that overlaps at one configuration (C013).

Forward kinematics of the link frames at the zero configuration, or at ``expect.q``
(``--q JOINT=VALUE``; a mimic joint follows its leader: ``multiplier * leader + offset``);
every ``<collision>`` placed in the world (primitives as written, meshes as their convex
hull, read once through the run's mesh cache); a broad phase over the world bounding
boxes; the depth of each remaining pair from :mod:`urdflint.sources.self_collision_depth`.

Which link pairs are measured is the caller's choice (``keep``): C013 keeps those some
engine collides (:mod:`urdflint.sources.contact_filters`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from typing import TYPE_CHECKING, Any

import numpy as np

from urdflint.model.geometry import Shape, read_shape
from urdflint.model.values import vector
from urdflint.sources.self_collision_depth import Placed, depth_function

if TYPE_CHECKING:
    from urdflint.model.document import Document, Joint

MOVING = ("revolute", "continuous", "prismatic")
MAX_PAIRS = 5000  # candidate pairs measured exactly (a real robot has tens to hundreds)
CHUNK = 1 << 20  # box pairs the broad phase tests in one numpy expression


@dataclass(frozen=True, slots=True)
class Overlap:
    """Two links whose collision geometry interpenetrates by ``depth`` metres.

    ``first``/``second`` are in document order; ``element`` is the second link's
    ``<collision>`` of the deepest contact. ``approximate``: a bounding box stood in for a
    shape (no coal); ``mesh``: a convex hull stood in for a mesh.
    """

    first: str
    second: str
    depth: float
    element: Any
    approximate: bool
    mesh: bool


# -- configuration and forward kinematics ---------------------------------------------------


def joint_values(doc: Document) -> dict[str, float]:
    """Joint positions of ``expect.q`` (unknown and non-moving names are left out), with
    every mimic joint following its leader."""
    requested = {
        name: value
        for name, value in dict(doc.settings.expect.q).items()
        if name in doc.joint_map and doc.joint_map[name].type in MOVING
    }
    mimics: dict[str, tuple[str, float, float]] = {}
    for joint in doc.joints:
        mimic = joint.find("mimic")
        if joint.name is None or mimic is None or not mimic.get("joint"):
            continue
        multiplier = _number(mimic.get("multiplier"), 1.0)
        offset = _number(mimic.get("offset"), 0.0)
        mimics[joint.name] = (str(mimic.get("joint")), multiplier, offset)

    def position(name: str, depth: int = 0) -> float:
        if name in mimics and depth < 64:
            leader, multiplier, offset = mimics[name]
            return multiplier * position(leader, depth + 1) + offset
        return requested.get(name, 0.0)

    values = {k: v for k, v in requested.items() if k not in mimics}
    values.update({name: position(name) for name in mimics})
    return values


def _number(text: str | None, default: float) -> float:
    try:
        value = float(text) if text is not None else default
    except ValueError:
        return default
    return value if math.isfinite(value) else default


def transform(xyz: tuple[float, ...], rpy: tuple[float, ...]) -> np.ndarray:
    """The 4x4 transform of a URDF ``<origin>`` (fixed-axis roll, pitch, yaw)."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = (
        math.cos(r),
        math.sin(r),
        math.cos(p),
        math.sin(p),
        math.cos(y),
        math.sin(y),
    )
    x, y, z = xyz
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr, x],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr, y],
            [-sp, cp * sr, cp * cr, z],
            [0.0, 0.0, 0.0, 1.0],
        ],
        dtype=float,
    )


def _motion(joint: Joint, value: float) -> np.ndarray:
    """The joint's own motion at ``value``: a rotation or a translation along its axis."""
    if value == 0.0 or joint.type not in MOVING:
        return _still()
    matrix = np.eye(4)
    axis = np.array(vector(joint.find("axis"), "xyz", 3, (1.0, 0.0, 0.0)) or (0.0, 0.0, 0.0))
    norm = float(np.linalg.norm(axis))
    if not norm > 0 or not math.isfinite(norm):
        return matrix
    axis = axis / norm
    if joint.type == "prismatic":
        matrix[:3, 3] = axis * value
        return matrix
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    matrix[:3, :3] = np.eye(3) + math.sin(value) * k + (1 - math.cos(value)) * (k @ k)
    return matrix


@cache
def _still() -> np.ndarray:
    """The motion of a joint at rest: the identity, shared and read-only."""
    identity = np.eye(4)
    identity.flags.writeable = False
    return identity


def link_poses(doc: Document, values: dict[str, float]) -> dict[str, np.ndarray]:
    """World transform of every link reachable from a root (each root at the origin)."""
    graph = doc.graph
    poses: dict[str, np.ndarray] = {}
    stack = [(root, np.eye(4)) for root in graph.roots]
    while stack:
        name, pose = stack.pop()
        if name in poses:
            continue  # a kinematic loop (S005): the first path wins
        poses[name] = pose
        for joint in graph.child_joints.get(name, []):
            origin = joint.find("origin")
            xyz = vector(origin, "xyz", 3, (0.0, 0.0, 0.0)) or (0.0, 0.0, 0.0)
            rpy = vector(origin, "rpy", 3, (0.0, 0.0, 0.0)) or (0.0, 0.0, 0.0)
            local = transform(xyz, rpy) @ _motion(joint, values.get(joint.name or "", 0.0))
            if joint.child is not None and np.isfinite(local).all():
                stack.append((joint.child, pose @ local))
    return poses


# -- shapes in the world -------------------------------------------------------------------


def place(doc: Document, poses: dict[str, np.ndarray], hulls: dict[Any, Any]) -> list[Placed]:
    """Every readable ``<collision>`` of the posed links, in document order."""
    found: list[Placed] = []
    for link in doc.links:
        pose = poses.get(link.name or "")
        if pose is None or doc.link_map.get(link.name or "") is not link:
            continue
        for owner in link.collisions:
            shape = read_shape(owner)
            if shape is None or not shape.valid:
                continue  # C003 reports invalid shapes
            frame = pose @ transform(shape.xyz, shape.rpy)
            placed = _placed(doc, str(link.name), shape, frame, hulls)
            if placed is not None and np.isfinite(placed.center).all():
                found.append(placed)
    return found


def _placed(
    doc: Document, link: str, shape: Shape, frame: np.ndarray, hulls: dict[Any, Any]
) -> Placed | None:
    rotation, center = frame[:3, :3], frame[:3, 3]
    kind = shape.kind
    if kind == "box" and shape.size is not None:
        half = np.array(shape.size) / 2.0
        return Placed(link, shape.owner, kind, rotation, center, half)
    if kind == "sphere" and shape.radius is not None:
        r = shape.radius
        return Placed(link, shape.owner, kind, rotation, center, np.full(3, r), radius=r)
    if kind in ("cylinder", "capsule") and shape.radius and shape.length:
        r, length = shape.radius, shape.length
        reach = length / 2.0 + (r if kind == "capsule" else 0.0)
        half = np.array([r, r, reach])
        return Placed(link, shape.owner, kind, rotation, center, half, r, length)
    hull = _hull(doc, link, shape, hulls) if kind == "mesh" else None
    if hull is None:
        return None
    key, points = hull
    lo, hi = points.min(axis=0), points.max(axis=0)
    return Placed(
        link, shape.owner, kind, rotation, center, (hi - lo) / 2.0, points=points,
        box_center=(hi + lo) / 2.0, key=key,
    )  # fmt: skip


def _hull(
    doc: Document, link: str, shape: Shape, hulls: dict[Any, Any]
) -> tuple[Any, np.ndarray] | None:
    """The convex hull's vertices of a mesh (after scale), read once per file and scale;
    ``None`` when it cannot be read (C004-C006 report why), or trimesh is not installed."""
    from urdflint.model.inertia import meshes_readable
    from urdflint.sources.meshes import MeshRef, load, suspicious_size

    if not meshes_readable():
        return None
    info = load(doc, MeshRef(link, "collision", shape))
    if info is None or not info.ok or suspicious_size(info):
        return None
    key = (info.path, shape.scale)
    if key not in hulls:
        hulls[key] = info.hull_points()
    found = hulls[key]
    return None if found is None else (key, found)


# -- pairs ------------------------------------------------------------------------------------


def candidates(shapes: list[Placed], margin: float) -> list[tuple[int, int]]:
    """Index pairs whose world boxes need a move of ``margin`` or more along every axis to
    come apart (the shorter way out, so a thin plate deep inside a box counts): a pair of
    shapes that interpenetrates by ``margin`` has such boxes.

    Sweep and prune, vectorised: boxes sorted by their low end along the axis they spread
    most on; each box is tested at once against the block of later boxes that start before
    it ends there (a binary search), in chunks of at most :data:`CHUNK` pairs. The time is
    ``O(n log n)`` plus the count of pairs overlapping along that one axis."""
    if not shapes:
        return []
    boxes = [s.world_box() for s in shapes]
    lo = np.array([b[0] for b in boxes])
    hi = np.array([b[1] for b in boxes])
    axis = int(np.argmax(np.ptp(lo + hi, axis=0)))
    order = np.argsort(lo[:, axis], kind="stable")
    lo, hi = lo[order], hi[order]
    start = lo[:, axis]
    # a superset of the block: the exact test below decides, so rounding here only widens
    bound = hi[:, axis] - margin
    bound = bound + 1e-9 * (np.abs(bound) + abs(margin) + 1.0)
    ends = np.searchsorted(start, np.where(np.isnan(bound), -np.inf, bound), side="right")
    counts = np.maximum(ends - np.arange(1, len(shapes) + 1), 0)  # later boxes in the block
    found = [_block_pairs(lo, hi, counts, p, q, margin) for p, q in _chunks(counts.tolist())]
    if not found:
        return []
    a = order[np.concatenate([rows for rows, _ in found])]
    b = order[np.concatenate([cols for _, cols in found])]
    first, second = np.minimum(a, b), np.maximum(a, b)
    return sorted(zip(first.tolist(), second.tolist(), strict=True))


def _chunks(counts: list[int]) -> list[tuple[int, int]]:
    """Runs ``[p, q)`` of boxes whose blocks hold at most :data:`CHUNK` pairs together (one
    box alone when its block is larger); runs without any pair are left out."""
    found: list[tuple[int, int]] = []
    p = 0
    while p < len(counts):
        total, q = counts[p], p + 1
        while q < len(counts) and total + counts[q] <= CHUNK:
            total += counts[q]
            q += 1
        if total:
            found.append((p, q))
        p = q
    return found


def _block_pairs(
    lo: np.ndarray, hi: np.ndarray, counts: np.ndarray, p: int, q: int, margin: float
) -> tuple[np.ndarray, np.ndarray]:
    """The pairs ``(i, j)`` (sorted positions) of boxes ``p <= i < q`` and the boxes of their
    blocks (``i < j <= i + counts[i]``) that need ``margin`` on every axis to come apart."""
    run = counts[p:q]
    rows = np.repeat(np.arange(p, q), run)
    offsets = np.arange(len(rows)) - np.repeat(np.cumsum(run) - run, run)  # 0, 1.. per row
    cols = rows + 1 + offsets
    reach = np.minimum(hi[rows] - lo[cols], hi[cols] - lo[rows])  # the shorter way apart
    keep = (reach >= margin).all(axis=1)
    return rows[keep], cols[keep]


def overlaps(
    doc: Document, min_depth: float, keep: Callable[[str, str], bool]
) -> tuple[list[Overlap], str]:
    """The overlapping link pairs that ``keep(first, second)`` accepts (deepest contact per
    pair), and the method used."""
    poses = link_poses(doc, joint_values(doc))
    shapes = place(doc, poses, {})
    depth_of, method = depth_function()
    order = {name: i for i, name in enumerate(doc.link_map)}
    kept: dict[frozenset[str], bool] = {}
    best: dict[frozenset[str], Overlap] = {}
    pairs = list(candidates(shapes, min_depth))
    if len(pairs) > MAX_PAIRS:  # links piled up at the pose: bound the narrow phase
        method += f"; {len(pairs)} candidate pairs, the first {MAX_PAIRS} measured"
        pairs = pairs[:MAX_PAIRS]
    for i, j in pairs:
        a, b = sorted((shapes[i], shapes[j]), key=lambda s: order[s.link])
        pair = frozenset((a.link, b.link))
        if a.link == b.link:
            continue
        if pair not in kept:
            kept[pair] = keep(a.link, b.link)
        if not kept[pair]:
            continue
        depth, approximate = depth_of(a, b)
        if depth < min_depth or (pair in best and best[pair].depth >= depth):
            continue
        mesh = "mesh" in (a.kind, b.kind)
        best[pair] = Overlap(a.link, b.link, depth, b.owner, approximate, mesh)
    found = sorted(best.values(), key=lambda o: (order[o.second], order[o.first]))
    return found, method
