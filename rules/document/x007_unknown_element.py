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
"""

from __future__ import annotations

import difflib
from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.schema import SPECS, describe, homes, walk

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
)
def check(doc: Document) -> Iterator[Hit]:
    for visit in walk(doc.robot):
        if visit.key is not None:
            continue
        el = visit.element
        if visit.parent_key == "geometry" and not homes(el.tag):
            continue  # an unknown shape is C003 invalid-geometry's (an error there)
        where = describe(el.getparent())
        hint = _hint(el.tag, visit.parent_key)
        suffix = f" ({hint})" if hint else ""
        yield Hit(el, f"<{el.tag}> is not a URDF element of {where}{suffix}")


def _hint(tag: str, context: str) -> str | None:
    if (context, tag) in HINTS:
        return HINTS[(context, tag)]
    places = [p for p in homes(tag) if p != context]
    if places:
        if places == ["robot"]:
            return "it belongs at the top level, directly inside <robot>"
        names = [f"<{p}>" for p in places]
        listed = names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1]
        return f"it belongs inside {listed}"
    close = difflib.get_close_matches(tag, list(SPECS[context].children), n=1, cutoff=0.75)
    return f"did you mean <{close[0]}>?" if close else None
