"""A link has two parent joints, or joints form a closed loop.

## What it does
Reports a joint whose child link is already the child of an earlier joint
(naming both joints), and a directed cycle of joints (a link that is its own
ancestor, including a joint whose parent and child are the same link). A
cycle is reported once, on its joint that comes last in the file, unless one
of its joints was already reported as a second parent. A second parent is
reported even when that link's name is also defined twice (S001) or when the
joint's parent link is undefined (S003), so fixing those does not reveal it
in a second run.

## Why is this bad?
URDF describes a tree. urdfdom does not notice a second parent: `check_urdf`
reports success and prints the link under both parents, while the link's
parent is whichever joint came last, so ROS, RViz and MoveIt see a different
robot from the file. Pinocchio builds the link (and its subtree) twice, so
its mass is counted twice. PyBullet crashes with a segmentation fault and
yourdfpy with a `ValueError`; Drake ("form one or more loops in the system
graph") and MuJoCo ("URDF body has multiple parents") refuse the model. A
cycle with no root at all makes urdfdom refuse it ("No root link found. The
robot xml is not a valid tree."), and PyBullet, MuJoCo and Drake too.

## How to fix
Keep one joint per child link. A real closed chain (a four-bar linkage, a
parallel gripper) has to be cut open in URDF: model one branch with joints and
close the loop in the simulator (a `<mimic>` element, a Gazebo `<joint>` inside
`<gazebo>`, or an SDF model).
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K
from urdflint.rules import lumping as L

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, Joint
from urdflint.model.finding import Severity
from urdflint.model.structure import q


@rule(
    "S005", "kinematic-loop", Severity.ERROR, effects={"two-parents": K.TWO_PARENTS, "loop": K.LOOP}
)
def check(doc: Document) -> Iterator[Hit]:
    graph = doc.graph
    reported: set[int] = set()
    for link, parents in _parents(doc).items():
        for joint in parents[1:]:
            reported.add(id(joint.element))
            yield Hit(
                joint.element,
                f"link {link!r} is the child of both joint {q(parents[0].name)} "
                f"and joint {q(joint.name)}",
                fix="Keep one parent joint per link; close real loops in the simulator.",
                variant="two-parents",
                effects=L.two_parents(doc, parents[0], joint),
            )
    order = {id(joint.element): index for index, joint in enumerate(doc.joints)}
    for cycle in graph.cycles():
        if any(id(joint.element) in reported for joint in cycle):
            continue
        last = max(cycle, key=lambda joint: order.get(id(joint.element), -1))
        reported.add(id(last.element))
        if len(cycle) == 1:
            message = f"joint {q(last.name)} connects link {last.child!r} to itself"
        else:
            names = " -> ".join(repr(joint.name) for joint in cycle)
            message = (
                f"joints {names} form a closed loop: link {cycle[0].parent!r} is its own ancestor"
            )
        yield Hit(
            last.element, message, fix="Remove or redirect one joint of the loop.", variant="loop"
        )


def _parents(doc: Document) -> dict[str, list[Joint]]:
    """Every joint naming each defined link as its child, whatever its parent (S003)."""
    found: dict[str, list[Joint]] = {name: [] for name in doc.link_map}
    for joint in doc.joints:
        if joint.child is not None and joint.child in found:
            found[joint.child].append(joint)
    return found
