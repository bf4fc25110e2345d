"""A robot, link, joint or material has no `name`, or an empty one.

## What it does
Reports `<robot>`, `<link>`, `<joint>`, a top-level `<material>` and the
`<material>` of a `<visual>` whose `name` attribute is missing or blank.

## Why is this bad?
Names are how URDF refers to everything: joints name their parent and child
links, visuals name their material, controllers and TF name joints and links.
urdfdom (and with it ROS, Gazebo's URDF import and Pinocchio) refuses the whole
model: "No name given for the robot.", "No name given for the link.",
"unnamed joint found", "Material must contain a name attribute" and "Visual
material must contain a name attribute". PyBullet fails the same way, Drake
wants a robot name, and MuJoCo silently skips unnamed materials. An empty
`name=""` passes the parsers but produces a robot, link or joint nobody can
refer to (an error too).

An empty material name is a warning: a top-level `<material name="">` or a
visual's `<material name=""/>` reference without a colour of its own defines
or finds nothing. A visual's `<material name="">` that carries its own
`<color>` or `<texture>` is not reported: the SolidWorks exporter writes it
for every link, and urdfdom, Gazebo, MuJoCo and PyBullet use the inline colour
without looking the name up.

## How to fix
Give the element a unique, non-empty `name`. A visual's colour still needs a
name even when it is defined inline: `<material name="red"><color rgba="1 0 0 1"/></material>`.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity
from urdflint.model.schema import owner


@rule("X003", "missing-name", Severity.ERROR, fix="Add a unique, non-empty name attribute.")
def check(doc: Document) -> Iterator[Hit]:
    # A xacro library's <robot> is only a wrapper for its macros: it needs no name.
    named: list[tuple[etree._Element, str]] = [] if doc.library else [(doc.robot, "<robot>")]
    named += [(link.element, "<link>") for link in doc.links]
    named += [(joint.element, "<joint>") for joint in doc.joints]
    named += [(material, "top-level <material>") for material in doc.materials]
    for link in doc.links:
        for visual in link.visuals:
            what = f"<material> of a visual of {owner(visual)}"
            named += [(m, what) for m in children(visual, "material")]
    for el, what in named:
        name = el.get("name")
        if name is None:
            yield Hit(el, f"{what} has no name")
        elif not name.strip():
            if el.tag != "material":
                yield Hit(el, f"{what} has an empty name")
            elif not _inline(el):
                yield Hit(el, f"{what} has an empty name", severity=Severity.WARNING)


def _inline(material: etree._Element) -> bool:
    """A visual material that defines its own colour or texture (needs no lookup)."""
    parent = material.getparent()
    own = material.find("color") is not None or material.find("texture") is not None
    return own and parent is not None and parent.tag == "visual"
