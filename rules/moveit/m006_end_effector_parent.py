"""An end effector's parent link is not in the URDF, or its parent group does not hold it.

## What it does
For every `<end_effector>`: the `parent_link` must be written and be a link of the
URDF; when `parent_group` is written, that group must contain `parent_link` (MoveIt's
group links are the child links of the group's joints) and must not be the end
effector's own `group`. An unknown group is M005's.

## Why is this bad?
srdfdom (`srdf::Model::loadEndEffectors` in `src/model.cpp`) drops an end effector
whose parent link is missing or unknown ("Link 'L' specified as parent for end
effector 'E' is not known to the URDF"): the gripper is then no end effector, and
RViz's interactive marker and `getEndEffectorLink()` fall back to the arm's last
link. moveit_core (`RobotModel::buildGroupsInfoEndEffectors` in `robot_model.cpp`)
logs "Group 'G' was specified as parent group for end-effector 'E' but it does not
include the parent link 'L'" or "cannot be its own parent", and ignores the
`parent_group`: the end effector is attached to whichever group happens to hold the
link, or to none (haosulab/MPlib#71, moveit_pr2#90).

## How to fix
Set `parent_link` to the arm link the end effector is mounted on (usually the
arm group's tip link) and `parent_group` to the arm group that contains it.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.moveit.common import Model, hit, name_of, srdf_of

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import did_you_mean


@rule(
    "M006",
    "end-effector-parent",
    Severity.ERROR,
    fix="Set parent_link to the link the end effector is mounted on, inside parent_group.",
)
def check(doc: Document) -> Iterator[Hit]:
    srdf = srdf_of(doc)
    if srdf is None:
        return
    model = Model(doc, srdf)
    groups = model.groups()
    for eef in srdf.elements("end_effector"):
        label = name_of(eef)
        parent, group, parent_group = (
            name_of(eef, a) for a in ("parent_link", "group", "parent_group")
        )
        if parent is None:
            yield hit(srdf, eef, f"end effector {label!r} has no parent_link; srdfdom drops it")
            continue
        if parent not in doc.link_map:
            yield hit(
                srdf,
                eef,
                f"end effector {label!r} has parent_link {parent!r}, which is not in the URDF",
                attribute="parent_link",
                fix=did_you_mean(parent, doc.link_map, "link"),
            )
            continue
        if parent_group is None or parent_group not in groups:
            continue  # no parent group, or one that MoveIt does not build (M003, M005)
        if parent_group == group:
            yield hit(
                srdf,
                eef,
                f"end effector {label!r} names its own group {group!r} as parent_group",
                attribute="parent_group",
                fix="Set parent_group to the arm group the end effector is mounted on.",
            )
        elif parent not in model.group_links(groups[parent_group]):
            yield hit(
                srdf,
                eef,
                f"parent_group {parent_group!r} of end effector {label!r} does not contain its "
                f"parent_link {parent!r}",
                attribute="parent_group",
                fix="Set parent_link to a link of parent_group (usually its tip link).",
            )
