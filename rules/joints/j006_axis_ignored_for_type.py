"""A `fixed` or `floating` joint has an `<axis>`, which is ignored.

## What it does
Reports an `<axis>` inside a `fixed` or `floating` joint.

## Why is this bad?
urdfdom does not read `<axis>` for these two types (`joint.cpp` skips it), and
neither do sdformat, MuJoCo, Drake or Pinocchio: a fixed joint has no degree of
freedom, and a floating joint has all six. The element is dead data. Often it is
left over from a joint that used to move. Sometimes it holds a value, such as
`0 0 0`, that would be an error on a moving joint (J007).

This finding is informational.

## How to fix
Delete the `<axis>`. If the joint is meant to move, change its type to
`revolute`, `continuous` or `prismatic`.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model.document import Document
from urdflint.model.edits import RemoveElement, Repair
from urdflint.model.finding import Severity


@rule(
    "J006",
    "axis-ignored-for-type",
    Severity.INFO,
    fix="Delete the <axis>, or change the joint type if the joint is meant to move.",
    fixable="safe",
)
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        if joint.type not in J.AXIS_IGNORED:
            continue
        el = joint.find("axis")  # a repeated <axis> is X015's
        if el is not None:
            yield Hit(
                el,
                f"{J.label(joint)} has an <axis>, which is ignored for {joint.type} joints",
                repair=Repair("safe", "delete the ignored <axis>", (RemoveElement(el),)),
            )
