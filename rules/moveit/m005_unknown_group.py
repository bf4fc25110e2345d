"""The SRDF refers to a planning group that does not exist, or groups include each other.

## What it does
Reports:

- a subgroup (`<group name>` inside a `<group>`) naming no group of the SRDF;
- groups that include each other (a subgroup cycle);
- a `<group_state group>` or `<end_effector group>` naming no group, and an
  `<end_effector parent_group>` naming no group;
- a second `<group>` with the name of an earlier one (a warning).

## Why is this bad?
srdfdom (`srdf::Model::loadGroups` in `src/model.cpp`) drops every group whose
subgroups are not all defined, transitively ("Group 'G' has unsatisfied
subgroups"): a cycle or a typo removes the group and every group that includes it.
`loadGroupStates` and `loadEndEffectors` drop a named pose or end effector whose
group is unknown ("... specified for group 'G', but that group is not known"), so
`setNamedTarget("home")` fails and the gripper is no end effector. moveit_core
(`RobotModel::buildGroupsInfoEndEffectors`) logs "Group name 'G' not found
(specified as parent group for end-effector 'E')" and `addJointModelGroup` does not
add a second group of the same name ("A group named 'G' already exists").

## How to fix
Name an existing group (names are case-sensitive), break the cycle, or rename the
duplicate group.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree
from urdflint.rules.moveit.common import Model, Srdf, hit, name_of, srdf_of

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity
from urdflint.model.structure import did_you_mean


@rule("M005", "unknown-group", Severity.ERROR, fix="Name a group defined in the SRDF.")
def check(doc: Document) -> Iterator[Hit]:
    srdf = srdf_of(doc)
    if srdf is None:
        return
    model = Model(doc, srdf)
    elements = model.group_elements()
    yield from _subgroups(srdf, elements)
    for tag, attrs in (("group_state", ("group",)), ("end_effector", ("group", "parent_group"))):
        for el in srdf.elements(tag):
            for attr in attrs:
                name = name_of(el, attr)
                if name is not None and name not in elements:
                    yield hit(
                        srdf,
                        el,
                        f"<{tag}> {name_of(el)!r} names {attr} {name!r}, which is not a group "
                        "of the SRDF",
                        attribute=attr,
                        fix=did_you_mean(name, elements, "group"),
                    )


Groups = dict[str, etree._Element]


def _subgroups(srdf: Srdf, elements: Groups) -> Iterator[Hit]:
    seen: set[str] = set()
    for group in srdf.elements("group"):
        label = name_of(group)
        if label is None:
            continue
        if label in seen:
            yield hit(
                srdf,
                group,
                f"a second group is named {label!r}; MoveIt keeps only the first",
                attribute="name",
                fix="Rename one of the groups, or merge them.",
                severity=Severity.WARNING,
            )
        seen.add(label)
        unknown = False
        for sub in children(group, "group"):
            name = name_of(sub)
            if name is not None and name not in elements:
                unknown = True
                yield hit(
                    srdf,
                    sub,
                    f"group {label!r} includes group {name!r}, which is not defined",
                    attribute="name",
                    fix=did_you_mean(name, elements, "group"),
                )
        if not unknown and elements.get(label) is group and _in_cycle(label, elements):
            yield hit(
                srdf,
                group,
                f"group {label!r} includes itself through its subgroups; srdfdom drops it",
                fix="Remove the subgroup that leads back to this group.",
            )


def _in_cycle(start: str, elements: Groups) -> bool:
    stack = [name_of(s) for s in children(elements[start], "group")]
    seen: set[str] = set()
    while stack:
        name = stack.pop()
        if name == start:
            return True
        if name is None or name in seen or name not in elements:
            continue
        seen.add(name)
        stack.extend(name_of(s) for s in children(elements[name], "group"))
    return False
