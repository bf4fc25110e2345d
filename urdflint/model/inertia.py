"""Inertia maths and Gazebo's view of link masses, shared by the I rules.

Pure Python on purpose (no numpy): reading a link's ``<inertial>``, a closed-form
eigen-solver for symmetric 3x3 tensors, the inertia and bounding box of
primitive shapes, and the rigid bodies that sdformat's fixed-joint lumping
builds (a link plus every link merged into it through fixed joints). Gazebo,
Pinocchio and MuJoCo (``fusestatic``) all simulate those lumped bodies, so
degenerate but physically possible values (point masses, tiny frames) are
judged on the body, while impossible ones are reported on the link itself.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING
from weakref import WeakKeyDictionary

from urdflint.model import optional
from urdflint.model.document import provided
from urdflint.model.finding import Severity
from urdflint.model.gazebo_spec import preserved_joints
from urdflint.model.geometry import Shape, shapes
from urdflint.model.targets import gazebo_label
from urdflint.model.values import number, vector

if TYPE_CHECKING:
    from lxml import etree

    from urdflint.model.document import Document

Vec = tuple[float, float, float]
Mat = tuple[Vec, Vec, Vec]

GAZEBO_MASSLESS = 1e-6  # sdformat: math::equal(mass, 0.0), whose default tolerance is 1e-6
REL_TOL = 1e-6  # moments below REL_TOL * largest count as zero; same slack for A + B >= C
ZERO_MOMENT = 1e-15  # kg m^2, MuJoCo's mjMINVAL: below it a moment is numerical noise
TINY_MOMENT = 1e-12  # kg m^2
MOVABLE = frozenset({"revolute", "continuous", "prismatic", "floating", "planar"})
COMPONENTS = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")
PLACEHOLDER = (1.0, 1.0, 1.0, 0.0, 0.0, 0.0)  # the Gazebo tutorial's made-up tensor
ZERO: Vec = (0.0, 0.0, 0.0)
IDENTITY: Mat = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


@dataclass(frozen=True, slots=True)
class Inertial:
    """A link's ``<inertial>``; each value is ``None`` when missing or malformed."""

    element: etree._Element
    mass: float | None
    mass_element: etree._Element | None
    xyz: Vec | None
    rpy: Vec | None
    origin: etree._Element | None
    tensor: tuple[float, ...] | None  # ixx iyy izz ixy ixz iyz
    inertia_element: etree._Element | None

    @property
    def matrix(self) -> Mat | None:
        return None if self.tensor is None else matrix(self.tensor)


def read_inertial(link: etree._Element) -> Inertial | None:
    """The link's ``<inertial>``, or ``None`` when it has none."""
    el = link.find("inertial")
    if el is None:
        return None
    mass_el, origin, inertia = el.find("mass"), el.find("origin"), el.find("inertia")
    values = [number(inertia, k) for k in COMPONENTS] if inertia is not None else [None]
    tensor = None if any(v is None for v in values) else tuple(values)  # type: ignore[arg-type]
    return Inertial(
        el,
        number(mass_el, "value") if mass_el is not None else None,
        mass_el,
        vector(origin, "xyz", 3, ZERO),  # type: ignore[arg-type]
        vector(origin, "rpy", 3, ZERO),  # type: ignore[arg-type]
        origin,
        tensor,  # type: ignore[arg-type]
        inertia,
    )


# -- linear algebra ----------------------------------------------------------------------


def matrix(t: tuple[float, ...]) -> Mat:
    ixx, iyy, izz, ixy, ixz, iyz = t
    return ((ixx, ixy, ixz), (ixy, iyy, iyz), (ixz, iyz, izz))


def matmul(a: Mat, b: Mat) -> Mat:
    rows = (tuple(sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)) for i in range(3))
    return tuple(rows)  # type: ignore[return-value]


def transpose(a: Mat) -> Mat:
    return tuple(tuple(a[j][i] for j in range(3)) for i in range(3))  # type: ignore[return-value]


def apply(a: Mat, v: Vec) -> Vec:
    return tuple(sum(a[i][k] * v[k] for k in range(3)) for i in range(3))  # type: ignore[return-value]


def rotate(tensor: Mat, r: Mat) -> Mat:
    """``R I R^T``: a tensor expressed in a frame rotated by ``r``."""
    return matmul(matmul(r, tensor), transpose(r))


def rpy_matrix(rpy: Vec) -> Mat:
    """URDF's fixed-axis roll-pitch-yaw: ``Rz(yaw) Ry(pitch) Rx(roll)``."""
    cr, sr = math.cos(rpy[0]), math.sin(rpy[0])
    cp, sp = math.cos(rpy[1]), math.sin(rpy[1])
    cy, sy = math.cos(rpy[2]), math.sin(rpy[2])
    return (
        (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
        (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
        (-sp, cp * sr, cp * cr),
    )


def eigenvalues(a: Mat) -> Vec:
    """Eigenvalues of a symmetric 3x3 matrix, ascending (trigonometric method)."""
    scale = max(abs(x) for row in a for x in row)
    if scale == 0.0:
        return ZERO
    m = [[x / scale for x in row] for row in a]
    off = m[0][1] ** 2 + m[0][2] ** 2 + m[1][2] ** 2
    if off <= 1e-30:
        return tuple(sorted(m[i][i] * scale for i in range(3)))  # type: ignore[return-value]
    q = (m[0][0] + m[1][1] + m[2][2]) / 3.0
    p = math.sqrt(((m[0][0] - q) ** 2 + (m[1][1] - q) ** 2 + (m[2][2] - q) ** 2 + 2.0 * off) / 6.0)
    b = [[(m[i][j] - (q if i == j else 0.0)) / p for j in range(3)] for i in range(3)]
    det = (
        b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1])
        - b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0])
        + b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0])
    )
    phi = math.acos(max(-1.0, min(1.0, det / 2.0))) / 3.0
    big = q + 2.0 * p * math.cos(phi)
    small = q + 2.0 * p * math.cos(phi + 2.0 * math.pi / 3.0)
    middle = 3.0 * q - big - small
    return tuple(sorted(v * scale for v in (small, middle, big)))  # type: ignore[return-value]


def principal_moments(tensor: tuple[float, ...]) -> Vec:
    return eigenvalues(matrix(tensor))


def tolerance(moments: Vec) -> float:
    """How close to zero a moment counts as zero: relative to the largest, and absolute."""
    return max(REL_TOL * max(abs(m) for m in moments), ZERO_MOMENT)


def judge(moments: Vec) -> str:
    """``impossible`` (negative or A + B < C), ``degenerate`` (a zero moment) or ``valid``."""
    a, b, c = sorted(moments)
    tol = tolerance(moments)
    if c <= tol:
        return "degenerate"
    if a < -tol or a + b < c - tol:
        return "impossible"
    return "degenerate" if a <= tol else "valid"


# -- primitive shapes ---------------------------------------------------------------------


def primitive_moments(shape: Shape, mass: float) -> Vec | None:
    """Principal moments of a solid box, cylinder or capsule (about z), or sphere."""
    if not shape.valid:
        return None
    if shape.kind == "box" and shape.size is not None:
        x, y, z = shape.size
        return (
            mass * (y * y + z * z) / 12,
            mass * (x * x + z * z) / 12,
            mass * (x * x + y * y) / 12,
        )
    r, h = shape.radius or 0.0, shape.length or 0.0
    if shape.kind == "sphere":
        return (0.4 * mass * r * r,) * 3  # type: ignore[return-value]
    if shape.kind == "cylinder":
        side = mass * (3 * r * r + h * h) / 12
        return (side, side, mass * r * r / 2)
    if shape.kind == "capsule":
        cyl, caps = math.pi * r * r * h, 4.0 / 3.0 * math.pi * r**3
        mc, ms = mass * cyl / (cyl + caps), mass * caps / (cyl + caps)
        side = mc * (h * h / 12 + r * r / 4) + ms * (0.4 * r * r + h * h / 4 + 3 * h * r / 8)
        return (side, side, mc * r * r / 2 + ms * 0.4 * r * r)
    return None


def aabb(shape: Shape) -> tuple[Vec, Vec] | None:
    """The axis-aligned box of a primitive in the link frame (its origin xyz and rpy applied)."""
    if not shape.valid or shape.kind == "mesh":
        return None
    rot = rpy_matrix(shape.rpy)  # type: ignore[arg-type]
    if shape.kind == "box" and shape.size is not None:
        half = [sum(abs(rot[i][k]) * shape.size[k] / 2 for k in range(3)) for i in range(3)]
    else:
        r, h = shape.radius or 0.0, shape.length or 0.0
        if shape.kind == "sphere":
            half = [r, r, r]
        elif shape.kind == "cylinder":
            half = [
                abs(rot[i][2]) * h / 2 + r * math.sqrt(max(0.0, 1 - rot[i][2] ** 2))
                for i in range(3)
            ]
        else:  # capsule: the segment's box grown by the radius
            half = [abs(rot[i][2]) * h / 2 + r for i in range(3)]
    lo = tuple(shape.xyz[i] - half[i] for i in range(3))
    hi = tuple(shape.xyz[i] + half[i] for i in range(3))
    return lo, hi  # type: ignore[return-value]


def primitive_box(
    link: etree._Element, tags: tuple[str, ...] = ("collision",)
) -> tuple[Vec, Vec] | None:
    """Union box of the link's shapes under ``tags``; ``None`` unless all are valid primitives."""
    boxes: list[tuple[Vec, Vec]] = []
    for tag in tags:
        owners = link.findall(tag)
        found = [aabb(s) for s in shapes(link, tag)]
        if len(found) != len(owners) or any(b is None for b in found):
            return None
        boxes.extend(b for b in found if b is not None)
    if not boxes:
        return None
    lo = tuple(min(b[0][i] for b in boxes) for i in range(3))
    hi = tuple(max(b[1][i] for b in boxes) for i in range(3))
    return lo, hi  # type: ignore[return-value]


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
    return transform_box(bounds, rpy_matrix(shape.rpy), shape.xyz)


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


def transform_box(box: tuple[Vec, Vec], rot: Mat, pos: Vec) -> tuple[Vec, Vec]:
    """The axis-aligned box around ``box`` rotated by ``rot`` and moved by ``pos``."""
    lo, hi = box
    corners = [
        apply(rot, (x, y, z))
        for x in (lo[0], hi[0])
        for y in (lo[1], hi[1])
        for z in (lo[2], hi[2])
    ]
    new_lo = tuple(pos[i] + min(c[i] for c in corners) for i in range(3))
    new_hi = tuple(pos[i] + max(c[i] for c in corners) for i in range(3))
    return new_lo, new_hi  # type: ignore[return-value]


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


def times(x: float) -> str:
    """A ratio for messages, to two significant digits: ``15``, ``1000``, ``3.1e+11``."""
    rounded = float(f"{x:.2g}")
    return f"{rounded:.0f}" if rounded < 1e6 else f"{rounded:.1e}"


def _add(a: Vec, b: Vec) -> Vec:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])
