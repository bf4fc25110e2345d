"""A named pose (`<group_state>`) puts a joint outside its URDF limits.

## What it does
For every `<group_state>` joint value of a revolute or prismatic joint of the state's
group, compares the value with the joint's position bounds as MoveIt computes them
(`jointBoundsFromURDF` in moveit_core `robot_model.cpp`): the `<limit>` lower and
upper, narrowed by the `<safety_controller>` `soft_lower_limit`/`soft_upper_limit`
when the joint has one. A value more than 1e-4 (MoveIt's default goal joint
tolerance) outside is reported. Continuous joints are unbounded
(`RevoluteJointModel::setContinuous`) and mimic joints take their value from the
joint they follow, so neither is checked.

## Why is this bad?
moveit_core loads the pose without checking it (`RobotModel::buildGroupStates`).
Planning to it fails: `JointConstraintSampler::configure` (moveit_core
`constraint_samplers/src/default_constraint_samplers.cpp`) finds "no possible values
for the joint" and gives up, and OMPL reports an invalid goal; a pose used as the
start or home position is reported out of bounds by the planning pipeline. The
usual cause is a changed joint limit, or a pose written by hand in degrees.

## How to fix
Move the value inside the joint's limits (regenerate the pose in the Setup
Assistant), or correct the URDF limit if the pose is right.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.moveit.common import Model, bounds, hit, name_of, parse_values, srdf_of

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity
from urdflint.model.values import fmt

TOLERANCE = 1e-4  # MoveGroupInterface's default goal joint tolerance


@rule(
    "M011",
    "group-state-out-of-limits",
    Severity.ERROR,
    fix="Move the value inside the joint's limits, or correct the limit.",
)
def check(doc: Document) -> Iterator[Hit]:
    srdf = srdf_of(doc)
    if srdf is None:
        return
    groups = Model(doc, srdf).groups()
    for state in srdf.elements("group_state"):
        label, group = name_of(state), name_of(state, "group")
        members = groups.get(group or "")
        if label is None or members is None:
            continue
        for el in children(state, "joint"):
            name, values = name_of(el), parse_values(el.get("value") or "")
            joint = doc.joint_map.get(name or "")
            if joint is None or name not in members or not values or len(values) != 1:
                continue  # M010
            if J.is_mimic(joint):
                continue
            found = bounds(doc, joint.name or "")
            if found is None:
                continue
            lower, upper = found
            value = values[0]
            if lower - TOLERANCE <= value <= upper + TOLERANCE:
                continue
            unit = J.units(joint.type)[0]
            soft = (
                " (the safety_controller's soft limits)"
                if joint.find("safety_controller") is not None
                else ""
            )
            yield hit(
                srdf,
                el,
                f"group state {label!r} sets joint {name!r} to {fmt(value)} {unit}, outside its "
                f"limits [{fmt(lower)}, {fmt(upper)}]{soft}",
                attribute="value",
            )
