"""More than one link has no parent joint: the model is not one connected tree.

## What it does
Finds the links that no joint names as its child. The one carrying the
largest subtree is the robot's root; every other one is reported on its
`<link>`, naming the main root. A link that is only a root because its
parent joint names an undefined parent (S003) or lacks a `<parent>` (S007) is
left to those rules.

## Why is this bad?
urdfdom refuses the model ("Failed to find root link: Two root links found:
[a] and [b]"), and with it ROS, `check_urdf`, Gazebo's URDF converter and
Pinocchio. PyBullet crashes with a segmentation fault. MuJoCo silently welds
the orphan to the world, Drake adds it as a free body, and yourdfpy attaches
it to the base frame ("not connected via joints. Will add link to base
frame"), so the part stays in the air or falls away from the robot
depending on the tool.

## How to fix
Connect the orphan to the tree with a joint (usually `fixed`), or delete it
if it is left over from an edit. A sensor frame needs a joint to its mount
link like any other link.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.effects import single
from urdflint.model.finding import Severity


@rule(
    "S004",
    "multiple-roots",
    Severity.ERROR,
    fix="Attach the link to the tree with a joint, or remove it.",
    effects=single(K.SECOND_ROOT),
)
def check(doc: Document) -> Iterator[Hit]:
    graph = doc.graph
    named_as_child = {joint.child for joint in doc.joints if joint.child}
    roots = [name for name in graph.roots if name not in named_as_child]
    if len(roots) < 2:
        return
    main = graph.root if graph.root in roots else None
    if main is None:
        main = max(roots, key=lambda name: (len(graph.subtree(name)), -roots.index(name)))
    for name in roots:
        if name != main:
            yield Hit(
                doc.link_map[name].element,
                f"link {name!r} is a second root: no joint connects it to the tree of {main!r}",
            )
