"""A passive joint is not in the URDF, or is a fixed joint.

## What it does
Checks every `<passive_joint name>`: the name must be written and name a joint of the
URDF or a virtual joint of the SRDF. Marking a `fixed` joint passive is reported as
information: it has no variable, so the mark does nothing.

## Why is this bad?
srdfdom (`srdf::Model::loadPassiveJoints` in `src/model.cpp`) logs "Joint 'J' marked
as passive is not known to the URDF. Ignoring." and drops it. A passive joint is one
MoveIt must not plan for (a caster wheel, an unactuated linkage joint); when the
name is stale the real joint is planned for as if it were actuated, and the
trajectory controller is asked to move a joint it does not drive. moveit_core
(`RobotModel::constructJointModel` in `robot_model.cpp`) sets the flag on the joint
model of that name, which for a fixed joint changes nothing.

## How to fix
Name the joint as the URDF does, or remove the `<passive_joint>`.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.moveit.common import Model, hit, name_of, srdf_of

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import did_you_mean


@rule(
    "M008",
    "passive-joint-invalid",
    Severity.WARNING,
    fix="Name a joint of the URDF, or remove the passive_joint.",
)
def check(doc: Document) -> Iterator[Hit]:
    srdf = srdf_of(doc)
    if srdf is None:
        return
    model = Model(doc, srdf)
    for el in srdf.elements("passive_joint"):
        name = name_of(el)
        if name is None:
            yield hit(srdf, el, "a <passive_joint> has no name; srdfdom ignores it")
        elif not model.known_joint(name):
            yield hit(
                srdf,
                el,
                f"passive joint {name!r} is not a joint of the URDF; srdfdom ignores it",
                attribute="name",
                fix=did_you_mean(name, doc.joint_map, "joint"),
            )
        elif name in doc.joint_map and doc.joint_map[name].type == "fixed":
            yield hit(
                srdf,
                el,
                f"passive joint {name!r} is a fixed joint: marking it passive does nothing",
                attribute="name",
                fix="Remove the passive_joint.",
                severity=Severity.INFO,
            )
