"""A joint has no `<origin>`, so its frame is the identity.

## What it does
Reports a `<joint>` without an `<origin>` child.

## Why is this bad?
urdfdom and every other parser then place the child link's frame exactly on the
parent's (identity transform). That is sometimes intended: a wheel frame on its
hub, or a sensor frame at its mount. But it is also what a forgotten or
misplaced `<origin>` looks like, for instance one written inside `<axis>` or
`<limit>` instead of directly in `<joint>`. The Gazebo tutorial "Using a URDF in
Gazebo" lists `<origin>` as required on joints. Writing it, even as zeros,
states that the identity is intended.

This finding is informational.

## How to fix
Add `<origin xyz="0 0 0" rpy="0 0 0"/>` to the joint, or the real offset if the
child frame is not on the parent's.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model.document import Document
from urdflint.model.finding import Severity


@rule(
    "J011",
    "missing-joint-origin",
    Severity.INFO,
    fix='Add <origin xyz="0 0 0" rpy="0 0 0"/> (or the real offset) to the joint.',
)
def check(doc: Document) -> Iterator[Hit]:
    for joint in doc.joints:
        if joint.find("origin") is None:
            yield Hit(
                joint.element,
                f"{J.label(joint)} has no <origin>; its child frame sits on the parent's",
            )
