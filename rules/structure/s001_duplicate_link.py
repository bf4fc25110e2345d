"""Two `<link>` elements share a name.

## What it does
Reports every `<link>` whose `name` was already used by an earlier link, and
names the line of the first definition.

## Why is this bad?
urdfdom refuses the whole model with "link 'X' is not unique", and with it
ROS, `check_urdf`, Gazebo's URDF converter and Pinocchio. PyBullet ("Link
name is not unique, link names in the same model have to be unique"),
MuJoCo ("repeated URDF name") and Drake ("already contains a body named 'X'")
refuse it too. yourdfpy loads it without a word; tools that look links up by
name then find one of the two, so joints, `<gazebo reference>` blocks and
SRDF entries may end up attached to a body you did not mean.

## How to fix
Rename one of the links (and the joints that refer to it), or delete the
copy. Duplicates usually come from including a xacro macro twice with the
same `prefix`.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.effects import single
from urdflint.model.finding import Severity
from urdflint.model.structure import q, written_at


@rule(
    "S001",
    "duplicate-link",
    Severity.ERROR,
    fix="Rename or remove one of the two links.",
    effects=single(K.DUPLICATE_LINK),
)
def check(doc: Document) -> Iterator[Hit]:
    for link in doc.links:
        first = doc.link_map.get(link.name) if link.name is not None else None
        if first is not None and first is not link:
            yield Hit(
                link.element,
                f"link {q(link.name)} is defined again "
                f"(first defined on {written_at(doc, first.element)})",
            )
