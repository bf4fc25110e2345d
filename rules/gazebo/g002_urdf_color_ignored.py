"""A link is coloured only by URDF `<material><color>`, which Gazebo Classic ignores.

## What it does
Flags each link with a visual whose `<material>` carries a colour (inline `<color>` or a
robot-level `<material>` with a `<color>`) when the link has no
`<gazebo reference="link"><material>` and no `<gazebo reference="link"><visual><material>`.
Only primitives and STL meshes are checked: Collada (`.dae`), OBJ and other meshes carry
their own colours and textures, which Gazebo uses. Mid greys (r = g = b within 0.05,
brightness 0.4-0.8) are skipped, since they look like Gazebo's default anyway. One
finding per link, on the first coloured visual's `<material>`. The finding is a warning
only when the file has `<gazebo>` blocks; a file without any is most likely a pure
description (RViz, MoveIt, MuJoCo) or keeps its Gazebo extensions elsewhere (info).

## Why is this bad?
Gazebo Classic (sdformat 9) drops URDF colours when it converts the model to SDF: the
tutorial says this "does not work in Gazebo as it adopts OGRE's material scripts", so a
robot that is orange in RViz is plain grey in simulation. Gazebo Sim (sdformat >= 11.2,
gazebosim/sdformat#526) converts the colour into an SDF `<material>` with
`<diffuse>`/`<ambient>`, so under the `gz-sim` target this is only a portability note
(info). Fixed-joint lumping does not change this: a lumped link's visuals keep the
material of the `<gazebo>` block that names the lumped link, never that of the parent.

## How to fix
Add `<gazebo reference="link"><material>Gazebo/Orange</material></gazebo>` (a stock
Gazebo Classic material script), or, for both simulators, an SDF material in a visual
blob: `<gazebo reference="link"><visual><material>` with `<ambient>` and `<diffuse>`.
Or accept the grey if the robot is never simulated in Gazebo Classic.

`urdflint fix` writes the second form, in the link's `<gazebo reference>` block or in a
new one after the `<link>`, with the values Gazebo Sim derives from the URDF colour
(`<ambient>` and `<diffuse>` both rgb / 0.8, capped at 1, and the same alpha; sdformat's
`parser_urdf.cc`, gazebosim/sdformat#526): Gazebo Sim shows the link exactly as before,
and Gazebo Classic now the same. It does so when the finding is a warning (a file with
`<gazebo>` blocks, for Gazebo Classic) and every visual of the link has that same colour,
since the blob colours all of them; not in xacro sources, where the link may be written
in a macro.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model import targets
from urdflint.model.document import Document, Link, children
from urdflint.model.edits import InsertChild, Repair
from urdflint.model.finding import Severity
from urdflint.model.gazebo_spec import blocks_for, keys_of
from urdflint.model.values import fmt, vector, xml_attribute

# Achromatic colours in this brightness band look like Gazebo's default grey anyway.
GREY_SPREAD, GREY_LOW, GREY_HIGH = 0.05, 0.4, 0.8


@rule(
    "G002",
    "urdf-color-ignored",
    Severity.WARNING,
    fix='Add <gazebo reference="link"><material>Gazebo/...</material></gazebo> for the link.',
    targets=targets.GAZEBO,
    fixable="safe",
)
def check(doc: Document) -> Iterator[Hit]:
    classic = "gazebo-classic" in doc.targets
    # A file without any <gazebo> element is most likely a pure description (RViz, MoveIt,
    # MuJoCo...) or keeps its Gazebo extensions elsewhere: a note, not a warning.
    severity = Severity.WARNING if classic and doc.gazebo else Severity.INFO
    for link in doc.links:
        if link.name is None or _has_gazebo_material(doc, link.name):
            continue
        for visual in link.visuals:
            found = _colour(doc, visual)
            if found is None:
                continue
            material, label, _ = found
            if classic:
                tail = " (Gazebo Sim converts it)" if "gz-sim" in doc.targets else ""
                message = (
                    f"Gazebo Classic ignores the colour{label} of link {link.name!r} "
                    f"and shows the link grey{tail}"
                )
            else:
                message = (
                    f"link {link.name!r} is coloured only by its URDF colour{label}, "
                    "which Gazebo Sim converts but Gazebo Classic ignores"
                )
            repair = _repair(doc, link) if severity is Severity.WARNING else None
            yield Hit(material, message, severity=severity, repair=repair)
            break


def _has_gazebo_material(doc: Document, name: str) -> bool:
    for gazebo in blocks_for(doc, name):
        for el in keys_of(gazebo):
            if el.tag == "material":
                return True
            if el.tag == "visual" and el.find("material") is not None:
                return True
    return False


def _colour(
    doc: Document, visual: etree._Element
) -> tuple[etree._Element, str, etree._Element] | None:
    """The visual's ``<material>``, a label for it and its ``<color>``, when it sets a colour
    Gazebo drops."""
    material = visual.find("material")
    if material is None or _own_colours(visual):
        return None
    name = material.get("name")
    label = f" {name!r}" if name else ""
    colour = material.find("color")
    if colour is None:
        defined = doc.material_map.get(name or "")
        colour = defined.find("color") if defined is not None else None
    if colour is None or _mid_grey(colour):
        return None
    return material, label, colour


def _mid_grey(colour: etree._Element) -> bool:
    """A grey close to Gazebo's own default (nothing visibly lost), or unreadable (X004)."""
    rgba = vector(colour, "rgba", 4)
    if rgba is None:
        return True
    r, g, b, _ = rgba
    return max(r, g, b) - min(r, g, b) <= GREY_SPREAD and GREY_LOW <= (r + g + b) / 3 <= GREY_HIGH


def _own_colours(visual: etree._Element) -> bool:
    mesh = visual.find("geometry/mesh")
    if mesh is None:
        return False
    filename = (mesh.get("filename") or "").lower()
    return not filename.endswith(".stl")


def _repair(doc: Document, link: Link) -> Repair | None:
    """An SDF material with the link's URDF colour, in a ``<visual>`` blob of its
    ``<gazebo reference>`` block (which colours every visual of the link)."""
    if doc.origin is not None or link.name is None:
        return None  # xacro: the link may be written in a macro, for several names
    found = [_colour(doc, v) for v in link.visuals]
    colours = {vector(f[2], "rgba", 4) if f else None for f in found}
    colour = colours.pop() if len(colours) == 1 else None
    blocks = blocks_for(doc, link.name)
    if colour is None or any(k.tag == "visual" for g in blocks for k in keys_of(g)):
        return None  # visuals of different colours, or a visual blob already there
    rgba = _gz_sim(colour)
    material = f"<ambient>{rgba}</ambient>\n<diffuse>{rgba}</diffuse>"
    visual = f"<visual>\n  <material>\n{_indent(material, 4)}\n  </material>\n</visual>"
    description = f"give link {link.name!r} its colour in Gazebo Classic too ({rgba})"
    if blocks:
        last = children(blocks[0])
        op = InsertChild(blocks[0], visual, after=last[-1] if last else None)
        return Repair("safe", description, (op,))
    name = xml_attribute(link.name)
    block = f'<gazebo reference="{name}">\n{_indent(visual, 2)}\n</gazebo>'
    return Repair("safe", description, (InsertChild(doc.robot, block, after=link.element),))


def _gz_sim(rgba: tuple[float, ...]) -> str:
    """What sdformat's URDF converter writes for a URDF colour (diffuse rgb / 0.8, ambient
    0.5 * rgb / 0.4: the same), as Gazebo Sim shows it."""
    *rgb, alpha = rgba
    return " ".join([*(fmt(min(max(c / 0.8, 0.0), 1.0)) for c in rgb), fmt(alpha)])


def _indent(xml: str, width: int) -> str:
    return "\n".join(" " * width + line for line in xml.split("\n"))
