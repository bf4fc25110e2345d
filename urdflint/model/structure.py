"""Helpers shared by the structure (S), transmission (T) and collision (C) rules.

Name suggestions for misspelt references, quoting names for messages, the
links welded together by fixed joints (one rigid body once Gazebo lumps fixed
joints), and which children of a ``<transmission>`` name joints.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING

from urdflint.model.document import children, local_tag

if TYPE_CHECKING:
    from lxml import etree

    from urdflint.model.graph import Graph

JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")

# Children of a <transmission> whose attributes name a joint of the robot.
# <joint> is the ros_control (transmission_interface) form; the others are the
# legacy pr2_mechanism_model forms (WristTransmission, PR2GripperTransmission,
# the simulated screw joint of SimpleTransmission). <leftActuator>,
# <rightActuator> and <actuator> name actuators, and <use_simulated_gripper_joint>
# is a flag, so none of those is checked.
TRANSMISSION_JOINT_REFS: dict[str, tuple[str, ...]] = {
    "joint": ("name",),
    "flexJoint": ("name",),
    "rollJoint": ("name",),
    "gap_joint": ("name",),
    "passive_joint": ("name",),
    "simulated_actuated_joint": ("name", "passive_actuated_joint"),
}


def closest(name: str, candidates: Iterable[str | None]) -> str | None:
    """The candidate most similar to ``name`` (a likely typo), or ``None``."""
    pool = [c for c in candidates if c]
    exact = [c for c in pool if c.lower() == name.lower()]
    if exact:
        return exact[0]
    found = difflib.get_close_matches(name, pool, n=1, cutoff=0.6)
    return found[0] if found else None


def did_you_mean(name: str, candidates: Iterable[str | None], what: str) -> str | None:
    """A fix sentence suggesting the closest candidate, or ``None``."""
    match = closest(name, candidates)
    return f"Did you mean {what} '{match}'?" if match else None


def welded(graph: Graph, link: str) -> list[str]:
    """``link`` and every link joined to it through fixed joints only (one rigid body).

    Gazebo's fixed-joint lumping merges exactly this set into one body, and
    MuJoCo's ``fusestatic`` does the same.
    """
    seen = {link}
    order = [link]
    stack = [link]
    while stack:
        name = stack.pop()
        joints = list(graph.parent_joints.get(name, [])) + list(graph.child_joints.get(name, []))
        for joint in joints:
            if joint.type != "fixed":
                continue
            for other in (joint.parent, joint.child):
                if other is not None and other in graph.links and other not in seen:
                    seen.add(other)
                    order.append(other)
                    stack.append(other)
    return order


def transmission_joint_refs(
    transmission: etree._Element,
) -> Iterator[tuple[etree._Element, str, str | None]]:
    """``(element, attribute, value)`` for every joint reference in a transmission."""
    for child in children(transmission):
        for attr in TRANSMISSION_JOINT_REFS.get(local_tag(child), ()):
            if attr == "name" or child.get(attr) is not None:
                yield child, attr, child.get(attr)


def q(name: str | None) -> str:
    """A name quoted for a message, or ``(unnamed)`` when the attribute is missing."""
    return repr(name) if name is not None else "(unnamed)"
