"""A virtual joint does not attach the URDF's root link, or is incomplete.

## What it does
For every `<virtual_joint>`: `name`, `child_link`, `parent_frame` and `type` must be
written, `type` must be `fixed`, `planar` or `floating`, `child_link` must be a link
of the URDF, and it must be the URDF's root link. A fixed virtual joint from a
geometry-less root link named `world` (the Gazebo convention) is accepted, as MoveIt
accepts it.

## Why is this bad?
srdfdom (`srdf::Model::loadVirtualJoints` in `src/model.cpp`) drops a virtual joint
whose name, child link, parent frame or type is missing, or whose child link is
unknown ("Virtual joint does not attach to a link on the robot"), and turns an
unknown type into `fixed` ("Unknown type of joint ... Assuming 'fixed' instead").
moveit_core (`RobotModel::constructJointModel` in `robot_model.cpp`) only uses a
virtual joint whose child is the URDF root: any other is skipped ("Skipping virtual
joint 'V' because its child frame 'L' does not match the URDF frame 'R'"), and the
robot gets a fixed `ASSUMED_FIXED_ROOT_JOINT` instead. A mobile base declared with a
planar or floating virtual joint then cannot move in planning, and groups that list
the virtual joint lose it. Skipping a fixed virtual joint is a warning; a planar or
floating one is an error.

## How to fix
Set `child_link` to the URDF's root link (the first link of the tree), and `type` to
`fixed`, `planar` or `floating`.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.moveit.common import VIRTUAL_TYPES, hit, name_of, srdf_of

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import did_you_mean

ATTRIBUTES = ("name", "child_link", "parent_frame", "type")


@rule(
    "M007",
    "virtual-joint-not-root",
    Severity.ERROR,
    fix="Attach the virtual joint to the URDF's root link.",
)
def check(doc: Document) -> Iterator[Hit]:
    srdf = srdf_of(doc)
    if srdf is None:
        return
    root = doc.graph.root
    for vj in srdf.elements("virtual_joint"):
        label = name_of(vj)
        missing = [a for a in ATTRIBUTES if vj.get(a) is None]
        if missing:
            yield hit(srdf, vj, f"virtual joint {label!r} has no {missing[0]}; srdfdom drops it")
            continue
        child, kind = name_of(vj, "child_link") or "", (name_of(vj, "type") or "").lower()
        if kind not in VIRTUAL_TYPES:
            yield hit(
                srdf,
                vj,
                f"virtual joint {label!r} has type {kind!r}; srdfdom makes it 'fixed'",
                attribute="type",
                fix="Use type fixed, planar or floating.",
            )
            kind = "fixed"
        if child not in doc.link_map:
            yield hit(
                srdf,
                vj,
                f"virtual joint {label!r} has child_link {child!r}, which is not in the URDF",
                attribute="child_link",
                fix=did_you_mean(child, doc.link_map, "link"),
            )
        elif root is not None and child != root and not _world_root(doc, root, kind):
            yield hit(
                srdf,
                vj,
                f"{kind} virtual joint {label!r} attaches link {child!r}, but the URDF's root "
                f"link is {root!r}: MoveIt skips the virtual joint",
                attribute="child_link",
                severity=Severity.WARNING if kind == "fixed" else None,
            )


def _world_root(doc: Document, root: str, kind: str) -> bool:
    """MoveIt's exception: a fixed virtual joint below a geometry-less ``world`` root link."""
    link = doc.link_map[root]
    return root == "world" and kind == "fixed" and not link.visuals and not link.collisions
