"""Effects that depend on the model around the defect: what fixed-joint lumping makes of it.

sdformat lumps links welded by fixed joints into one body before it checks inertias or
drops massless links; these functions adjust a rule's table (:mod:`consequences`) to that.
"""

from __future__ import annotations

from lxml import etree
from urdflint.rules.consequences import INVALID_MASS, TWO_PARENTS, gazebo

from urdflint.model.bodies import GAZEBO_MASSLESS, bodies
from urdflint.model.document import Document, Joint
from urdflint.model.effects import Effect, kept, refused


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
