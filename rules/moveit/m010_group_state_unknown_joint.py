"""A named pose (`<group_state>`) sets a joint that is not in the URDF or not in its group.

## What it does
For every `<group_state>` of a group MoveIt builds, checks each `<joint name value>`:

- the joint must be a joint of the URDF (or a virtual joint of the SRDF);
- it must belong to the state's group (its `<joint>`s, the parent joints of its
  `<link>`s, the joints of its `<chain>`s and of its subgroups);
- `value` must be numbers, as many as the joint has variables (1 for revolute,
  continuous and prismatic joints, 3 for planar, 7 for floating, none for fixed).

A state without `name` or `group`, and a `<joint>` without `name` or `value`, are
reported too. An unknown group is M005's.

## Why is this bad?
srdfdom (`srdf::Model::loadGroupStates` in `src/model.cpp`) logs "Joint 'J' declared
as part of group state 'S' is not known to the URDF" and drops the value; it reads
`value` with a `std::istringstream`, so a word reads as `0`. moveit_core
(`RobotModel::buildGroupStates` in `robot_model.cpp`) ignores a value for a joint
outside the group ("Group state 'S' specifies value for joint 'J', but that joint is
not part of group 'G'") or with the wrong number of values ("The model for joint 'J'
requires N variable values"). The named pose then leaves that joint wherever it is:
`setNamedTarget("home")` plans to a different pose than the one written, or, when no
value is left, the name does not exist at all.

## How to fix
Use the URDF's joint names, set only the joints of the state's group (define the
state on the group that holds the joint), and write one number per variable.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree
from urdflint.rules.moveit.common import Model, hit, name_of, parse_values, srdf_of

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity
from urdflint.model.structure import did_you_mean


@rule(
    "M010",
    "group-state-unknown-joint",
    Severity.ERROR,
    fix="Set only joints of the state's group, by their URDF names, one number per variable.",
)
def check(doc: Document) -> Iterator[Hit]:
    srdf = srdf_of(doc)
    if srdf is None:
        return
    model = Model(doc, srdf)
    groups = model.groups()
    for state in srdf.elements("group_state"):
        label, group = name_of(state), name_of(state, "group")
        if label is None or group is None:
            what = "name" if label is None else "group"
            yield hit(srdf, state, f"a <group_state> has no {what}; srdfdom drops it")
            continue
        if group not in groups:
            continue  # M003, M005
        for joint in children(state, "joint"):
            problem = _problem(model, groups[group], label, group, joint)
            if problem is not None:
                attribute, message, fix = problem
                yield hit(srdf, joint, message, attribute=attribute, fix=fix)


def _problem(
    model: Model, members: set[str], label: str, group: str, joint: etree._Element
) -> tuple[str | None, str, str | None] | None:
    name, raw = name_of(joint), joint.get("value")
    if name is None or raw is None:
        what = "name" if name is None else "value"
        return None, f"a <joint> of group state {label!r} has no {what}", None
    if not model.known_joint(name):
        fix = did_you_mean(name, model.doc.joint_map, "joint")
        return "name", f"group state {label!r} sets joint {name!r}, which is not in the URDF", fix
    if name not in members:
        message = (
            f"group state {label!r} sets joint {name!r}, which is not in group {group!r}: "
            "MoveIt ignores the value"
        )
        return "name", message, "Remove the joint, or define the state on a group that has it."
    values = parse_values(raw)
    if values is None:
        return (
            "value",
            f"group state {label!r} gives joint {name!r} the value {raw!r}, not a number",
            None,
        )
    wanted = model.variables(name)
    if wanted is not None and len(values) != wanted:
        message = (
            f"group state {label!r} gives joint {name!r} {len(values)} value(s), but it has "
            f"{wanted} variable(s): MoveIt ignores them"
        )
        return "value", message, None
    return None
