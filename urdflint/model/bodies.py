"""Gazebo's view of link masses: the rigid bodies of fixed-joint lumping, and their boxes.

sdformat's fixed-joint lumping builds rigid bodies (a link plus every link merged
into it through fixed joints). Gazebo, Pinocchio and MuJoCo (``fusestatic``) all
simulate those lumped bodies, so degenerate but physically possible values (point
masses, tiny frames) are judged on the body, while impossible ones are reported on
the link itself. The maths are in :mod:`urdflint.model.inertia`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING
from weakref import WeakKeyDictionary

from urdflint.model import optional
from urdflint.model.finding import Severity
from urdflint.model.gazebo_spec import preserved_joints
from urdflint.model.geometry import Shape, shapes
from urdflint.model.inertia import (
    IDENTITY,
    TINY_MOMENT,
    ZERO,
    Mat,
    Vec,
    aabb,
    apply,
    eigenvalues,
    judge,
    matmul,
    read_inertial,
    rotate,
    rpy_matrix,
    transform_box,
)
from urdflint.model.providers import provided
from urdflint.model.targets import gazebo_label
from urdflint.model.values import vector

if TYPE_CHECKING:
    from lxml import etree

    from urdflint.model.document import Document

GAZEBO_MASSLESS = 1e-6  # sdformat: math::equal(mass, 0.0), whose default tolerance is 1e-6
MOVABLE = frozenset({"revolute", "continuous", "prismatic", "floating", "planar"})


# -- meshes (loaded through the run's mesh cache; trimesh only when a link has a mesh) ---------


def meshes_readable() -> bool:
    """Whether meshes can be loaded here (trimesh installed): the I rules' mesh variants."""
    return optional.available("trimesh")


def mesh_box(doc: Document, shape: Shape) -> tuple[Vec, Vec] | None:
    """The axis-aligned box, in the link frame, of a mesh shape after scale and origin.

    ``None`` when the mesh does not resolve, cannot be read, or is not in metres (C004-C006).
    """
    bounds = provided("mesh_bounds", doc)(shape)
    if bounds is None:
        return None
    return transform_box(bounds, rpy_matrix(shape.rpy), shape.xyz)  # type: ignore[arg-type]


def geometry_box(
    doc: Document, link: etree._Element, tags: tuple[str, ...] = ("collision",)
) -> tuple[Vec, Vec] | None:
    """Union box of the link's shapes under ``tags``, meshes included when they can be read.

    Like :func:`primitive_box`, but a mesh contributes its loaded bounding box. ``None``
    unless every shape is readable (without trimesh: unless all are primitives).
    """
    boxes: list[tuple[Vec, Vec]] = []
    readable = None
    for tag in tags:
        owners = link.findall(tag)
        found = shapes(link, tag)
        if len(found) != len(owners):
            return None
        for shape in found:
            if shape.kind == "mesh":
                if readable is None:
                    readable = meshes_readable()
                box = mesh_box(doc, shape) if readable else None
            else:
                box = aabb(shape)
            if box is None:
                return None
            boxes.append(box)
    if not boxes:
        return None
    lo = tuple(min(b[0][i] for b in boxes) for i in range(3))
    hi = tuple(max(b[1][i] for b in boxes) for i in range(3))
    return lo, hi  # type: ignore[return-value]


def has_mesh(link: etree._Element, tags: tuple[str, ...] = ("collision", "visual")) -> bool:
    return any(s.kind == "mesh" for tag in tags for s in shapes(link, tag))


def body_box(
    doc: Document, body: str, tags: tuple[str, ...] = ("collision", "visual")
) -> tuple[Vec, Vec] | None:
    """Union box, in the body's frame, of the geometry of every link lumped into ``body``.

    Links without any visual or collision add nothing; ``None`` when one member's
    geometry cannot be read or its origin is unreadable.
    """
    b = bodies(doc)
    boxes: list[tuple[Vec, Vec]] = []
    for name, rot, pos in b.members(body):
        link = doc.link_map.get(name)
        if link is None or not any(link.element.findall(tag) for tag in tags):
            continue
        box = geometry_box(doc, link.element, tags)
        if box is None or rot is None or pos is None:
            return None
        boxes.append(transform_box(box, rot, pos))
    if not boxes:
        return None
    lo = tuple(min(x[0][i] for x in boxes) for i in range(3))
    hi = tuple(max(x[1][i] for x in boxes) for i in range(3))
    return lo, hi  # type: ignore[return-value]


# -- Gazebo's lumped bodies ---------------------------------------------------------------


class Bodies:
    """The links of one document grouped as sdformat's fixed-joint lumping groups them."""

    def __init__(self, doc: Document) -> None:
        self.doc = doc
        self.graph = doc.graph
        self.kept = preserved_joints(doc)
        self.inertials = {name: read_inertial(link.element) for name, link in doc.link_map.items()}
        self._members: dict[str, list] = {}
        self._inertia: dict[str, tuple[float, Vec, Mat] | None] = {}

    def merged(self, name: str) -> bool:
        """Whether ``name`` is lumped into its parent (fixed joint, not kept, parent not world)."""
        joint = self.graph.parent_joint(name)
        return (
            joint is not None
            and joint.type == "fixed"
            and joint.name not in self.kept
            and joint.parent not in (None, "world")
        )

    def body_of(self, name: str) -> str:
        seen = {name}
        while self.merged(name):
            parent = self.graph.parent_link(name)
            if parent is None or parent in seen:
                break
            seen.add(parent)
            name = parent
        return name

    def members(self, body: str) -> list[tuple[str, Mat, Vec] | tuple[str, None, None]]:
        """``(link, R, p)`` of the body's links in its frame (``None``: unreadable origin)."""
        if body not in self._members:
            self._members[body] = self._collect(body)
        return self._members[body]

    def _collect(self, body: str) -> list[tuple[str, Mat, Vec] | tuple[str, None, None]]:
        found: list = [(body, IDENTITY, ZERO)]
        seen = {body}
        index = 0
        while index < len(found):
            name, rot, pos = found[index]
            index += 1
            for joint in self.graph.child_joints.get(name, []):
                child = joint.child
                if child is None or child in seen or not self.merged(child):
                    continue
                seen.add(child)
                origin = joint.find("origin")
                xyz, rpy = vector(origin, "xyz", 3, ZERO), vector(origin, "rpy", 3, ZERO)
                if rot is None or xyz is None or rpy is None:
                    found.append((child, None, None))
                else:
                    found.append((child, matmul(rot, rpy_matrix(rpy)), _add(apply(rot, xyz), pos)))  # type: ignore[arg-type]
        return found

    def mass(self, body: str) -> float | None:
        """Total mass of the body's links; ``None`` when one of them is unreadable."""
        total = 0.0
        for name, _, _ in self.members(body):
            inertial = self.inertials.get(name)
            if inertial is not None:
                if inertial.mass is None:
                    return None
                total += inertial.mass
        return total

    def inertia(self, body: str) -> tuple[float, Vec, Mat] | None:
        """``(mass, centre of mass, tensor about it)`` of the lumped body, in the body's frame."""
        if body not in self._inertia:
            self._inertia[body] = self._combine(body)
        return self._inertia[body]

    def _combine(self, body: str) -> tuple[float, Vec, Mat] | None:
        parts: list[tuple[float, Vec, Mat]] = []
        for name, rot, pos in self.members(body):
            inertial = self.inertials.get(name)
            if inertial is None:
                continue
            if rot is None or pos is None or inertial.mass is None or inertial.matrix is None:
                return None
            if inertial.xyz is None or inertial.rpy is None:
                return None
            frame = matmul(rot, rpy_matrix(inertial.rpy))
            parts.append(
                (inertial.mass, _add(apply(rot, inertial.xyz), pos), rotate(inertial.matrix, frame))
            )
        total = sum(m for m, _, _ in parts)
        if total <= 0.0:
            return None
        com = tuple(sum(m * c[i] for m, c, _ in parts) / total for i in range(3))
        tensor = [[0.0] * 3 for _ in range(3)]
        for m, c, t in parts:
            d = [c[i] - com[i] for i in range(3)]
            dd = sum(x * x for x in d)
            for i in range(3):
                for j in range(3):
                    tensor[i][j] += t[i][j] + m * ((dd if i == j else 0.0) - d[i] * d[j])
        return total, com, tuple(tuple(row) for row in tensor)  # type: ignore[return-value]

    def body_is_sound(self, name: str) -> bool:
        """Whether the body ``name`` belongs to has mass and valid, not tiny, principal moments."""
        found = self.inertia(self.body_of(name))
        if found is None or found[0] <= GAZEBO_MASSLESS:
            return False
        moments = eigenvalues(found[2])
        return judge(moments) == "valid" and min(moments) >= TINY_MOMENT

    def excused(self, name: str) -> bool:
        """Whether degenerate values on ``name`` are harmless or better reported elsewhere.

        True when the lumped body is sound anyway, or when the link carries under 1% of
        the body's mass (a dummy root or frame): the heavier links that leave the body
        without a valid inertia are the ones reported.
        """
        if self.body_is_sound(name):
            return True
        own, total = self.inertials.get(name), self.mass(self.body_of(name))
        return own is not None and own.mass is not None and bool(total) and own.mass < 0.01 * total  # type: ignore[operator]

    def negligible(self, name: str) -> bool:
        """A merged link whose mass and inertia are under 1% of its body's (a sensor frame)."""
        own, body = self.inertials.get(name), self.inertia(self.body_of(name))
        if (
            not self.merged(name)
            or own is None
            or own.mass is None
            or own.tensor is None
            or body is None
        ):
            return False
        return own.mass < 0.01 * body[0] and sum(own.tensor[:3]) < 0.01 * sum(
            body[2][i][i] for i in range(3)
        )


_CACHE: WeakKeyDictionary[Document, Bodies] = WeakKeyDictionary()


def bodies(doc: Document) -> Bodies:
    """The (cached) lumped bodies of ``doc``."""
    found = _CACHE.get(doc)
    if found is None:
        found = _CACHE[doc] = Bodies(doc)
    return found


@dataclass(frozen=True, slots=True)
class Verdict:
    """What Gazebo does with a link whose own mass is zero, and how bad that is."""

    severity: Severity
    consequence: str


def massless_verdict(doc: Document, name: str) -> Verdict | None:
    """Gazebo's handling of link ``name`` when it has no mass of its own (``None``: harmless)."""
    b = bodies(doc)
    graph = b.graph
    label = gazebo_label(doc.targets)
    link = doc.link_map[name]
    if b.merged(name):
        if link.visuals or link.collisions:
            merged = f"{label} merges it into '{b.body_of(name)}' as geometry without mass"
            return Verdict(Severity.INFO, merged)
        return None
    total = b.mass(name)
    joint = graph.parent_joint(name)
    if total is None or total > GAZEBO_MASSLESS or (joint is None and name == "world"):
        return None
    below = graph.subtree(name)[1:]
    if joint is None:
        if not below or name != graph.root:
            return None
        return Verdict(Severity.WARNING, f"{label} drops it and with it the whole model")
    if below:
        lost = f"the {len(below)} link{'s' if len(below) > 1 else ''} below it"
        consequence = f"{label} drops it, its joint '{joint.name}' and {lost}"
    else:
        consequence = f"{label} drops it and its joint '{joint.name}'"
    moving = joint.type in MOVABLE or any(
        j.type in MOVABLE for n in below for j in graph.parent_joints.get(n, [])
    )
    if moving:
        return Verdict(Severity.ERROR, consequence)
    if any(doc.link_map[n].visuals or doc.link_map[n].collisions for n in [name, *below]):
        return Verdict(Severity.WARNING, consequence)
    return None


def _add(a: Vec, b: Vec) -> Vec:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])
