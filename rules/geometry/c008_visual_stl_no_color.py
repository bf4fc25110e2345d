"""An STL visual has no colour and its link no Gazebo material: Gazebo Classic draws it grey.

## What it does
Under the `gazebo-classic` target, in a file that has `<gazebo>` blocks (a
model meant for Gazebo), reports a link whose `<visual>` is an STL mesh when
the link has no `<gazebo reference="link"><material>` (or
`<visual><material>`) and none of its visuals carries a URDF colour. One
finding per link, on the first such `<mesh>`. Links whose visuals do carry a
URDF colour are G002's (urdf-color-ignored), so the two rules never report
the same link.

## Why is this bad?
STL stores triangles only, no colour or texture, so Gazebo Classic draws it
with its default material: every such part of the robot comes out the same
flat grey. Collada (`.dae`) and OBJ (with its `.mtl`) carry their own colours
and textures, which Gazebo uses. Gazebo Sim converts URDF colours, which is
why the rule only concerns Gazebo Classic. Only the look suffers: this is a
note, not a defect.

## How to fix
Give the link a Gazebo material,
`<gazebo reference="link"><material>Gazebo/DarkGrey</material></gazebo>`,
or export the visual as Collada with its colours.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.gazebo_spec import blocks_for, keys_of
from urdflint.model.structure import q
from urdflint.sources.mesh_formats import suffix

STL = frozenset({"stl", "stla", "stlb"})


@rule(
    "C008",
    "visual-stl-no-color",
    Severity.INFO,
    fix='Add <gazebo reference="link"><material>Gazebo/...</material></gazebo>, '
    "or use a Collada visual.",
)
def check(doc: Document) -> Iterator[Hit]:
    if "gazebo-classic" not in doc.targets or not doc.gazebo:
        return
    for link in doc.links:
        if link.name is None or _has_gazebo_material(doc, link.name):
            continue
        if any(_urdf_colour(doc, visual) for visual in link.visuals):
            continue  # G002's finding (or a grey it deliberately accepts)
        for visual in link.visuals:
            mesh = visual.find("geometry/mesh")
            if mesh is not None and suffix(mesh.get("filename") or "") in STL:
                uri = (mesh.get("filename") or "").strip()
                yield Hit(
                    mesh,
                    f"Gazebo Classic draws link {q(link.name)} plain grey: its visual mesh "
                    f"{uri!r} is STL, which has no colour, and the link has no Gazebo material",
                )
                break


def _has_gazebo_material(doc: Document, name: str) -> bool:
    for gazebo in blocks_for(doc, name):
        for el in keys_of(gazebo):
            if el.tag == "material" or (el.tag == "visual" and el.find("material") is not None):
                return True
    return False


def _urdf_colour(doc: Document, visual: etree._Element) -> bool:
    """Whether the visual's ``<material>`` gives a colour (inline or by a robot-level name)."""
    material = visual.find("material")
    if material is None:
        return False
    if material.find("color") is not None:
        return True
    defined = doc.material_map.get(material.get("name") or "")
    return defined is not None and defined.find("color") is not None
