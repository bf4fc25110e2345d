"""Helpers shared by the structure (S), transmission (T) and collision (C) rules.

Name suggestions for misspelt references, quoting names for messages, where an
element was written (for "first defined on ..."), the links welded together by
fixed joints (one rigid body once Gazebo lumps fixed joints), and what the
children of a ``<transmission>`` are: which name joints, which actuators, which
elements its parsers read.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING

from urdflint.model.document import children, local_tag

if TYPE_CHECKING:
    from lxml import etree

    from urdflint.model.document import Document
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


# Direct children of a robot-level <transmission> that a parser reads: ros_control's
# TransmissionParser (<type>, <joint>, <actuator>) and the pr2_mechanism_model
# transmissions: SimpleTransmission and PR2BeltCompensatorTransmission (a
# <mechanicalReduction> and a <compensator> beside <joint>/<actuator>), WristTransmission
# (<leftActuator>, <rightActuator>, <flexJoint>, <rollJoint>), PR2GripperTransmission
# (<gap_joint>, <passive_joint>, <simulated_actuated_joint>, <use_simulated_gripper_joint>).
TRANSMISSION_CHILDREN = frozenset(
    {"type", "joint", "actuator", "mechanicalReduction", "compensator"}
    | {"leftActuator", "rightActuator", "flexJoint", "rollJoint"}
    | {"gap_joint", "passive_joint", "simulated_actuated_joint", "use_simulated_gripper_joint"}
)
# What ros_control's transmission loaders read inside <joint> and <actuator>; vendors'
# loaders read more (PAL's <saturationLower>, ...), so only near misses of these count.
TRANSMISSION_PART_CHILDREN: dict[str, frozenset[str]] = {
    "joint": frozenset(
        {"hardwareInterface", "role", "mechanicalReduction", "offset"}
        | {"ignoreTransmissionAbsoluteEncoder"}
    ),
    "actuator": frozenset({"hardwareInterface", "role", "mechanicalReduction"}),
}
# Elements that name a motor: ros_control's <actuator>, WristTransmission's two actuators.
ACTUATOR_TAGS = ("actuator", "leftActuator", "rightActuator")


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


def written_at(doc: Document, el: etree._Element) -> str:
    """Where ``el`` is written, for "first defined on ..." messages.

    ``line 12`` in a plain URDF (the line of its start tag); in an expanded xacro
    document, the file and line of the source (``arm.xacro:9``, ``line 9`` when it is the
    checked file itself) and the macro call that produced it.
    """
    origin = doc.origin(el) if doc.origin is not None else None
    if origin is None:
        return f"line {doc.start_of(el)[0]}"
    where = f"line {origin.line}" if origin.path == doc.path else f"{origin.path}:{origin.line}"
    if origin.trace:
        call = origin.trace[0]
        where += f", in macro `{call.macro}` called from {call.path}:{call.line}"
    return where
