"""The unsafe repairs of I001, I004, I005, I006 and I007: inertials computed from a link's
collision geometry (:mod:`urdflint.sources.inertia_from_geometry`) written into the file.

A declared tensor is replaced by that of the collision shapes at the declared mass, about
their own centroid and in the link's axes: the ``<inertial><origin rpy>`` becomes ``0 0 0``
when it rotated the old tensor, and the declared centre of mass is kept (these rules judge
the moments, not where the mass is; I008 judges the centre). A value equal to the one
written is left alone, so only what changes is edited.
"""

from __future__ import annotations

from lxml import etree

from urdflint.model.document import Document
from urdflint.model.edits import Operation, Repair, SetAttribute
from urdflint.model.inertia import Inertial, Mat, judge, principal_moments
from urdflint.model.values import fmt, number, parse_number
from urdflint.sources.inertia_from_geometry import (
    Estimate,
    balance,
    geometry_inertial,
    inertia_attributes,
)

ORDER = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")  # the order of Inertial.tensor
MAX_DENSITY = 1e5  # kg/m^3, as I007: denser collision shapes are tokens, not the body


def source(estimate: Estimate) -> str:
    """What the estimate was computed from: ``the collision box``, ``the convex hull of the
    collision mesh``, ``the 2 collision shapes (box + mesh (solid))``."""
    method = estimate.method
    if method == "mesh (solid)":
        return "the collision mesh taken as a solid"
    if method == "mesh (convex hull)":
        return "the convex hull of the collision mesh (it is not watertight)"
    if ": " in method:
        count, _, parts = method.partition(": ")
        return f"the {count.replace('shapes', 'collision shapes')} ({parts})"
    return f"the collision {method}"


def written(tensor: Mat) -> tuple[float, ...] | None:
    """``tensor`` as its six attributes read back (``Inertial.tensor`` order), or ``None``
    when the rounded values are no longer a physical tensor (a very thin plate)."""
    text = inertia_attributes(tensor)
    values = tuple(parse_number(text[key]) for key in ORDER)
    if any(v is None for v in values) or judge(principal_moments(values)) != "valid":  # type: ignore[arg-type]
        return None
    return values  # type: ignore[return-value]


def set_tensor(inertia: etree._Element, tensor: Mat) -> list[Operation]:
    """Write ``tensor`` over ``<inertia>``'s attributes (those whose value changes)."""
    found: list[Operation] = []
    for key, value in inertia_attributes(tensor).items():
        if number(inertia, key) != parse_number(value):
            found.append(SetAttribute(inertia, key, value))
    return found


def link_axes(inertial: Inertial) -> list[Operation]:
    """``rpy="0 0 0"`` on the inertial's origin when it rotates the tensor's frame."""
    origin = inertial.origin
    if origin is None or origin.get("rpy") is None:
        return []
    if inertial.rpy is not None and not any(inertial.rpy):
        return []
    return [SetAttribute(origin, "rpy", "0 0 0")]


def estimate_at_mass(doc: Document, name: str, inertial: Inertial) -> Estimate | None:
    """The collision geometry's inertial at the declared mass, when both are usable, the
    shapes are not a token (a 1 mm sphere on a 1 kg link) and the written values stay
    physical."""
    mass = inertial.mass
    if mass is None or not mass > 0 or inertial.inertia_element is None:
        return None
    estimate = geometry_inertial(doc, name, mass=mass)
    if estimate is None or estimate.density > MAX_DENSITY or written(estimate.tensor) is None:
        return None
    return estimate


def refit(inertial: Inertial, estimate: Estimate, kept: str) -> tuple[str, list[Operation]]:
    """The description and operations writing ``estimate``'s tensor over the declared one;
    ``kept`` says why the declared centre of mass stays."""
    assert inertial.inertia_element is not None
    operations = set_tensor(inertial.inertia_element, estimate.tensor) + link_axes(inertial)
    moments = inertia_attributes(estimate.tensor)
    shown = " ".join(f"{k}={moments[k]}" for k in ("ixx", "iyy", "izz"))
    text = (
        f"set the inertia to that of {source(estimate)} at {fmt(estimate.mass)} kg ({shown}, "
        f"about its centroid in the link's axes"
    )
    if link_axes(inertial):
        text += ', so the origin\'s rpy becomes "0 0 0"'
    return text + f"); the declared centre of mass is kept: {kept}", operations


def repair_moments(doc: Document, name: str, inertial: Inertial) -> Repair | None:
    """An impossible or singular tensor (I004, I005): the collision geometry's at the declared
    mass, else MuJoCo's balance when A + B < C (none for a tensor it leaves as it is)."""
    el, tensor = inertial.inertia_element, inertial.matrix
    estimate = estimate_at_mass(doc, name, inertial)
    if estimate is not None:
        text, operations = refit(inertial, estimate, "only the moments are impossible")
    elif el is not None and tensor is not None:
        try:
            balanced = balance(tensor)
        except ValueError:
            return None
        if balanced == tensor:
            return None
        operations = set_tensor(el, balanced)
        text = (
            "MuJoCo's balanceinertia: the three principal moments set to their average, "
            f"{fmt(balanced[0][0])} kg·m² (no usable collision geometry to compute the tensor "
            "from)"
        )
    else:
        return None
    return Repair("unsafe", text, tuple(operations)) if operations else None
