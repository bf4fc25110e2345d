"""The root link has a mass, which KDL and robot_state_publisher ignore.

## What it does
Reports an `<inertial>` with a positive mass on the root link of the tree.

## Why is this bad?
kdl_parser cannot attach an inertia to the root segment. It prints "The root
link X has an inertia specified in the URDF, but KDL does not support a root
link with an inertia. As a workaround, you can add an extra dummy link to your
URDF." (ros/kdl_parser#27, still open), and every KDL-based dynamics
computation (gravity compensation, inverse dynamics, total mass) leaves that
mass out. robot_state_publisher prints the warning on every start.

## How to fix
Add a massless root link (for example `base_footprint`, or `world` for a
fixed-base arm) and attach the current root to it with a `fixed` joint. KDL then
sees the mass on a regular segment. Gazebo keeps it: it lumps the base into the
massless root (the simulated link takes the root's name, so move `<gazebo
reference>` blocks to it, see G008), or, for `world`, pins the base to the world.
Pinocchio puts both on its universe joint (see P002).
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import bodies
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.values import fmt


@rule(
    "I011",
    "root-link-inertia",
    Severity.INFO,
    fix="Add a massless root link and attach this link to it with a fixed joint.",
    effects={"": K.ROOT_INERTIA, "world": K.WORLD_INERTIA},
)
def check(doc: Document) -> Iterator[Hit]:
    root = doc.graph.root
    inertial = bodies(doc).inertials.get(root) if root is not None else None
    if inertial is not None and inertial.mass is not None and inertial.mass > 0:
        yield Hit(
            inertial.element,
            f"root link '{root}' has an <inertial> of {fmt(inertial.mass)} kg, which KDL ignores",
            variant="world" if root == "world" else "",
        )
