"""A material's `<color rgba>` has a component outside [0, 1], or no `rgba` beside a texture.

## What it does
Checks the `<color>` of every robot-level `<material>` and of every visual's
`<material>`, the two places urdfdom reads colours, and reports:

- an `rgba` with a component below 0 or above 1, typically 0-255 values such as
  `rgba="255 128 0 255"`;
- a `<color>` without `rgba` in a material that also has a
  `<texture filename>`.

A material with a `<color>` without `rgba` and no texture defines nothing,
and S009 reports it. Malformed numbers and a count other than four are X004's and
X005's. Materials inside `<collision>` and `<gazebo>` blocks are not checked:
urdfdom does not read them.

## Why is this bad?
urdfdom (urdfdom_headers `color.h`) rejects an out-of-range component and logs
"Material [X] has malformed color rgba values" (urdfdom 3.0.1 with
urdfdom_headers 1.0.5 words the reason "Unable to parse component [2] to a
double", newer headers "Component [..] is outside the valid range for colors
[0, 1]"). `check_urdf` prints the error and still ends with "Successfully
Parsed XML". What is left depends on where the colour is: a robot-level
material is kept with its colour reset to opaque black (Pinocchio 4.1 loads
the visual as 0 0 0 1), while a visual's own material is dropped ("link 'X'
material 'Y' undefined"), so the visual gets the default colour (Pinocchio:
0.9 grey); RViz and Gazebo Sim, which take colours from urdfdom, show the
same. Drake refuses the model ("Rgba values must be within the range [0,
1]"). PyBullet and MuJoCo pass the numbers on unchecked, so the same file
shows different colours in different tools. That is a warning: everything
but Drake loads the model, and only the colour is wrong.

A `<color>` without `rgba` beside a texture is ignored by urdfdom, but Drake
("Failed to parse 'rgba' attribute of <color>") and MuJoCo ("required
attribute missing: 'rgba'") refuse the model, so that case is an error.

## How to fix
Write each component as a fraction from 0 to 1: divide 0-255 values by 255, so
`rgba="255 128 0 255"` becomes `rgba="1 0.5 0 1"`. Give every `<color>` its
`rgba`, or delete an empty `<color>` from a textured material.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity
from urdflint.model.schema import owner
from urdflint.model.values import fmt, parse_numbers


def _materials(doc: Document) -> Iterator[etree._Element]:
    yield from doc.materials
    for link in doc.links:
        for visual in link.visuals:
            yield from children(visual, "material")


def _textured(material: etree._Element) -> bool:
    texture = material.find("texture")
    return texture is not None and bool((texture.get("filename") or "").strip())


def _label(material: etree._Element) -> str:
    name = material.get("name")
    label = f"material {name!r}" if name else "an unnamed material"
    parent = material.getparent()
    return (
        label if parent is not None and parent.tag == "robot" else f"{label} of {owner(material)}"
    )


@rule(
    "C010",
    "invalid-color",
    Severity.WARNING,
    fix='Write each rgba component as a fraction from 0 to 1, e.g. rgba="1 0.5 0 1".',
)
def check(doc: Document) -> Iterator[Hit]:
    for material in _materials(doc):
        color = material.find("color")  # urdfdom reads the first one
        if color is None:
            continue
        raw = color.get("rgba")
        if raw is None:
            if _textured(material):
                yield Hit(
                    color,
                    f"<color> of {_label(material)} has no rgba; urdfdom ignores it, "
                    "Drake and MuJoCo refuse the model",
                    fix="Add rgba to the <color> or delete it: the texture colours the visual.",
                    severity=Severity.ERROR,
                )
            continue
        values = parse_numbers(raw)
        if values is None or len(values) != 4:
            continue  # X004, X005
        outside = [v for v in values if not 0.0 <= v <= 1.0]
        if outside:
            shown = ", ".join(fmt(v) for v in outside)
            noun = "component" if len(outside) == 1 else "components"
            parent = material.getparent()
            kept = parent is not None and parent.tag == "robot"
            effect = "replaces the colour with opaque black" if kept else "drops the material"
            yield Hit(
                color,
                f"<color> of {_label(material)} has {noun} {shown} outside [0, 1]; "
                f"urdfdom {effect} and Drake refuses the model",
            )
