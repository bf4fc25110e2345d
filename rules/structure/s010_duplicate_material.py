"""Two robot-level `<material>` elements share a name.

## What it does
Reports every robot-level `<material>` whose `name` was already used by an
earlier robot-level material, and names the line of the first definition. It
does so even when both definitions give the same colour. A visual's own
`<material name="x"><color .../></material>` is not a robot-level definition
and is not counted. Materials without a name are X003's.

## Why is this bad?
urdfdom refuses the whole model with "material 'X' is not unique." (verified
with `check_urdf` from urdfdom 3.0.1 and 6.0.0: "ERROR: Model Parsing the xml
failed"), and with it ROS (`robot_state_publisher`, RViz, MoveIt), kdl_parser,
Pinocchio and Gazebo's URDF converter. Drake refuses it as well ("Material 'X'
was previously defined"). PyBullet warns "Duplicate material" and loads it;
MuJoCo and yourdfpy load it silently, so different tools show different
colours. Duplicates usually come from including a xacro file that defines
its colours twice, or from two macros that each define the same colour.

## How to fix
Keep a single definition of each material name (move shared colours into one
xacro file included once), or rename one of them and the visuals that use it.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import q, written_at


@rule(
    "S010",
    "duplicate-material",
    Severity.ERROR,
    fix="Define each material name once at robot level, or rename one of them.",
)
def check(doc: Document) -> Iterator[Hit]:
    first: dict[str, etree._Element] = {}
    for material in doc.materials:
        name = material.get("name")
        if name is None or not name.strip():
            continue
        if name in first:
            yield Hit(
                material,
                f"material {q(name)} is defined again "
                f"(first defined on {written_at(doc, first[name])})",
            )
        else:
            first[name] = material
