"""A `<transmission>` holds an element no transmission parser reads.

## What it does
Checks the direct children of every robot-level `<transmission>` against what
its parsers read: ros_control's form (`<type>`, `<joint>`, `<actuator>`) and the
pr2_mechanism_model forms (`<mechanicalReduction>` and `<compensator>` beside
`<joint>`/`<actuator>`; WristTransmission's `<leftActuator>`, `<rightActuator>`,
`<flexJoint>`, `<rollJoint>`; PR2GripperTransmission's `<gap_joint>`,
`<passive_joint>`, `<simulated_actuated_joint>`, `<use_simulated_gripper_joint>`).
Any other child is reported, with the closest known name. Inside `<joint>` and
`<actuator>`, where robot vendors' own loaders read extra elements (PAL's
`<saturationLower>`...), only near misses of what ros_control reads are
reported (`<hardwareInterfaces>`, `<mechanical_reduction>`, `<mechanicalReducton>`).
The ros2_control elements `<plugin>` and `<param>` get a note that they belong in
a `<transmission>` inside `<ros2_control>`.

## Why is this bad?
Every transmission parser looks its elements up by name and ignores the rest
(ros_control's `TransmissionParser` and loaders, pr2_mechanism_model's
`initXml`), and urdfdom ignores transmissions altogether, so a misspelt element
is silently missing: without `<hardwareInterface>` in `<joint>` gazebo_ros_control
skips the joint, without `<mechanicalReduction>` in `<actuator>` the
SimpleTransmission loader fails ("does not specify the required
<mechanicalReduction> element"), and a `<mechanical_reduction>` (the ros2_control
spelling) is never read by ROS 1 at all.

## How to fix
Rename the element as suggested (names are case-sensitive), move it to where its
parser reads it, or delete it. A ros2_control transmission (`<plugin>`, `<param>`,
`<mechanical_reduction>`) goes inside the `<ros2_control>` block.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity
from urdflint.model.spelling import near_miss, suggest
from urdflint.model.structure import TRANSMISSION_CHILDREN, TRANSMISSION_PART_CHILDREN, q

ROS2_CONTROL = frozenset({"plugin", "param"})


@rule(
    "T004",
    "unknown-transmission-element",
    Severity.WARNING,
    fix="Rename or move the element to where its transmission parser reads it, or remove it.",
)
def check(doc: Document) -> Iterator[Hit]:
    for transmission in doc.transmissions:
        label = f"transmission {q(transmission.get('name'))}"
        for el in _plain(transmission):
            tag = str(el.tag)
            if tag in TRANSMISSION_CHILDREN:
                yield from _part(el, label)
            elif tag in ROS2_CONTROL:
                yield Hit(
                    el,
                    f"<{tag}> in {label} is a ros2_control element; robot-level transmissions "
                    "are read by ROS 1's transmission_interface, which ignores it",
                    fix="Move a ros2_control transmission into the <ros2_control> block, "
                    "or use <type> for ROS 1.",
                )
            else:
                guess = suggest(tag, sorted(TRANSMISSION_CHILDREN))
                hint = f" (did you mean <{guess}>?)" if guess else ""
                inside = [p for p, known in TRANSMISSION_PART_CHILDREN.items() if tag in known]
                if inside:
                    hint = f" (it belongs inside {' or '.join(f'<{p}>' for p in inside)})"
                yield Hit(el, f"<{tag}> in {label} is not read by any transmission parser{hint}")


def _plain(el: etree._Element) -> list[etree._Element]:
    """Element children that are not in a namespace (xacro leftovers are X008's)."""
    return [c for c in children(el) if not str(c.tag).startswith("{")]


def _part(part: etree._Element, label: str) -> Iterator[Hit]:
    known = TRANSMISSION_PART_CHILDREN.get(str(part.tag))
    if known is None:
        return
    for el in _plain(part):
        tag = str(el.tag)
        guess = None if tag in known else near_miss(tag, known)
        if guess is not None:
            yield Hit(
                el,
                f"<{tag}> in <{part.tag}> {q(part.get('name'))} of {label} is not read by "
                f"ros_control (did you mean <{guess}>?)",
                fix=f"Rename it to <{guess}>.",
            )
