"""An element that URDF does not define at that place.

## What it does
Walks the document against URDF's element table (urdflint/schema.py) and
reports elements that URDF does not define where they stand: typos
(`<colision>`), elements one level off (`<inertia>` directly in `<link>`,
`<inertial>` directly in `<robot>`, `<origin>` in `<link>`) and elements no
parser reads (`<joint_properties>`, a link's `<gravity>` or `<self_filter>`,
a joint's `<controller_gains>`), including URDF elements written inside
`<geometry>` (a visual's `<material>` or an `<origin>` put one level too deep;
an unknown shape such as `<cube>` is C003's). The message names the place the
element belongs or the closest known name.

Accepted extensions are not reported and not descended into: top-level
`<gazebo>`, `<transmission>`, `<ros2_control>`, `<mujoco>`, `<sensor>` (URDF
sensors) and `<deformable>` (PyBullet); a link's `<contact>` (PyBullet) and
`<collision_checking>` (Pinocchio/HPP); `<capsule>` and `<plane>` geometry;
`<specular>` in a material (PyBullet); a `<material>` inside `<collision>`
(MuJoCo registers it as a colour). Namespaced elements (`drake:*`...) are
extensions and skipped; `xacro:*` elements are X008's. Unknown *attributes*
are X013's.

## Why is this bad?
Every URDF parser looks children up by name and silently ignores the rest:
urdfdom (`check_urdf`), sdformat (Gazebo), MuJoCo, Drake, PyBullet and Pinocchio
say nothing about this rule's bad example (urdf_parser_py alone warns "Unknown
tag"). A misspelt `<colision>` leaves the link without collision; an `<inertia>`
outside `<inertial>` leaves the link without mass properties, so Gazebo drops it
(sdformat 12 drops every massless link of the example: "A model must have at
least one link") and MuJoCo refuses the model ("mass and inertia of moving
bodies must be larger than mjMINVAL"); `<joint_properties>` (the pre-1.0
spelling of `<dynamics>`) leaves the joint undamped. A `<material>` after the
shape inside `<geometry>` is ignored by urdfdom, which reads the shape and
gives the visual no material. The model loads, and behaves differently from
what the file says.

## How to fix
Rename or move the element as the message suggests. If it is data for a
specific tool, put it in that tool's block (`<gazebo reference="...">` for
Gazebo) or in a namespace of its own (`xmlns:mytool="..."`); otherwise delete it.

`urdflint fix` renames a misspelt element when one URDF name is certainly meant: it is the
suggested one, the only closest name at most one edit away (two for names of 8+ letters,
ignoring case and `_`), with the same digits, and the parent has no such element yet
(except `<visual>` and `<collision>`, which a link may have several of): `<colision>`
becomes `<collision>`, `<colour>` `<color>`. Elements to move or delete, and misspelt
top-level elements (a `<lnk>` would add a link to the tree), are left to you.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, children
from urdflint.model.edits import RenameElement, Repair
from urdflint.model.finding import Severity
from urdflint.model.schema import SPECS, describe, homes, visits
from urdflint.model.spelling import ranked, same_digits

# Well-known mistakes that deserve a specific hint: (context, tag) -> hint.
HINTS = {
    ("joint", "joint_properties"): "it is the pre-1.0 name of <dynamics>",
    ("link", "gravity"): "URDF has no per-link gravity; Gazebo reads it from <gazebo reference>",
    ("geometry", "material"): "a visual's <material> goes beside <geometry>, inside <visual>",
}


@rule(
    "X007",
    "unknown-element",
    Severity.WARNING,
    fix="Rename or move the element as suggested, or delete it: every URDF parser ignores it.",
    fixable="safe",
)
def check(doc: Document) -> Iterator[Hit]:
    for visit in visits(doc.robot):
        if visit.key is not None:
            continue
        el = visit.element
        if visit.parent_key == "geometry" and not homes(el.tag):
            continue  # an unknown shape is C003 invalid-geometry's (an error there)
        where = describe(el.getparent())
        hint, suggested = _hint(el.tag, visit.parent_key)
        suffix = f" ({hint})" if hint else ""
        yield Hit(
            el,
            f"<{el.tag}> is not a URDF element of {where}{suffix}",
            repair=_rename(el, visit.parent_key, suggested),
        )


def _hint(tag: str, context: str) -> tuple[str | None, str | None]:
    """The hint for the message, and the name it suggests (a did-you-mean)."""
    if (context, tag) in HINTS:
        return HINTS[(context, tag)], None
    places = [p for p in homes(tag) if p != context]
    if places:
        if places == ["robot"]:
            return "it belongs at the top level, directly inside <robot>", None
        names = [f"<{p}>" for p in places]
        listed = names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1]
        return f"it belongs inside {listed}", None
    close = difflib.get_close_matches(tag, list(SPECS[context].children), n=1, cutoff=0.75)
    return (f"did you mean <{close[0]}>?", close[0]) if close else (None, None)


MANY = frozenset({"visual", "collision"})  # the children URDF reads more than one of


def _rename(el: etree._Element, context: str, suggested: str | None) -> Repair | None:
    """Rename a misspelt element to the suggested name when nothing else is as close."""
    if suggested is None or context == "robot":
        return None  # a whole link or joint appearing is not a spelling fix: left to you
    tag = str(el.tag)
    found = ranked(tag, SPECS[context].children)
    if not found or found[0][2] != suggested:
        return None
    if len(found) > 1 and found[0][:2] == found[1][:2]:
        return None  # two names as close: not certain
    if not same_digits(tag, suggested):
        return None
    parent = el.getparent()
    if suggested not in MANY and parent is not None and children(parent, suggested):
        return None  # URDF reads only the first one: the two would compete
    return Repair("safe", f"rename <{tag}> to <{suggested}>", (RenameElement(el, suggested),))
