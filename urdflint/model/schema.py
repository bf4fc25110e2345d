"""The URDF element table read by X004, X005, X007 and X013.

For every context (``robot``, ``link``, ``joint``, ``origin``...) it lists the
child elements URDF defines there and the attributes each element carries,
with their kind (a string, one number, 3 numbers, 4 numbers). Known extension
blocks (``<gazebo>``, ``<transmission>``, PyBullet's ``<contact>``...) are
*opaque*: accepted, but their contents belong to other rule families; known
extension attributes (PyBullet's ``<collision group>``...) are in
:data:`EXTENSION_ATTRS`. :func:`walk` visits the elements of a document against
this table.
"""

from __future__ import annotations

import enum
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from functools import lru_cache
from typing import NamedTuple

from lxml import etree

from urdflint.model.memo import once
from urdflint.model.values import parse_number


class Kind(enum.Enum):
    """What an attribute holds; ``arity`` is its count of numbers (0 for text)."""

    STRING = 0
    NUMBER = 1
    VECTOR3 = 3
    RGBA = 4

    __hash__ = object.__hash__  # members are singletons (the number caches key on them)

    @property
    def arity(self) -> int:
        return self.value


@dataclass(frozen=True, slots=True)
class Spec:
    """One element kind: its children (tag -> spec key) and attributes."""

    children: Mapping[str, str] = field(default_factory=dict)
    attrs: Mapping[str, Kind] = field(default_factory=dict)


S, N, V3 = Kind.STRING, Kind.NUMBER, Kind.VECTOR3
OPAQUE = "opaque"  # a known extension: accepted, never descended into


def known(*tags: str) -> dict[str, str]:
    """Children whose spec key is their own tag."""
    return {tag: tag for tag in tags}


def opaque(*tags: str) -> dict[str, str]:
    """Extension children: accepted, contents owned by other rules or tools."""
    return dict.fromkeys(tags, OPAQUE)


def numbers(*attrs: str) -> dict[str, Kind]:
    return dict.fromkeys(attrs, N)


SPECS: dict[str, Spec] = {
    "robot": Spec(
        known("link", "joint", "material")
        # gazebo/transmission/ros2_control have their own rule families; <sensor> is the
        # URDF sensor spec (urdfdom's sensor parser), <deformable> PyBullet's soft bodies
        | opaque("gazebo", "transmission", "ros2_control", "mujoco", "sensor", "deformable"),
        {"name": S, "version": S},
    ),
    "link": Spec(
        known("inertial", "visual", "collision")
        # PyBullet's contact parameters; Pinocchio/HPP capsule and convex extension
        | opaque("contact", "collision_checking"),
        {"name": S},
    ),
    "inertial": Spec(known("origin", "mass", "inertia")),
    # quat_xyzw: URDF 1.1 (urdfdom 5.1), instead of rpy
    "origin": Spec(attrs={"xyz": V3, "rpy": V3, "quat_xyzw": Kind.RGBA}),
    "mass": Spec(attrs=numbers("value")),
    "inertia": Spec(attrs=numbers("ixx", "ixy", "ixz", "iyy", "iyz", "izz")),
    "visual": Spec(known("origin", "geometry", "material"), {"name": S}),
    # MuJoCo's importer registers every named <material> with a <color>, even in a collision
    "collision": Spec(known("origin", "geometry", "material"), {"name": S}),
    # capsule: URDF 1.2 (urdfdom 6), PyBullet, MuJoCo; plane: PyBullet
    "geometry": Spec(known("box", "cylinder", "sphere", "mesh", "capsule", "plane")),
    "box": Spec(attrs={"size": V3}),
    "cylinder": Spec(attrs=numbers("radius", "length")),
    "capsule": Spec(attrs=numbers("radius", "length")),
    "sphere": Spec(attrs=numbers("radius")),
    "mesh": Spec(attrs={"filename": S, "scale": V3}),
    "plane": Spec(attrs={"normal": V3}),
    "material": Spec(known("color", "texture", "specular"), {"name": S}),
    "color": Spec(attrs={"rgba": Kind.RGBA}),
    "texture": Spec(attrs={"filename": S}),
    "specular": Spec(attrs={"rgb": V3}),  # PyBullet
    "joint": Spec(
        known("origin", "parent", "child", "axis", "limit", "dynamics")
        | known("calibration", "mimic", "safety_controller"),
        {"name": S, "type": S},
    ),
    "parent": Spec(attrs={"link": S}),
    "child": Spec(attrs={"link": S}),
    "axis": Spec(attrs={"xyz": V3}),
    # acceleration, deceleration and jerk: URDF 1.2
    "limit": Spec(
        attrs=numbers("lower", "upper", "effort", "velocity", "acceleration")
        | numbers("deceleration", "jerk")
    ),
    "dynamics": Spec(attrs=numbers("damping", "friction")),
    "calibration": Spec(attrs=numbers("rising", "falling", "reference_position")),
    "mimic": Spec(attrs={"joint": S} | numbers("multiplier", "offset")),
    "safety_controller": Spec(
        attrs=numbers("soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity")
    ),
}

# Attributes URDF does not define that a consumer or a widespread exporter writes on
# purpose: accepted by X013, with who reads or writes them.
EXTENSION_ATTRS: dict[str, dict[str, str]] = {
    # PyBullet's UrdfParser: collision filter group and mask, and a concave triangle mesh
    "collision": dict.fromkeys(("group", "mask", "concave"), "PyBullet"),
    "link": {"drake_ignore": "Drake"},  # Drake skips a link with drake_ignore="true"
    # franka_description's joint friction parameters, on every Panda/FR3 joint
    "dynamics": dict.fromkeys(("D", "K", "mu_coulomb", "mu_viscous"), "franka_description"),
    "geometry": {"name": "sr_description"},  # a label the Shadow Hand description writes
}

XACRO_URIS = ("ros.org/wiki/xacro",)


def is_xacro(el: etree._Element) -> bool:
    """An element of the xacro language (``xacro:`` prefix or the xacro namespace)."""
    if not isinstance(el.tag, str) or not el.tag.startswith("{"):
        return False
    uri = etree.QName(el).namespace or ""
    return el.prefix == "xacro" or any(u in uri for u in XACRO_URIS)


def is_foreign(el: etree._Element) -> bool:
    """A namespaced element that is not xacro (``drake:*`` and other extensions)."""
    return isinstance(el.tag, str) and el.tag.startswith("{") and not is_xacro(el)


class Visit(NamedTuple):
    """One element met by :func:`walk`: its spec key, or ``None`` if URDF does not define it."""

    element: etree._Element
    key: str | None
    parent_key: str


_visit = tuple.__new__  # Visit(...) without the named tuple's Python-level __new__


def walk(robot: etree._Element) -> Iterator[Visit]:
    """Every un-namespaced element under ``robot`` with its spec key.

    Descends into known elements only; skips comments, namespaced elements
    (xacro is X008's, other namespaces are extensions) and opaque blocks.
    """
    stack: list[tuple[etree._Element, str]] = [(robot, "robot")]
    while stack:
        node, key = stack.pop()
        known = SPECS[key].children
        for child in node:
            tag = child.tag
            if not isinstance(tag, str) or tag.startswith("{"):
                continue
            child_key = known.get(tag)
            if child_key == OPAQUE:
                continue
            yield _visit(Visit, (child, child_key, key))
            if child_key is not None:
                stack.append((child, child_key))


def visits(robot: etree._Element) -> list[Visit]:
    """:func:`walk` of ``robot`` as a list, computed once per document (X004, X005, X007
    and X013 read it)."""
    return once(robot, "schema.visits", lambda: list(walk(robot)))


def attributes(robot: etree._Element) -> list[tuple[etree._Element, str, Kind]]:
    """``(element, attribute, kind)`` for each typed attribute present on a known element."""
    return [(el, attr, kind) for el, attr, kind, _ in typed_values(robot)]


def typed_values(robot: etree._Element) -> list[tuple[etree._Element, str, Kind, str]]:
    """``(element, attribute, kind, value)`` for each typed attribute present on a known
    element, in document order; computed once per document (X004 and X005 both read it)."""
    return once(robot, "schema.typed_values", lambda: _typed_values(robot))


def _typed_values(robot: etree._Element) -> list[tuple[etree._Element, str, Kind, str]]:
    found = []
    for visit in visits(robot):
        if visit.key is None:
            continue
        get = visit.element.get
        for attr, kind in SPECS[visit.key].attrs.items():
            value = get(attr)
            if value is not None:
                found.append((visit.element, attr, kind, value))
    return found


def homes(tag: str) -> list[str]:
    """The contexts (as tags) where URDF defines ``tag``, e.g. ``inertia`` -> ``['inertial']``."""
    return sorted(key for key, spec in SPECS.items() if tag in spec.children)


def owner(el: etree._Element) -> str:
    """The named thing an element belongs to: ``link 'arm'``, ``joint 'j'``, ``material 'red'``."""
    node: etree._Element | None = el
    while node is not None:
        if node.tag in ("link", "joint") or (node.tag == "material" and _is_top(node)):
            name = node.get("name")
            return f"{node.tag} {name!r}" if name else f"an unnamed {node.tag}"
        if node.tag == "gazebo" and _is_top(node):
            ref = node.get("reference")
            return f"<gazebo reference={ref!r}>" if ref else "a top-level <gazebo> block"
        if node.tag == "robot" and node.getparent() is None:
            return "the robot"
        node = node.getparent()
    return "the robot"


def describe(el: etree._Element) -> str:
    """``link 'arm'`` for a named owner itself, else ``the <visual> of link 'arm'``."""
    if el.tag in ("robot", "link", "joint") or (el.tag == "material" and _is_top(el)):
        return owner(el)
    return f"the <{el.tag}> of {owner(el)}"


def _is_top(el: etree._Element) -> bool:
    parent = el.getparent()
    return parent is not None and parent.tag == "robot" and parent.getparent() is None


@lru_cache(maxsize=4096)
def malformed(value: str, kind: Kind) -> str | None:
    """Why ``value`` is not a valid number of ``kind`` (X004), or ``None`` if it is.

    A one-number attribute must be exactly one number, without trailing
    whitespace (urdfdom's ``strToDouble`` reads the whole string and refuses
    ``"1.0 "``). Vectors report only a malformed token; a wrong count of good
    numbers is :func:`wrong_arity`'s (X005), so each value is reported once.
    """
    tokens = value.split()
    if kind is Kind.NUMBER:
        if not tokens:
            return "is empty"
        if len(tokens) > 1:
            return "must be a single number"
        if parse_number(tokens[0]) is None:
            return "is not a finite number"
        if value != value.rstrip():
            return "ends with whitespace, which urdfdom refuses"
        return None
    bad = next((t for t in tokens if parse_number(t) is None), None)
    return None if bad is None else f"contains {bad!r}, which is not a finite number"


@lru_cache(maxsize=4096)
def wrong_arity(value: str, kind: Kind) -> int | None:
    """The count of numbers when a vector of valid numbers has the wrong size, else ``None``."""
    if kind.arity < 2 or malformed(value, kind) is not None:
        return None
    count = len(value.split())
    return count if count != kind.arity else None
