"""The robot has no `<link>` at all.

## What it does
Reports a `<robot>` with no `<link>` child, once, on the `<robot>` element.
Expanded xacro files without links are libraries of macros or fragments and
are reported by X011 instead (only document rules run on them); a `.urdf` file
that still holds xacro definitions (an unexpanded library) is left to X008, and
a file that is not well-formed XML to X001.

## Why is this bad?
urdfdom refuses the model ("No link elements found in urdf file"), and with it
ROS, `check_urdf`, sdformat/Gazebo and Pinocchio; PyBullet refuses it too ("No
links found in URDF file"). Drake and MuJoCo load an empty model without a
word, so a simulation silently contains no robot. It usually means a xacro
file was expanded without the argument that enables its body, or that a
fragment (materials, Gazebo blocks) was handed over as the robot.

## How to fix
Check the right file: the robot's entry xacro or its expanded URDF, not a
fragment. If the file is expanded from xacro, pass the arguments that make it
write its links.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity
from urdflint.model.schema import is_xacro


@rule(
    "S011",
    "no-links",
    Severity.ERROR,
    fix="Check the robot's entry file (or pass the xacro arguments that write its links).",
)
def check(doc: Document) -> Iterator[Hit]:
    if doc.links or doc.library or getattr(doc, "recovered", False):
        return  # a tree libxml2 rebuilt from broken XML (X001) may have lost its links
    if any(is_xacro(el) for el in doc.robot.iter() if isinstance(el.tag, str)):
        return  # an unexpanded xacro library saved as .urdf: X008
    found = children(doc.robot)
    what = ", ".join(sorted({f"<{el.tag}>" for el in found if isinstance(el.tag, str)}))
    contents = f" (it holds {what})" if what else ""
    yield Hit(doc.robot, f"robot {doc.robot.get('name')!r} has no <link>{contents}")
