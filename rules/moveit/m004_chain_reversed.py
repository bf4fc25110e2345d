"""A group's `<chain>` runs from a link to one of its ancestors, or to itself.

## What it does
For every `<chain base_link tip_link>` whose two links exist, reports a chain whose
`base_link` lies below its `tip_link` in the URDF tree (the two are swapped), and a
chain whose base and tip are the same link (it has no joint). A chain between two
branches (from one gripper to the other, through the root) is what MoveIt
supports on purpose and is not reported.

## Why is this bad?
srdfdom (`srdf::Model::loadGroups` in `src/model.cpp`) accepts any two links of the
tree. MoveIt (`RobotModel::addJointModelGroup` in moveit_core `robot_model.cpp`)
walks up from the tip looking for the base; for a swapped chain it never finds it,
takes the "two branches" path and puts in the group the joints from the base up to
the tip plus the joint *above* the tip, which is not between the two links; the
kinematics plugins (KDL, TRAC-IK) build their solver chain from `base_link` to
`tip_link` in the order written, so IK solves for the wrong end. A chain from a link
to itself gives the group no joint.

## How to fix
Swap `base_link` and `tip_link` so the base is the link nearer the root.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.moveit.common import hit, name_of, srdf_of

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity


@rule(
    "M004",
    "chain-reversed",
    Severity.WARNING,
    fix="Swap base_link and tip_link: the base is the link nearer the root.",
)
def check(doc: Document) -> Iterator[Hit]:
    srdf = srdf_of(doc)
    if srdf is None:
        return
    for group in srdf.elements("group"):
        label = name_of(group)
        for chain in children(group, "chain"):
            base, tip = name_of(chain, "base_link"), name_of(chain, "tip_link")
            if base not in doc.link_map or tip not in doc.link_map:
                continue  # M003
            assert base is not None and tip is not None
            if base == tip:
                yield hit(
                    srdf,
                    chain,
                    f"the chain of group {label!r} starts and ends at link {base!r}: "
                    "it has no joint",
                    attribute="tip_link",
                    fix="Set tip_link to the last link the group moves.",
                )
            elif tip in doc.graph.ancestors(base):
                yield hit(
                    srdf,
                    chain,
                    f"the chain of group {label!r} is reversed: base_link {base!r} is below "
                    f"tip_link {tip!r} in the URDF tree",
                    attribute="base_link",
                )
