"""What the statics rules need to know besides the numbers: which joints have an actuator,
which links Gazebo weighs, and what a joint carries.

- **actuated joints**: when the model declares its actuators (a ``<transmission>`` or a
  ``<ros2_control>`` joint with a command interface), the joints it names; a joint it does
  not name is passive (a suspension, a caster, a spring-loaded finger) and nothing
  commands it, so its effort limit holds nothing. A model that declares no actuator at
  all (many do not) is taken as actuated everywhere.
- **the tool link**, where a payload goes by default: the end of the longest chain, or the
  hand it ends in: the highest link on that chain below which the chain splits into
  short branches of moving joints (fingers: at most :data:`FINGER` long), so that a
  gripper's payload sits in its palm, not on one finger.
- **weightless links**: ``<gazebo reference="link">`` with ``<turnGravityOff>true`` or
  ``<gravity>false``. PR2 does this for its arms, whose real counterbalance springs the
  URDF does not model: Gazebo then sees no gravity load on them, the other targets do.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from urdflint.model import joints as J
from urdflint.model import ros2_control
from urdflint.model.gazebo_spec import canonical
from urdflint.model.structure import transmission_joint_refs
from urdflint.model.values import parse_numbers

if TYPE_CHECKING:
    from urdflint.model.document import Document, Joint


def actuated(doc: Document) -> frozenset[str] | None:
    """The joints a ``<transmission>`` or ``<ros2_control>`` command names; ``None`` when
    the model declares no actuator (then every joint counts as actuated)."""
    found = doc.memo.get("statics.actuated", False)
    if found is not False:
        return found  # type: ignore[no-any-return]
    names: set[str] = set()
    declared = False
    for transmission in doc.transmissions:
        refs = [
            value
            for el, attr, value in transmission_joint_refs(transmission)
            if value and not (el.tag == "passive_joint" or attr == "passive_actuated_joint")
        ]
        declared = declared or bool(refs)
        names.update(refs)
    for block in ros2_control.blocks(doc):
        for joint in block.joints:
            declared = True
            if joint.name is not None and joint.commands:
                names.add(joint.name)
    result = frozenset(names) if declared else None
    doc.memo["statics.actuated"] = result
    return result


def weightless(doc: Document) -> frozenset[str]:
    """The links whose ``<gazebo>`` block turns gravity off."""
    found: set[str] = set()
    for block in doc.gazebo:
        link = block.get("reference")
        if link is None:
            continue
        for child in block:
            if not isinstance(child.tag, str) or child.tag not in ("turnGravityOff", "gravity"):
                continue
            if canonical(child.tag, child) == ("gravity", "false"):
                found.add(link)
    return frozenset(found)


def carried(doc: Document, joint: str) -> list[str]:
    """The links below ``joint`` (its child and the child's descendants)."""
    entry = doc.joint_map.get(joint)
    if entry is None or entry.child is None:
        return []
    graph = doc.graph
    seen: list[str] = []
    stack = [entry.child]
    while stack:
        link = stack.pop()
        if link in seen:
            continue
        seen.append(link)
        stack.extend(graph.children(link))
    return seen


FINGER = 0.25  # m: a branch of moving joints this short (joint offsets summed) is a finger


def moving(joint: Joint) -> bool:
    """A joint that moves on its own: revolute, continuous or prismatic, not a mimic."""
    return joint.type in J.ACTUATED and not J.is_mimic(joint)


def tool_link(doc: Document) -> str | None:
    """Where a payload goes by default (see the module docstring)."""
    graph = doc.graph
    if graph.root is None:
        return None
    best: tuple[int, int] = (-1, -1)
    found: str | None = None
    stack = [(graph.root, 0, 0)]
    seen: set[str] = set()
    while stack:
        link, count, depth = stack.pop()
        if link in seen:
            continue
        seen.add(link)
        below = [j for j in graph.child_joints.get(link, []) if j.child is not None]
        if not below and (count, depth) > best:
            best, found = (count, depth), link
        for joint in reversed(below):
            stack.append((joint.child, count + moving(joint), depth + 1))  # type: ignore[arg-type]
    return _hand(doc, found) if found is not None else None


def _hand(doc: Document, leaf: str) -> str:
    """The highest link above ``leaf``, below a moving joint, whose branches of one-axis
    joints are all fingers (two or more), else ``leaf``."""
    graph = doc.graph
    parents = {j.child: j for j in doc.joints if j.child is not None}
    path = [leaf]
    while path[-1] in parents and parents[path[-1]].parent not in (None, *path):
        path.append(parents[path[-1]].parent)  # type: ignore[arg-type]
    hand = leaf
    for index, link in enumerate(path[1:], start=1):
        if not any(moving(parents[up]) for up in path[index:] if up in parents):
            break  # nothing above moves it: the robot's body, not a hand
        lengths = [_reach(doc, j) for j in graph.child_joints.get(link, []) if j.child]
        lengths = [n for n in lengths if n >= 0]
        if len(lengths) >= 2:
            if max(lengths) > FINGER:
                break
            hand = link
    return hand


def _reach(doc: Document, joint: Joint, depth: int = 0) -> float:
    """How far ``joint``'s branch reaches: the longest sum of joint offsets down from it
    (``-1`` when no one-axis joint, mimics included, moves anything in it)."""
    if depth > 64:
        return -1.0
    below = [_reach(doc, j, depth + 1) for j in doc.graph.child_joints.get(joint.child or "", [])]
    deeper = max(below, default=-1.0)
    if deeper < 0 and joint.type not in J.ACTUATED:
        return -1.0
    return _offset(joint) + max(deeper, 0.0)


def _offset(joint: Joint) -> float:
    origin = joint.find("origin")
    values = parse_numbers(origin.get("xyz") or "") if origin is not None else None
    return math.sqrt(sum(v * v for v in values)) if values and len(values) == 3 else 0.0
