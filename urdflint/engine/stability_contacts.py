"""Where a mobile robot touches the ground: the candidate links, the lowest points of their
collision geometry and the support polygon those points span.

:mod:`urdflint.engine.stability` states the heuristic; this module implements it on link
poses it is given (4x4 numpy arrays in the root link's frame). numpy and the mesh loader are
imported inside the functions.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from urdflint.engine.stability_polygon import Point2, hull, shape_kind
from urdflint.model.geometry import Shape, shapes

if TYPE_CHECKING:
    from urdflint.model.document import Document

TOKENS = frozenset({"wheel", "wheels", "caster", "casters", "castor", "castors", "foot", "feet",
                    "toe", "toes", "sole", "soles"})  # fmt: skip
MOVING = ("revolute", "continuous", "prismatic")
FLAT = 1e-4  # m: the points of one shape this close to its lowest point are where it touches
RIM = 32  # points on each rim circle of a cylinder (the lowest one always among them)
Poses = dict[str, Any]  # link -> 4x4 numpy array in the root link frame


def tokens(name: str) -> set[str]:
    """The words of a link name: ``LF_FOOT`` -> {lf, foot}, ``leftWheel2`` -> {left, wheel}."""
    spaced = re.sub(r"([a-z])([A-Z])", r"\1 \2", name)
    return {w.lower() for w in re.split(r"[^A-Za-z]+", spaced) if w}


@dataclass
class Candidates:
    """The links that may touch the ground, each with why (``links``), or the configured
    ones; ``unknown`` configured names the model does not have."""

    links: dict[str, str] = field(default_factory=dict)
    configured: bool = False
    unknown: list[str] = field(default_factory=list)


FEET = frozenset({"foot", "feet", "toe", "toes", "sole", "soles"})


def named_or_rolling(doc: Document, root: str) -> dict[str, str]:
    """Links named like a wheel or caster (``wheel``) or a foot (``foot``), and links on a
    continuous joint (``wheel``)."""
    found: dict[str, str] = {}
    for name in doc.graph.subtree(root):
        joint = doc.graph.parent_joint(name)
        words = tokens(name) & TOKENS
        if words:
            found[name] = "foot" if words & FEET else "wheel"
        elif joint is not None and joint.type == "continuous":
            found[name] = "wheel"
    return found


def leg_ends(doc: Document, root: str) -> list[str]:
    """Leaf links at the end of at least two moving joints (legs, and arms: the caller keeps
    those that hang below the root's own geometry)."""
    graph = doc.graph
    found = []
    for name in graph.subtree(root):
        if graph.children(name):
            continue
        moving = 0
        for joint in chain(doc, name):
            moving += joint.type in MOVING
        if moving >= 2:
            found.append(name)
    return found


def chain(doc: Document, link: str) -> list[Any]:
    """The joints from ``link`` up to the root, nearest first."""
    graph, joints, seen = doc.graph, [], {link}
    joint = graph.parent_joint(link)
    while joint is not None and joint.parent is not None and joint.parent not in seen:
        joints.append(joint)
        seen.add(joint.parent)
        joint = graph.parent_joint(joint.parent)
    return joints


def body(doc: Document, link: str, stop: set[str] | dict[str, str]) -> list[str]:
    """``link`` and the links welded below it by fixed joints (not into another of ``stop``)."""
    found, stack, skip = [], [link], set(stop)
    while stack:
        name = stack.pop()
        found.append(name)
        skip.add(name)
        for joint in doc.graph.child_joints.get(name, []):
            if joint.type == "fixed" and joint.child is not None and joint.child not in skip:
                stack.append(joint.child)
    return found


def group(doc: Document, link: str, base: list[str]) -> list[str]:
    """The rigid body of ``link``: up through fixed joints (not into the root's body
    ``base``: a sole frame welded to the ankle link that carries the collision), then down."""
    top, seen = link, {link, *base}
    joint = doc.graph.parent_joint(top)
    while joint is not None and joint.type == "fixed" and joint.parent not in seen:
        top = joint.parent  # type: ignore[assignment]
        seen.add(top)
        joint = doc.graph.parent_joint(top)
    return body(doc, top, set(base))


# -- points --------------------------------------------------------------------------------


def shape_points(doc: Document, link: str, shape: Shape, pose: Any) -> Any:
    """The points of ``shape`` that bound it from below, in the root frame: a box's corners,
    a cylinder's rims, a sphere's or capsule's lowest points, a mesh's hull vertices;
    ``None`` when unreadable (a mesh that does not load)."""
    import numpy as np

    from urdflint.sources.self_collision import transform

    if not shape.valid:
        return None
    placed = pose @ transform(shape.xyz, shape.rpy)
    if shape.kind == "mesh":
        return _mesh_points(doc, link, shape, placed)
    rot, centre = placed[:3, :3], placed[:3, 3]
    down = np.array([0.0, 0.0, -1.0])
    if shape.kind == "box":
        half = np.array(shape.size) / 2
        corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
        return (corners * half) @ rot.T + centre
    if shape.kind == "sphere":
        return np.array([centre + down * shape.radius])
    axis = rot[:, 2]
    ends = [centre + axis * shape.length / 2, centre - axis * shape.length / 2]  # type: ignore[operator]
    if shape.kind == "capsule":
        return np.array([end + down * shape.radius for end in ends])
    across = down - axis * float(down @ axis)  # a cylinder
    if np.linalg.norm(across) < 1e-9:
        across = rot[:, 0]
    across = across / np.linalg.norm(across)
    side = np.cross(axis, across)
    angles = np.arange(RIM) * (2 * math.pi / RIM)
    rim = np.outer(np.cos(angles), across) + np.outer(np.sin(angles), side)
    return np.vstack([end + rim * shape.radius for end in ends])


def _mesh_points(doc: Document, link: str, shape: Shape, placed: Any) -> Any:
    from urdflint.sources.meshes import MeshRef, load

    info = load(doc, MeshRef(link, "collision", shape))
    if info is None or not info.ok:
        return None
    points = info.hull_points()
    if points is None:
        return None
    return points @ placed[:3, :3].T + placed[:3, 3]


def lowest(
    doc: Document, links: list[str], poses: Poses
) -> tuple[list[tuple[str, Any]], list[str]]:
    """``(link, points)`` of every readable collision shape of ``links`` (the points within
    :data:`FLAT` of the shape's own lowest point), and the links with an unreadable mesh."""
    found: list[tuple[str, Any]] = []
    unreadable: list[str] = []
    for name in links:
        link = doc.link_map.get(name)
        if link is None or name not in poses:
            continue
        for shape in shapes(link.element):
            points = shape_points(doc, name, shape, poses[name])
            if points is None or not len(points):
                if shape.kind == "mesh" and shape.valid:
                    unreadable.append(name)
                continue
            z = points[:, 2]
            found.append((name, points[z <= z.min() + FLAT]))
    return found, unreadable


def lowest_bound(doc: Document, name: str, pose: Any) -> float | None:
    """A lower bound of link ``name``'s collision geometry's height (meshes: their bounding
    box, not read again), ``None`` without geometry."""
    import numpy as np

    from urdflint.sources.meshes import MeshRef, load
    from urdflint.sources.self_collision import transform

    link = doc.link_map.get(name)
    best: float | None = None
    for shape in shapes(link.element) if link is not None else []:
        if shape.kind == "mesh":
            info = load(doc, MeshRef(name, "collision", shape)) if shape.valid else None
            if info is None or not info.ok:
                continue
            lo, hi = np.array(info.lo), np.array(info.hi)
            box = lo + (hi - lo) * np.array(
                [[a, b, c] for a in (0, 1) for b in (0, 1) for c in (0, 1)]
            )
            placed = pose @ transform(shape.xyz, shape.rpy)
            z = float((box @ placed[:3, :3].T + placed[:3, 3])[:, 2].min())
        else:
            points = shape_points(doc, name, shape, pose)
            if points is None or not len(points):
                continue
            z = float(points[:, 2].min())
        best = z if best is None else min(best, z)
    return best


def probes(doc: Document, link: str) -> tuple[Any, Any] | None:
    """Points that bound ``link``'s collision geometry in its own frame, and the radius to
    subtract below each (spheres, capsules): box corners, cylinder rims, mesh hull vertices;
    ``None`` without readable geometry."""
    import numpy as np

    from urdflint.sources.self_collision import transform

    element = doc.link_map[link].element if link in doc.link_map else None
    points, radii = [], []
    for shape in shapes(element) if element is not None else []:
        if not shape.valid:
            continue
        if shape.kind == "mesh":
            local = _mesh_points(doc, link, shape, transform(shape.xyz, shape.rpy))
            radius = 0.0
        else:
            local = shape_points(doc, link, shape, np.eye(4))
            radius = shape.radius if shape.kind in ("sphere", "capsule") else 0.0
            if shape.kind in ("sphere", "capsule"):
                local = local + np.array([0.0, 0.0, radius])  # back to the centres
        if local is not None and len(local):
            points.append(local)
            radii.append(np.full(len(local), radius))
    if not points:
        return None
    return np.vstack(points), np.concatenate(radii)


# -- the support ---------------------------------------------------------------------------


@dataclass
class Support:
    """What the robot stands on at one configuration.

    ``links``: the candidates that touch (their shape's lowest point within the tolerance
    of ``ground``, the lowest point of them all); ``points`` the contact points on the
    ground, ``polygon`` their convex hull (counter-clockwise), ``kind`` ``polygon``,
    ``line`` or ``point``. ``lifted``: candidates with geometry above the tolerance (height
    above the ground, m); ``bare``: candidates without collision geometry; ``below``: other
    links whose collision reaches under the ground (depth, m); ``unreadable``: candidates
    with a mesh that could not be read.
    """

    links: list[str]
    points: list[Point2]
    polygon: list[Point2]
    kind: str
    ground: float
    lifted: dict[str, float] = field(default_factory=dict)
    bare: list[str] = field(default_factory=list)
    below: dict[str, float] = field(default_factory=dict)
    unreadable: list[str] = field(default_factory=list)


def support(
    doc: Document, links: dict[str, str], poses: Poses, tolerance: float, base: list[str]
) -> Support:
    """The support of candidate ``links`` at ``poses`` (``base``: the root's rigid body);
    ``kind`` is ``none`` when no candidate has readable geometry."""
    shapes_of: dict[str, list[Any]] = {}
    unreadable: list[str] = []
    bodies: set[str] = set(base)
    for name in links:
        members = group(doc, name, base)
        if bodies.issuperset(members):
            continue  # welded to a candidate already read (a sole frame on a foot)
        bodies.update(members)
        found, bad = lowest(doc, members, poses)
        shapes_of[name] = [points for _, points in found]
        unreadable.extend(n for n in bad if n not in unreadable)
    heights = {n: min(float(p[:, 2].min()) for p in s) for n, s in shapes_of.items() if s}
    bare = [n for n, s in shapes_of.items() if not s]
    if not heights:
        return Support([], [], [], "none", 0.0, bare=bare, unreadable=unreadable)
    ground = min(heights.values())
    points: list[Point2] = []
    touching = []
    for name, found in shapes_of.items():
        for shape in found:
            if float(shape[:, 2].min()) <= ground + tolerance:
                points.extend((float(x), float(y)) for x, y in shape[:, :2])
                if name not in touching:
                    touching.append(name)
    polygon = hull(points)
    return Support(
        touching,
        points,
        polygon,
        shape_kind(polygon),
        ground,
        lifted={n: h - ground for n, h in heights.items() if n not in touching},
        bare=bare,
        below=_below(doc, poses, bodies - set(base), ground, tolerance),
        unreadable=unreadable,
    )


def _below(
    doc: Document, poses: Poses, skip: set[str], ground: float, tolerance: float
) -> dict[str, float]:
    """Links (not in ``skip``) whose collision geometry reaches more than ``tolerance`` under
    the ``ground``: how far (m)."""
    found: dict[str, float] = {}
    for name, pose in poses.items():
        if name in skip:
            continue
        bound = lowest_bound(doc, name, pose)
        if bound is None or bound >= ground - tolerance:
            continue
        exact, _ = lowest(doc, [name], {name: pose})
        depth = max((ground - float(p[:, 2].min()) for _, p in exact), default=0.0)
        if depth > tolerance:
            found[name] = depth
    return found
