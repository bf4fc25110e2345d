"""A visual refers to a material that is defined nowhere, or a material has no colour or texture.

## What it does
Reports a visual's `<material name="x"/>` that has no `<color>`/`<texture>`
of its own when no robot-level `<material name="x">` defines it and no earlier
visual defined it inline (a later inline definition does not count: urdfdom
and Drake read links in order). Also reports a robot-level `<material>` with
neither a `<color rgba>` nor a `<texture filename>`.

## Why is this bad?
An empty robot-level material makes Drake refuse the model ("Material 'x'
not previously defined, but has no color or texture information"), and
urdfdom logs "Material [x] color has no rgba" then "Material [x] not defined
in file". For a visual that refers to an undefined name urdfdom warns "link
'L' material 'x' undefined" (`check_urdf` still ends with "Successfully
Parsed XML") and gives the visual an empty material, so RViz and Gazebo Sim
draw it in a default colour instead of the one the author meant; when a
later visual does define the name, urdfdom hands that visual the empty
material too. Drake, MuJoCo, PyBullet and Pinocchio load such a reference
without a word, so this is a warning.

## How to fix
Define the material once at robot level,
`<material name="orange"><color rgba="1 0.5 0 1"/></material>`, and refer to
it by name; or give the visual's `<material>` its own `<color>`. Check the
spelling of the name (material names are case-sensitive).
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import did_you_mean, q


def _has_definition(material: etree._Element) -> bool:
    color = material.find("color")
    texture = material.find("texture")
    return (color is not None and color.get("rgba") is not None) or bool(
        texture is not None and (texture.get("filename") or "").strip()
    )


@rule("S009", "undefined-material", Severity.WARNING)
def check(doc: Document) -> Iterator[Hit]:
    known: dict[str, None] = {}  # ordered, for stable suggestions
    for material in doc.materials:
        name = material.get("name")
        if name is None:
            continue
        known[name] = None
        if not _has_definition(material):
            yield Hit(
                material,
                f"material {name!r} has neither a color nor a texture",
                fix='Add <color rgba="r g b a"/> (or a <texture filename=".."/>) to the material.',
            )
    uses = [(link, v.find("material")) for link in doc.links for v in link.visuals]
    inline = {
        m.get("name"): link for link, m in reversed(uses) if m is not None and _has_definition(m)
    }
    for link, material in uses:
        name = material.get("name") if material is not None else None
        if material is None or name is None:
            continue
        if _has_definition(material):
            known[name] = None
        elif name not in known:
            later = inline.get(name)
            where = f"only defined later, in link {later.name!r}" if later else "not defined"
            yield Hit(
                material,
                f"visual of link {q(link.name)} uses material {name!r}, which is {where}",
                fix=did_you_mean(name, known, "material")
                or "Define the material at robot level or give this <material> a <color>.",
            )
