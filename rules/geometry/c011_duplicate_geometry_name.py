"""Two `<visual>` or two `<collision>` elements of a link share a name.

## What it does
Reports a `<visual name="x">` when an earlier visual of the same link already
has that name, and likewise for `<collision>`. A visual and a collision may
share a name (every consumer keeps them apart). When MuJoCo is a target, a
collision whose name was already used by a collision of another link is
reported too: MuJoCo's geom names are global to the model.

## Why is this bad?
A geometry's name is how simulators and tools tell the shapes of a link
apart (Drake's `SceneGraph` names, MuJoCo's geom names), and a repeated name
does not survive loading:
- Drake renames the second one and warns: "collision name 'hull' has already
  been used, renaming to 'hull_1' instead" (the same for visuals);
- MuJoCo drops the name: "Geom with duplicate name 'hull' encountered in
  URDF, creating an unnamed geom", for collision names repeated anywhere in
  the model (visuals are discarded by default);
- urdfdom (`check_urdf`), PyBullet and Pinocchio accept the file and ignore
  the names, and sdformat's converter names SDF elements by position
  (`NAME_collision`, `NAME_collision_1`, ...), so Gazebo shows neither an
  error nor a warning.
Nothing refuses the model, which is why this is a warning; the duplicate
usually comes from copy-pasting a visual block or a xacro macro with a fixed
`name`.

## How to fix
Give each visual and each collision of a link its own name (a suffix such as
`_front`, `_rear`), or drop the `name` attribute where nothing refers to it.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, Link
from urdflint.model.finding import Severity
from urdflint.model.structure import q, written_at


@rule(
    "C011",
    "duplicate-geometry-name",
    Severity.WARNING,
    fix="Give each visual and collision of the link a unique name.",
)
def check(doc: Document) -> Iterator[Hit]:
    for link in doc.links:
        for tag in ("visual", "collision"):
            yield from _within(doc, link, tag)
    if "mujoco" in doc.targets:
        yield from _across_links(doc)


def _within(doc: Document, link: Link, tag: str) -> Iterator[Hit]:
    seen: dict[str, etree._Element] = {}
    for el in link.visuals if tag == "visual" else link.collisions:
        name = el.get("name")
        if not name:
            continue
        first = seen.setdefault(name, el)
        if first is not el:
            yield Hit(
                el,
                f"link {q(link.name)} has a second <{tag}> named {name!r} "
                f"(first on {written_at(doc, first)})",
                attribute="name",
            )


def _across_links(doc: Document) -> Iterator[Hit]:
    owner: dict[str, Link] = {}
    for link in doc.links:
        names = {el.get("name") for el in link.collisions} - {None, ""}
        for el in link.collisions:
            name = el.get("name")
            first = owner.get(name or "")
            if name and first is not None and first is not link:
                yield Hit(
                    el,
                    f"collision {name!r} of link {q(link.name)} has the name of a collision of "
                    f"link {q(first.name)}; MuJoCo's geom names are global, so it becomes an "
                    "unnamed geom",
                    attribute="name",
                )
        for name in names:
            owner.setdefault(str(name), link)
