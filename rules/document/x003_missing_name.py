"""A robot, link, joint or material has no `name`, or an empty one.

## What it does
Reports `<robot>`, `<link>`, `<joint>`, a top-level `<material>` and the
`<material>` of a `<visual>` whose `name` attribute is missing or blank.

## Why is this bad?
Names are how URDF refers to everything: joints name their parent and child
links, visuals name their material, controllers and TF name joints and links.
What a missing name costs depends on the element (observed with `check_urdf`
3.0.1, Pinocchio 4.1, sdformat 12.3, PyBullet 3.2.7, MuJoCo 4.0 and Drake 1.51):

- a `<robot>`, `<link>` or `<joint>` without `name`: urdfdom refuses the whole
  model ("No name given for the robot.", "No name given for the link.",
  "unnamed joint found"), and so do ROS, Pinocchio, sdformat (Gazebo), PyBullet
  and Drake. MuJoCo refuses a nameless link or joint too ("required attribute
  missing: 'name'") and only accepts a nameless robot;
- a top-level `<material>` without `name`: urdfdom skips that material ("Material
  must contain a name attribute") and loads the rest; Drake refuses the model
  ("Material tag is missing a required name");
- a visual's `<material>` without `name`: urdfdom drops the visual ("Visual
  material must contain a name attribute", "Could not parse visual element for
  Link") together with every collision of that link, and PyBullet refuses the
  file ("failed to parse link");
- an empty `name=""` passes urdfdom's attribute check but produces a link or
  joint nobody can refer to: urdfdom then refuses a joint whose child is `""`
  ("missing a parent and/or child link specification"), PyBullet crashes on a
  joint named `""`, sdformat refuses it ("Empty string used when setting a
  required parameter"). These are errors.

An empty *robot* name depends on the target: urdfdom, Pinocchio, PyBullet and
MuJoCo load such a robot, but sdformat refuses it ("Empty string used when
setting a required parameter. Key[name]"), so Gazebo cannot spawn it, and Drake
aborts the process. It is an error when a Gazebo target (`gazebo-classic`,
`gz-sim`) is selected and a warning otherwise (`--target mujoco`).

An empty material name is a warning: a top-level `<material name="">` or a
visual's `<material name=""/>` reference without a colour of its own defines
or finds nothing (Drake refuses the former). A visual's `<material name="">` that
carries its own `<color>` or `<texture>` is not reported: the SolidWorks exporter
writes it for every link, and urdfdom, Gazebo, MuJoCo and PyBullet use the inline
colour without looking the name up.

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
from urdflint.model.targets import GAZEBO


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
            if el is doc.root:
                yield _empty_robot_name(doc)
            elif el.tag != "material":
                yield Hit(el, f"{what} has an empty name")
            elif not _inline(el):
                yield Hit(el, f"{what} has an empty name", severity=Severity.WARNING)


def _empty_robot_name(doc: Document) -> Hit:
    """An empty robot name only breaks sdformat (Gazebo) and Drake: an error for Gazebo."""
    if doc.targets.intersection(GAZEBO):
        return Hit(doc.robot, "<robot> has an empty name, which sdformat (Gazebo) refuses")
    return Hit(
        doc.robot,
        "<robot> has an empty name; urdfdom and MuJoCo accept it, sdformat (Gazebo) and "
        "Drake refuse it",
        severity=Severity.WARNING,
    )


def _inline(material: etree._Element) -> bool:
    """A visual material that defines its own colour or texture (needs no lookup)."""
    parent = material.getparent()
    own = material.find("color") is not None or material.find("texture") is not None
    return own and parent is not None and parent.tag == "visual"
