"""A joint's `<parent>` or `<child>` names a link that does not exist.

## What it does
Reports the `<parent link="..">` or `<child link="..">` element of a joint
when no `<link>` of that name is defined, and suggests the closest existing
link name. A `<parent>`/`<child>` that is missing, or has no `link`
attribute, is S007's job.

## Why is this bad?
urdfdom refuses the model ("Failed to build tree: child link [X] of joint
[Y] not found", the same for a parent), and with it ROS, `check_urdf`,
Gazebo's URDF converter and Pinocchio. Drake ("Could not find link named
'X'"), MuJoCo ("URDF joint parent or child missing") and PyBullet ("Cannot
find child link for joint") refuse it too, and yourdfpy fails with a
`ValueError`.

## How to fix
Correct the spelling of the link name, or add the missing `<link>`. If the
parent is meant to be the world, add `<link name="world"/>` explicitly.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.effects import single
from urdflint.model.finding import Severity
from urdflint.model.structure import did_you_mean, q


@rule(
    "S003",
    "undefined-link",
    Severity.ERROR,
    fix="Correct the link name or define the link.",
    effects=single(K.UNDEFINED_LINK),
)
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        for role in ("parent", "child"):
            element = joint.find(role)
            name = (element.get("link") or "") if element is not None else ""
            if element is None or not name.strip() or name in doc.link_map:
                continue
            yield Hit(
                element,
                f"{role} link {name!r} of joint {q(joint.name)} is not defined",
                fix=did_you_mean(name, doc.link_map, "link"),
            )
