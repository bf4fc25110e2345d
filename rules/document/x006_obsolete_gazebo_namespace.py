"""The file declares the obsolete Player/Stage Gazebo XML namespaces.

## What it does
Reports the `xmlns:*="http://playerstage.sourceforge.net/gazebo/xmlschema/#..."`
declarations (usually `controller`, `interface`, `sensor`, `body`, `geom`...),
once per element that declares them: `<robot>` or any other element.

## Why is this bad?
These namespaces belong to the Gazebo 0.x XML schema of the Player/Stage era.
No URDF consumer reads them: urdfdom, Gazebo Classic, gz-sim (sdformat), MuJoCo,
Drake and PyBullet all ignore them. The Gazebo "Using a URDF in Gazebo" tutorial
lists removing them as a step of making a URDF work in Gazebo; keeping them
suggests the file still targets a simulator that no longer exists, and a
prefix such as `xacro` bound to one of them hides real xacro elements from
xacro.

## How to fix
Delete the `xmlns:...="http://playerstage.sourceforge.net/..."` attributes from
`<robot>`. Keep `xmlns:xacro="http://www.ros.org/wiki/xacro"` if the file is a
xacro source.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, local_tag
from urdflint.model.edits import RemoveAttribute, Repair
from urdflint.model.finding import Severity

PLAYERSTAGE = "playerstage.sourceforge.net/gazebo/xmlschema"


@rule(
    "X006",
    "obsolete-gazebo-namespace",
    Severity.WARNING,
    fix="Delete the Player/Stage xmlns declaration; no current parser reads it.",
    fixable="safe",
)
def check(doc: Document) -> Iterator[Hit]:
    if b"playerstage" not in doc.source:
        return  # no declaration to find: skip the walk
    for el in _declaring(doc.robot):
        parent = el.getparent()
        inherited = parent.nsmap if parent is not None else {}
        names = [
            f"xmlns:{prefix}" if prefix else "xmlns"
            for prefix, uri in sorted(el.nsmap.items(), key=lambda kv: kv[0] or "")
            if PLAYERSTAGE in uri and inherited.get(prefix) != uri
        ]
        repair = Repair(
            "safe",
            "delete the Player/Stage namespace declarations",
            tuple(RemoveAttribute(el, name) for name in names),
        )
        if len(names) == 1:
            message = f"<{local_tag(el)}> declares the obsolete Gazebo namespace {names[0]}"
            yield Hit(el, message, repair=repair)
        elif names:
            yield Hit(
                el,
                f"<{local_tag(el)}> declares {len(names)} obsolete Gazebo namespaces: "
                + ", ".join(names),
                repair=repair,
            )


def _declaring(robot: etree._Element) -> list[etree._Element]:
    """The elements that declare a namespace, in document order (the others inherit their
    parent's namespaces and declare nothing obsolete)."""
    found: list[etree._Element] = []
    declared = False
    for event, item in etree.iterwalk(robot, events=("start-ns", "start")):
        if event == "start-ns":
            declared = True  # a declaration of the element whose start comes next
        elif declared:
            found.append(item)
            declared = False
    return found
