"""Inertia maths shared by the I rules.

Pure Python on purpose (no numpy): reading a link's ``<inertial>``, a closed-form
eigen-solver for symmetric 3x3 tensors, the inertia and bounding box of primitive
shapes, and the boxes of a link's geometry (meshes through the run's mesh cache).
The rigid bodies that fixed-joint lumping builds are in :mod:`urdflint.model.bodies`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from urdflint.model import optional
from urdflint.model.document import children
from urdflint.model.geometry import Shape, shapes
from urdflint.model.providers import provided
from urdflint.model.values import number, vector

if TYPE_CHECKING:
    from lxml import etree

    from urdflint.model.document import Document

Vec = tuple[float, float, float]
Mat = tuple[Vec, Vec, Vec]

REL_TOL = 1e-6  # moments below REL_TOL * largest count as zero; same slack for A + B >= C
ZERO_MOMENT = 1e-15  # kg m^2, MuJoCo's mjMINVAL: below it a moment is numerical noise
TINY_MOMENT = 1e-12  # kg m^2
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
    # sum() of a tuple rather than of a generator: the same additions in the same order
    # (Python 3.12's compensated float sum included), without a generator per entry
    (b00, b01, b02), (b10, b11, b12), (b20, b21, b22) = b
    return tuple(  # type: ignore[return-value]
        (
            sum((x * b00, y * b10, z * b20)),
            sum((x * b01, y * b11, z * b21)),
            sum((x * b02, y * b12, z * b22)),
        )
        for x, y, z in a
    )


def transpose(a: Mat) -> Mat:
    return tuple(zip(*a, strict=True))  # type: ignore[return-value]


def apply(a: Mat, v: Vec) -> Vec:
    x, y, z = v
    return tuple(sum((r[0] * x, r[1] * y, r[2] * z)) for r in a)  # type: ignore[return-value]


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
    """The eigenvalues of a link's tensor, computed once: several rules ask for the same
    link's. A cached entry serves only the very tuple it was computed for (equal tuples may
    differ in the sign of a zero, which the moments can keep)."""
    found = _MOMENTS.get(tensor)
    if found is not None and found[0] is tensor:
        return found[1]
    moments = eigenvalues(matrix(tensor))
    if len(_MOMENTS) >= 4096:
        _MOMENTS.clear()
    _MOMENTS[tensor] = (tensor, moments)
    return moments


_MOMENTS: dict[tuple[float, ...], tuple[tuple[float, ...], Vec]] = {}


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
        owners = children(link, tag)
        found = [aabb(s) for s in shapes(link, tag)]
        if len(found) != len(owners) or any(b is None for b in found):
            return None
        boxes.extend(b for b in found if b is not None)
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


def times(x: float) -> str:
    """A ratio for messages, to two significant digits: ``15``, ``1000``, ``3.1e+11``."""
    rounded = float(f"{x:.2g}")
    return f"{rounded:.0f}" if rounded < 1e6 else f"{rounded:.1e}"


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
        owners = children(link, tag)
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
