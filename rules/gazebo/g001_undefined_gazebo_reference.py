"""A `<gazebo reference="X">` block names neither a link nor a joint.

## What it does
Flags `<gazebo>` blocks whose `reference` matches no `<link>` and no `<joint>` of the
robot, and suggests the closest existing name. The block's contents are still checked in
the same run (G003-G007 read them as meant for a link or a joint), so correcting the
reference does not reveal a second round of findings.

## Why is this bad?
sdformat's URDF converter (used by both Gazebo Classic and Gazebo Sim) files every
`<gazebo>` block under its reference name and only looks those names up while it writes
links and joints. A block for a name that does not exist is dropped without any message,
not even in `gz sdf -p` or the verbose log: its friction, material, sensors and plugins
silently vanish. This usually happens after a link is renamed or removed, or when a
xacro prefix is missing.

## How to fix
Point `reference` at an existing link or joint (mind xacro prefixes such as `left_`),
or delete the block if the element it configured is gone.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.gazebo_spec import scopes_of, suggest
from urdflint.model.values import has_xacro


@rule(
    "G001",
    "undefined-gazebo-reference",
    Severity.ERROR,
    fix="Rename the reference to an existing link or joint, or remove the block.",
)
def check(doc: Document) -> Iterator[Hit]:
    names = [*doc.link_map, *doc.joint_map]
    for gazebo in doc.gazebo:
        ref = gazebo.get("reference")
        if not ref or has_xacro(ref) or scopes_of(doc, gazebo) is not None:
            continue
        guess = suggest(ref, names)
        hint = f" (did you mean {guess!r}?)" if guess else ""
        yield Hit(gazebo, f"<gazebo reference={ref!r}> names no link or joint{hint}")
