"""Inertials computed from a link's geometry, for the unsafe repairs of ``urdflint fix``.

:func:`geometry_inertial` gives the mass, centre of mass and inertia tensor of a link's
collision shapes taken as one solid of uniform density: the declared mass spread over
their volume, or a density times it. Primitives are exact (the formulas of
:func:`urdflint.model.inertia.primitive_moments`, shared with I007); a mesh is read
through the run's mesh cache (trimesh, imported lazily) after its ``scale`` and Collada
unit, as a solid when it is watertight, else as its convex hull.
:func:`balance` repairs a tensor that breaks A + B >= C the way MuJoCo's
``balanceinertia`` does, and :func:`inertial_xml` / :func:`inertia_attributes` write the
results in a file's own indentation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from urdflint.model.geometry import Shape, shapes
from urdflint.model.inertia import (
    ZERO,
    Mat,
    Vec,
    apply,
    eigenvalues,
    meshes_readable,
    primitive_moments,
    rotate,
    rpy_matrix,
    tolerance,
)
from urdflint.model.values import fmt, vector

if TYPE_CHECKING:
    from urdflint.model.document import Document

COMPONENT_ORDER = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")  # as URDF files write them
_INDEX = {"x": 0, "y": 1, "z": 2}
NOISE = 1e-9  # relative: entries this far below the largest are rounding noise, written as 0
NOISE_METRES = 1e-12  # absolute floor for the centre of mass


@dataclass(frozen=True, slots=True)
class Estimate:
    """A link's inertial computed from its geometry, everything in the link frame.

    ``tensor`` is about ``com`` with axes parallel to the link's, i.e. what goes in
    ``<inertial>`` with ``<origin xyz="com" rpy="0 0 0"/>``. ``method`` says what it came
    from: ``box``, ``cylinder``, ``sphere``, ``capsule``, ``mesh (solid)``, ``mesh
    (convex hull)``, or ``2 shapes: box + mesh (solid)``. ``volume`` is in m³.
    """

    mass: float
    com: Vec
    tensor: Mat
    method: str
    volume: float

    @property
    def density(self) -> float:
        return self.mass / self.volume


@dataclass(frozen=True, slots=True)
class Part:
    """One shape at unit density, placed in the link frame."""

    volume: float
    com: Vec
    tensor: Mat  # about com, link axes, at 1 kg/m^3
    method: str


# -- the estimate ---------------------------------------------------------------------------


def geometry_inertial(
    doc: Document,
    link_name: str,
    mass: float | None = None,
    density: float | None = None,
    *,
    use_visual: bool = False,
) -> Estimate | None:
    """The inertial of link ``link_name``'s collision geometry (its visuals with ``use_visual``).

    Give exactly one of ``mass`` (kept, and spread over the shapes in proportion to their
    volumes: a uniform density) or ``density`` (kg/m³: the mass is density × volume). All
    the link's ``<collision>`` elements count, each placed by its ``<origin>``. ``None``
    when the link has none, or when one of them cannot be used: a malformed or
    non-positive dimension, a geometry with no single known shape, a mesh that does not
    resolve or cannot be read (or trimesh is missing), one not in metres (C006), or a
    mesh with no volume even as a convex hull. A partial answer would put the mass in
    the wrong place.
    """
    if (mass is None) == (density is None):
        raise ValueError("give exactly one of mass and density")
    given = mass if mass is not None else density
    if given is None or not (given > 0 and math.isfinite(given)):
        raise ValueError(f"the mass or density must be positive, not {given!r}")
    link = doc.link_map.get(link_name)
    if link is None:
        return None
    owners = link.visuals if use_visual else link.collisions
    found = shapes(link.element, "visual" if use_visual else "collision")
    if not owners or len(found) != len(owners):
        return None
    parts = [_part(doc, link_name, shape) for shape in found]
    if any(p is None for p in parts):
        return None
    return _estimate([p for p in parts if p is not None], mass, density)


def _estimate(parts: list[Part], mass: float | None, density: float | None) -> Estimate | None:
    volume, com, tensor = combine(parts)
    if not (volume > 0 and math.isfinite(volume)):
        return None
    k = density if density is not None else (mass or 0.0) / volume
    scaled = tuple(tuple(v * k for v in row) for row in tensor)
    if len(parts) == 1:
        method = parts[0].method
    else:
        method = f"{len(parts)} shapes: " + " + ".join(p.method for p in parts)
    total = mass if mass is not None else k * volume
    return Estimate(total, com, scaled, method, volume)  # type: ignore[arg-type]


def combine(parts: list[Part]) -> tuple[float, Vec, Mat]:
    """Total volume, centre and tensor about it (parallel axis theorem) of placed parts."""
    volume = sum(p.volume for p in parts)
    if volume <= 0:
        return 0.0, ZERO, ((0.0,) * 3,) * 3  # type: ignore[return-value]
    centre = tuple(sum(p.volume * p.com[i] for p in parts) / volume for i in range(3))
    total = [[0.0] * 3 for _ in range(3)]
    for p in parts:
        offset = [p.com[i] - centre[i] for i in range(3)]
        squared = sum(x * x for x in offset)
        for i in range(3):
            for j in range(3):
                steiner = (squared if i == j else 0.0) - offset[i] * offset[j]
                total[i][j] += p.tensor[i][j] + p.volume * steiner
    return volume, centre, tuple(tuple(row) for row in total)  # type: ignore[return-value]


def _part(doc: Document, link_name: str, shape: Shape) -> Part | None:
    """The shape at density 1, moved into the link frame by its origin."""
    origin = shape.owner.find("origin")  # read again: Shape takes a malformed origin as 0
    xyz, rpy = vector(origin, "xyz", 3, ZERO), vector(origin, "rpy", 3, ZERO)
    if not shape.valid or xyz is None or rpy is None:
        return None
    own = _mesh_solid(doc, link_name, shape) if shape.kind == "mesh" else _primitive(shape)
    if own is None:
        return None
    volume, com, tensor, method = own
    rot = rpy_matrix(rpy)  # type: ignore[arg-type]
    moved = apply(rot, com)
    placed = tuple(moved[i] + xyz[i] for i in range(3))
    return Part(volume, placed, rotate(tensor, rot), method)  # type: ignore[arg-type]


def _primitive(shape: Shape) -> tuple[float, Vec, Mat, str] | None:
    volume = primitive_volume(shape)
    moments = primitive_moments(shape, volume) if volume else None
    if volume is None or moments is None:
        return None
    a, b, c = moments
    return volume, ZERO, ((a, 0.0, 0.0), (0.0, b, 0.0), (0.0, 0.0, c)), shape.kind


def primitive_volume(shape: Shape) -> float | None:
    """Volume in m³ of a valid box, sphere, cylinder or capsule (``None`` otherwise)."""
    if not shape.valid:
        return None
    if shape.kind == "box" and shape.size is not None:
        return math.prod(shape.size)
    r, h = shape.radius or 0.0, shape.length or 0.0
    ball = 4.0 / 3.0 * math.pi * r**3
    found = {"sphere": ball, "cylinder": math.pi * r * r * h, "capsule": math.pi * r * r * h + ball}
    return found.get(shape.kind)


def _mesh_solid(doc: Document, link_name: str, shape: Shape) -> tuple[float, Vec, Mat, str] | None:
    """A mesh at density 1 in its own frame (after scale), as read for I007."""
    if not meshes_readable():
        return None
    from urdflint.sources.meshes import MeshRef, load, suspicious_size

    info = load(doc, MeshRef(link_name, str(shape.owner.tag), shape))
    if info is None or info.error is not None or suspicious_size(info):
        return None  # C004, C005 and C006 report those
    solid = info.solid()
    if solid is None:
        return None
    method = "mesh (solid)" if solid.kind == "mesh" else "mesh (convex hull)"
    return solid.volume, solid.com, solid.tensor, method


# -- balancing --------------------------------------------------------------------------------


def balance(tensor: Mat) -> Mat:
    """``tensor`` made physical the way MuJoCo's ``balanceinertia`` does it.

    MuJoCo (``src/user/user_objects.cc``, ``mjCBody::Compile``, checked at 3.12.1)
    diagonalises a URDF's full tensor (``mjuu_fullInertia``) and, when the principal
    moments break the triangle inequality for any permutation and the compiler has
    ``balanceinertia="true"``, sets all three to their mean::

        inertia[0] = inertia[1] = inertia[2] = (inertia[0] + inertia[1] + inertia[2])/3.0;

    (the XML reference: "the compiler will silently set all three diagonal elements to
    their average value"). It does not set C = A + B. Done in the principal frame and
    rotated back, the result is ``trace / 3`` times the identity: the trace (the sum of
    the moments) is kept, the axes are lost. A tensor that satisfies A + B >= C (within
    :func:`urdflint.model.inertia.tolerance`) is returned unchanged. MuJoCo refuses a
    negative moment before balancing; here it breaks the inequality like any other and
    is averaged away. A tensor whose trace is not positive has no balanced form:
    ``ValueError``.
    """
    a, b, c = eigenvalues(tensor)
    if a + b >= c - tolerance((a, b, c)):
        return tensor
    mean = (a + b + c) / 3.0
    if not mean > 0:
        raise ValueError("a tensor whose moments sum to zero or less cannot be balanced")
    return ((mean, 0.0, 0.0), (0.0, mean, 0.0), (0.0, 0.0, mean))


# -- writing ----------------------------------------------------------------------------------


def number_text(value: float) -> str:
    """A value to 6 significant digits (``0.00833333``, ``1.2e-08``); never ``-0``."""
    text = fmt(value + 0.0)
    return "0" if text in ("-0", "0") else text


def _cleaned(values: tuple[float, ...], floor: float) -> tuple[float, ...]:
    """``values`` with rounding noise (far below the largest, or below ``floor``) set to 0."""
    limit = max(floor, NOISE * max((abs(v) for v in values), default=0.0))
    return tuple(0.0 if abs(v) <= limit else v for v in values)


def inertia_attributes(tensor: Mat) -> dict[str, str]:
    """The ``<inertia>`` attributes of ``tensor`` (kg·m², 6 significant digits), in the
    usual order ixx ixy ixz iyy iyz izz. A product of inertia a billion times smaller than
    the largest moment is rounding noise (a rotated diagonal tensor) and is written as 0."""
    scale = max(abs(tensor[i][i]) for i in range(3)) or max(abs(v) for row in tensor for v in row)
    found: dict[str, str] = {}
    for key in COMPONENT_ORDER:
        i, j = _INDEX[key[1]], _INDEX[key[2]]
        value = tensor[i][j]
        found[key] = number_text(0.0 if i != j and abs(value) <= NOISE * scale else value)
    return found


def inertial_xml(estimate: Estimate, indent: str, newline: str, base: str = "") -> str:
    """The ``<inertial>`` element of ``estimate``, in the style of the file it goes into.

    ``indent`` is the file's indentation unit, ``newline`` its line ending, ``base`` the
    indentation of the line the element starts on. The first line has no indentation
    (the caller puts the text where the element starts), the children are indented by
    ``base + indent``, the closing tag by ``base``; there is no final newline::

        <inertial>
          <origin xyz="0 0 0.15" rpy="0 0 0"/>
          <mass value="1"/>
          <inertia ixx="0.0083" ixy="0" ixz="0" iyy="0.0083" iyz="0" izz="0.0017"/>
        </inertial>
    """
    com = " ".join(number_text(v) for v in _cleaned(estimate.com, NOISE_METRES))
    inertia = " ".join(f'{k}="{v}"' for k, v in inertia_attributes(estimate.tensor).items())
    inner = base + indent
    lines = [
        "<inertial>",
        f'{inner}<origin xyz="{com}" rpy="0 0 0"/>',
        f'{inner}<mass value="{number_text(estimate.mass)}"/>',
        f"{inner}<inertia {inertia}/>",
        f"{base}</inertial>",
    ]
    return newline.join(lines)
