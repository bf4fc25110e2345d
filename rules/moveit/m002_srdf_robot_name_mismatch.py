"""The SRDF's `<robot name>` is not the URDF's.

## What it does
Compares the `name` of the SRDF's `<robot>` (whitespace trimmed, as srdfdom reads
it) with the URDF's `<robot name>`, and reports an SRDF `<robot>` without a name.
Only an SRDF given with `--srdf`, or found beside the URDF or through a MoveIt
`.setup_assistant`, can disagree: the `config/*.srdf` of the package is only taken
when the names match.

## Why is this bad?
srdfdom (`srdf::Model::initXml` in `src/model.cpp`) logs "Semantic description is
not specified for the same robot as the URDF" (or "No name given for the robot")
and goes on. The mismatch usually means the SRDF was generated for another robot,
another variant or an older version of this one, and every group, chain and
disabled collision pair in it may describe a different arm.

## How to fix
Use the SRDF generated for this robot, or set its `<robot name>` to the URDF's.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.moveit.common import hit, srdf_of

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity


@rule(
    "M002",
    "srdf-robot-name-mismatch",
    Severity.WARNING,
    fix="Check that the SRDF is the one for this robot; then make the two names equal.",
)
def check(doc: Document) -> Iterator[Hit]:
    srdf = srdf_of(doc)
    if srdf is None or srdf.root is None:
        return
    urdf_name = (doc.robot.get("name") or "").strip()
    name = srdf.root.get("name")
    if name is None:
        yield hit(srdf, srdf.root, "the SRDF <robot> has no name")
    elif name.strip() != urdf_name:
        yield hit(
            srdf,
            srdf.root,
            f"the SRDF is for robot {name.strip()!r}, but the URDF is robot {urdf_name!r}",
            attribute="name",
        )
