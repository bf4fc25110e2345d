"""Shapes of visuals and collisions, read once and shared by the I and C rules."""

from __future__ import annotations

from dataclasses import dataclass

from lxml import etree

from urdflint.model.document import children
from urdflint.model.memo import table
from urdflint.model.values import number, vector

SHAPES = ("box", "cylinder", "sphere", "mesh", "capsule")
ZERO3 = (0.0, 0.0, 0.0)


@dataclass(frozen=True, slots=True)
class Shape:
    """One readable geometry: its kind, dimensions and pose in the link frame.

    ``element`` is the shape element (``<box>``...), ``owner`` the enclosing
    ``<visual>``/``<collision>``. Dimensions are ``None`` when malformed.
    """

    kind: str
    element: etree._Element
    owner: etree._Element
    xyz: tuple[float, ...]
    rpy: tuple[float, ...]
    size: tuple[float, ...] | None = None  # box
    radius: float | None = None  # cylinder, sphere, capsule
    length: float | None = None  # cylinder, capsule
    filename: str | None = None  # mesh
    scale: tuple[float, ...] | None = None  # mesh (1 1 1 when absent)

    @property
    def valid(self) -> bool:
        """All dimensions readable and strictly positive."""
        if self.kind == "box":
            return self.size is not None and all(v > 0 for v in self.size)
        if self.kind == "sphere":
            return self.radius is not None and self.radius > 0
        if self.kind in ("cylinder", "capsule"):
            return bool(self.radius and self.length and self.radius > 0 and self.length > 0)
        if self.kind == "mesh":
            return bool(self.filename) and self.scale is not None and all(v > 0 for v in self.scale)
        return False


def shape_elements(owner: etree._Element) -> list[etree._Element]:
    """The shape children of ``owner``'s ``<geometry>`` (0, 1 or several; read once)."""
    found = table(owner, "geometry.elements")
    elements = found.get(owner)
    if elements is None:
        geometry = owner.find("geometry")
        elements = found[owner] = [] if geometry is None else children(geometry)
    return elements


def read_shape(owner: etree._Element) -> Shape | None:
    """The shape of a ``<visual>``/``<collision>``, or ``None`` unless exactly one known shape
    (read once per element)."""
    found = table(owner, "geometry.shape")
    if owner in found:
        return found[owner]  # type: ignore[no-any-return]
    shape = found[owner] = _read_shape(owner)
    return shape


def _read_shape(owner: etree._Element) -> Shape | None:
    elements = shape_elements(owner)
    if len(elements) != 1 or elements[0].tag not in SHAPES:
        return None
    el = elements[0]
    origin = owner.find("origin")
    xyz = vector(origin, "xyz", 3, ZERO3) or ZERO3
    rpy = vector(origin, "rpy", 3, ZERO3) or ZERO3
    kind = str(el.tag)
    if kind == "box":
        return Shape(kind, el, owner, xyz, rpy, size=vector(el, "size", 3))
    if kind == "sphere":
        return Shape(kind, el, owner, xyz, rpy, radius=number(el, "radius"))
    if kind in ("cylinder", "capsule"):
        return Shape(
            kind, el, owner, xyz, rpy, radius=number(el, "radius"), length=number(el, "length")
        )
    return Shape(
        kind,
        el,
        owner,
        xyz,
        rpy,
        filename=el.get("filename"),
        scale=vector(el, "scale", 3, (1.0, 1.0, 1.0)),
    )


def shapes(link: etree._Element, tag: str = "collision") -> list[Shape]:
    """Readable shapes of a link's ``<collision>`` (or ``<visual>``) elements (read once;
    the list is shared: do not change it)."""
    found = table(link, "geometry.shapes")
    key = (link, tag)
    listed = found.get(key)
    if listed is None:
        read = (read_shape(owner) for owner in children(link, tag))
        listed = found[key] = [s for s in read if s is not None]
    return listed  # type: ignore[no-any-return]
