"""Effects that depend on the model around the defect: what fixed-joint lumping makes of it.

sdformat lumps links welded by fixed joints into one body before it checks inertias or
drops massless links; these functions adjust a rule's table (:mod:`consequences`) to that.
"""

from __future__ import annotations

from collections.abc import Mapping

from lxml import etree
from urdflint.rules.consequences import (
    BAD_TENSOR,
    DEGENERATE_TENSOR,
    INVALID_MASS,
    TWO_PARENTS,
    gazebo,
)

from urdflint.model.bodies import GAZEBO_MASSLESS, bodies, selected
from urdflint.model.document import Document, Joint
from urdflint.model.effects import Consequence, Effect, kept, refused, warns
from urdflint.model.finding import Severity
from urdflint.model.inertia import judge, principal_moments
from urdflint.model.targets import LABELS, gazebo_label, ordered


def impossible(doc: Document, name: str, table: dict[str, Effect]) -> dict[str, Effect]:
    """``table`` for an impossible mass or tensor on link ``name``; sdformat lumps a welded
    link with its parent (and a link with its welded children) before it checks, so Gazebo
    loads the model when the lumped body is sound (observed: minitaur's motor links)."""
    b = bodies(doc)
    if not b.body_is_sound(name):
        return table
    body = b.body_of(name)
    return {**table, **gazebo(kept(f"sdformat lumps it into body '{body}', which is valid"))}


def two_parents(doc: Document, first: Joint, second: Joint) -> dict[str, Effect]:
    """sdformat (observed, 12.3) lumps a child welded to two parents into both, its mass
    counted twice (nothing shows for a massless frame); with two moving parents it writes
    the link twice and refuses the model."""
    table = dict(TWO_PARENTS)
    moving = "fixed" not in (first.type, second.type)
    if moving or "world" in (first.parent, second.parent):
        table.update(gazebo(refused('sdformat: "link with name[...] already exists"')))
    elif (bodies(doc).mass(second.child or "") or 0.0) <= GAZEBO_MASSLESS:
        table.update(gazebo(kept("a massless frame lumped twice changes nothing")))
    return table


def invalid_mass(doc: Document, mass: etree._Element) -> dict[str, Effect]:
    """A mass that is not a number: sdformat reads no mass and drops the link, unless links
    welded to it bring mass into its lumped body (observed: minitaur, valkyrie)."""
    inertial = mass.getparent()
    link = inertial.getparent() if inertial is not None else None
    name = link.get("name") if link is not None and link.tag == "link" else None
    b = bodies(doc)
    welded = [
        i.mass
        for member, _, _ in (b.members(name)[1:] if name in doc.link_map else [])
        if (i := b.inertials.get(member)) is not None and i.mass is not None
    ]
    if sum(m for m in welded if m > 0) > GAZEBO_MASSLESS:
        return {**INVALID_MASS, **gazebo(kept("the links welded to it give its body a mass"))}
    return dict(INVALID_MASS)


PYBULLET_ZEROED = '"Bad inertia tensor properties, setting inertia to zero" on the welded link'
DRAKE_PARSING = '"While parsing inertia matrix: ... The rotational inertia" on the welded link'


def degenerate(doc: Document, name: str, tensor: tuple[float, ...]) -> dict[str, Effect]:
    """A tensor with a zero principal moment on link ``name``. With A + B < C as well it is
    impossible (:func:`impossible`); else sdformat, Drake and PyBullet load it and MuJoCo
    refuses it, on a welded link too (it checks every body before fusing them), except an
    all-zero tensor on a welded link (observed, MuJoCo 4.0)."""
    welded = bodies(doc).merged(name)
    if judge(principal_moments(tensor)) == "impossible":
        table = impossible(doc, name, BAD_TENSOR)
        if welded:  # observed: both warn; the welded link's body barely changes
            table = {**table, "pybullet": warns(PYBULLET_ZEROED), "drake": warns(DRAKE_PARSING)}
        return table
    if not any(tensor) and welded:
        fused = kept("a welded point mass is fused into its parent body")
        return {**DEGENERATE_TENSOR, "mujoco": fused}
    return DEGENERATE_TENSOR


def degenerate_severity(doc: Document, name: str, tensor: tuple[float, ...]) -> Severity | None:
    """How bad a zero principal moment on link ``name`` is: an error when
    :func:`degenerate_matters`; else a warning when the link carries mass and a target not
    selected refuses it (MuJoCo checks every body before fusing): harmless where it is
    lumped, but the same file feeds other consumers; ``None`` when nothing refuses it."""
    if degenerate_matters(doc, name, tensor):
        return Severity.ERROR
    own = bodies(doc).inertials.get(name)
    if own is None or own.mass is None or own.mass <= 0:
        return None
    table = degenerate(doc, name, tensor)
    if any(e.consequence is Consequence.REFUSED for e in table.values()):
        return Severity.WARNING
    return None


def degenerate_matters(doc: Document, name: str, tensor: tuple[float, ...]) -> bool:
    """Whether a zero principal moment on link ``name`` is worth reporting: it carries mass,
    and a selected target refuses it, or its lumped body has no valid inertia and the link
    carries 1% or more of that body's mass (else the heavier links are reported)."""
    b = bodies(doc)
    own = b.inertials.get(name)
    if own is None or own.mass is None or own.mass == 0:
        return False
    if own.mass < 0:
        return True
    table = degenerate(doc, name, tensor)
    if any(table[t].consequence is Consequence.REFUSED for t in selected(doc) if t in table):
        return True
    return not b.excused(name)


def welded_note(
    doc: Document, name: str, severity: Severity, effects: Mapping[str, Effect] | None = None
) -> str:
    """The clause a message adds when :func:`impossible_severity` lowered a finding: harmless
    where the link is lumped, and the targets not selected that refuse the file anyway
    (from the finding's ``effects``): the same file feeds other consumers."""
    if severity is Severity.ERROR:
        return ""
    body = bodies(doc).body_of(name)
    label = gazebo_label(doc.targets)
    if body == name:  # the body's own link: the links welded to it make it sound
        note = f"{label} lumps the links welded to it into it, and that body stays valid"
    else:
        note = f"welded: {label} lumps it into '{body}', which stays valid"
    refusing = refused_elsewhere(doc, effects or {})
    if refusing:
        note += f"; {refusing} the file"
    return f" ({note})"


def refused_elsewhere(doc: Document, effects: Mapping[str, Effect]) -> str:
    """``MuJoCo refuses`` / ``MuJoCo and Drake refuse``: the targets outside the selection
    whose effect is a refusal ('' when none)."""
    chosen = selected(doc)
    names = [
        LABELS[t]
        for t in ordered(tuple(effects))
        if t not in chosen and effects[t].consequence is Consequence.REFUSED
    ]
    if not names:
        return ""
    if len(names) == 1:
        return f"{names[0]} refuses"
    return f"{', '.join(names[:-1])} and {names[-1]} refuse"
