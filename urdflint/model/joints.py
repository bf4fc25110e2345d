"""Joint tables and readers shared by the J rules.

The type sets follow urdfdom (``urdf_parser/src/joint.cpp``): it reads
``<axis>`` for every type except ``fixed`` and ``floating``, reads ``<limit>``
for every type (and then demands ``effort`` and ``velocity``), requires a
``<limit>`` only for ``revolute`` and ``prismatic``, and ignores ``lower`` and
``upper`` of ``continuous`` joints.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from urdflint.model.values import fmt, number, parse_numbers

if TYPE_CHECKING:
    from lxml import etree

    from urdflint.model.document import Joint

TYPES = frozenset({"revolute", "continuous", "prismatic", "fixed", "floating", "planar"})
BOUNDED = frozenset({"revolute", "prismatic"})  # lower/upper are used; <limit> is required
ACTUATED = frozenset({"revolute", "continuous", "prismatic"})  # one DOF: effort/velocity apply
AXIS_USED = frozenset({"revolute", "continuous", "prismatic", "planar"})
AXIS_IGNORED = frozenset({"fixed", "floating"})
LIMIT_IGNORED = frozenset({"fixed", "floating", "planar"})
LINEAR = frozenset({"prismatic"})

DEFAULT_AXIS = (1.0, 0.0, 0.0)
ZERO_NORM = 1e-12


@dataclass(frozen=True, slots=True)
class Limit:
    """A joint's ``<limit>``: each value is ``None`` when absent or malformed."""

    element: etree._Element
    lower: float | None
    upper: float | None
    effort: float | None
    velocity: float | None
    absent: frozenset[str]  # attributes not written at all

    def has(self, attr: str) -> bool:
        return attr not in self.absent


def limit(joint: Joint) -> Limit | None:
    """The joint's first ``<limit>`` (the one urdfdom reads), or ``None``."""
    el = joint.find("limit")
    if el is None:
        return None
    attrs = ("lower", "upper", "effort", "velocity")
    values = {a: number(el, a) for a in attrs}
    absent = frozenset(a for a in attrs if el.get(a) is None)
    return Limit(el, absent=absent, **values)


def axis(joint: Joint) -> tuple[float, float, float] | None:
    """The axis urdfdom uses: (1, 0, 0) without ``<axis>``, (0, 0, 0) for an
    ``<axis>`` without ``xyz`` (urdfdom leaves the cleared vector), ``None`` when
    ``xyz`` is malformed (X004/X005 report that)."""
    el = joint.find("axis")
    if el is None:
        return DEFAULT_AXIS
    raw = el.get("xyz")
    if raw is None:
        return (0.0, 0.0, 0.0)
    values = parse_numbers(raw)
    if values is None or len(values) != 3:
        return None
    return (values[0], values[1], values[2])


def norm(v: tuple[float, ...]) -> float:
    return math.sqrt(sum(x * x for x in v))


def normalised(v: tuple[float, ...]) -> tuple[float, ...]:
    n = norm(v)
    return tuple(x / n for x in v)


def fmt_vector(v: tuple[float, ...]) -> str:
    """``0.707107 0.707107 0`` (``-0`` printed as ``0``)."""
    return " ".join(fmt(x + 0.0) for x in v)


def is_mimic(joint: Joint) -> bool:
    return joint.find("mimic") is not None


def label(joint: Joint) -> str:
    """``revolute joint 'elbow'`` for messages."""
    kind = f"{joint.type} joint" if joint.type else "joint"
    return f"{kind} '{joint.name}'"


def units(joint_type: str | None) -> tuple[str, str, str]:
    """(position, effort, velocity) units for a joint type."""
    if joint_type in LINEAR:
        return ("m", "N", "m/s")
    return ("rad", "N·m", "rad/s")
