"""A planning group names a link or joint the URDF does not have.

## What it does
Checks every member of every SRDF `<group>`: the `name` of each `<link>` and
`<joint>`, and the `base_link` and `tip_link` of each `<chain>`, must be a link or
joint of the URDF (a `<joint>` may also name a `<virtual_joint>` of the SRDF). A
member without its name attribute, and a group whose members give MoveIt no joint at
all, are reported too. Names are compared after trimming whitespace, as srdfdom does.

## Why is this bad?
srdfdom (`srdf::Model::loadGroups` in `src/model.cpp`) logs "Link 'X' declared as
part of group 'G' is not known to the URDF" (or the joint / chain variant) and drops
the member: the group silently loses joints, and a planner or IK solver for it moves
fewer joints than intended. A group left without joints is not created at all
(`RobotModel::addJointModelGroup` in moveit_core `robot_model.cpp`: "Group 'G' must
have at least one valid joint"), so every controller, end effector and named pose
that uses it fails. Renamed joints (a changed xacro `prefix`, `tf_prefix`) are the
usual cause (moveit/moveit2#3092).

## How to fix
Rename the member to the URDF's link or joint (regenerate the SRDF with the MoveIt
Setup Assistant after renaming), or remove it.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree
from urdflint.rules.moveit.common import Model, hit, name_of, srdf_of

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity
from urdflint.model.structure import did_you_mean


@rule(
    "M003",
    "group-unknown-member",
    Severity.ERROR,
    fix="Name a link or joint of the URDF, or remove the member.",
)
def check(doc: Document) -> Iterator[Hit]:
    srdf = srdf_of(doc)
    if srdf is None:
        return
    model = Model(doc, srdf)
    built = model.groups()
    for group in srdf.elements("group"):
        label = name_of(group)
        found = list(_members(model, group))
        for el, attr, message, fix in found:
            yield hit(srdf, el, message, attribute=attr, fix=fix)
        if label is None:
            yield hit(srdf, group, "a <group> has no name; srdfdom skips it")
            continue
        members = [c for c in children(group) if c.tag in ("link", "joint", "chain", "group")]
        if members and not found and label not in built and _no_subgroups(group):
            yield hit(
                srdf,
                group,
                f"group {label!r} gives MoveIt no joint, so MoveIt does not create it",
                fix="Add the joints or links the group is meant to move.",
                severity=Severity.WARNING,
            )


def _no_subgroups(group: etree._Element) -> bool:
    return not children(group, "group")


Member = tuple[etree._Element, str | None, str, str | None]  # element, attribute, message, fix


def _members(model: Model, group: etree._Element) -> Iterator[Member]:
    doc, label = model.doc, repr(name_of(group))
    for el in children(group, "link"):
        name = name_of(el)
        if name is None:
            yield el, None, f"a <link> of group {label} has no name", None
        elif name not in doc.link_map:
            message = f"group {label} names link {name!r}, which is not in the URDF"
            yield el, "name", message, did_you_mean(name, doc.link_map, "link")
    for el in children(group, "joint"):
        name = name_of(el)
        if name is None:
            yield el, None, f"a <joint> of group {label} has no name", None
        elif not model.known_joint(name):
            message = f"group {label} names joint {name!r}, which is not in the URDF"
            yield el, "name", message, did_you_mean(name, doc.joint_map, "joint")
    for el in children(group, "chain"):
        for attr in ("base_link", "tip_link"):
            name = name_of(el, attr)
            if name is None:
                yield el, None, f"a <chain> of group {label} has no {attr}", None
                break
            if name not in doc.link_map:
                message = (
                    f"the chain of group {label} has {attr} {name!r}, which is not in the URDF"
                )
                yield el, attr, message, did_you_mean(name, doc.link_map, "link")
                break
