"""A transmission's mechanical reduction is not one non-zero number.

## What it does
Checks the text of every `<mechanicalReduction>` of a robot-level
`<transmission>` (inside `<actuator>` or `<joint>`, the ros_control form, or
directly in the transmission, the pr2_mechanism_model form), the
`mechanicalReduction` attribute of WristTransmission's `<leftActuator>`,
`<rightActuator>`, `<flexJoint>` and `<rollJoint>`, and the
`<mechanical_reduction>` of the joints and actuators of a `<ros2_control>`
block's `<transmission>`. Each must be a single finite decimal number other
than zero; negative values are valid (they reverse the direction).

## Why is this bad?
ros_control's transmission loaders (`TransmissionLoader::getActuatorReduction`
and `getJointReduction` in transmission_interface) read the text with
`std::stod`: text that does not start with a number fails with "specifies the
<mechanicalReduction> element, but is not a number" and the transmission is
not loaded, so `gazebo_ros_control` and the robot's hardware interface have
no transmission for the joint. Trailing text is cut silently (`50 100` reads
as 50, `1/50` as 1), and a zero reduction is refused when the transmission is
built ("Transmission reduction ratio cannot be zero."). pr2_mechanism_model
reads it with `atof`, which turns anything unreadable into 0 and divides by
it. ros2_control (`get_parameter_value_or` in hardware_interface's component
parser) silently falls back to a reduction of 1 when `<mechanical_reduction>`
is not a number, so the joint moves 50 times too far for a 50:1 gearbox.
Drake loads the model and only warns that MultibodyPlant "does not currently
support non-default mechanical reductions".

## How to fix
Write the ratio as one decimal number, e.g.
`<mechanicalReduction>50</mechanicalReduction>` (or `-50` for a reversed
motor), and compute fractions such as `1/50` beforehand (`0.02`).
"""

from __future__ import annotations

import re
from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity
from urdflint.model.structure import q
from urdflint.model.values import fmt, has_xacro, parse_number

LEADING = re.compile(r"^\s*[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
WRIST_PARTS = ("leftActuator", "rightActuator", "flexJoint", "rollJoint")
ATTR = "mechanicalReduction"  # WristTransmission writes it as an attribute


@rule(
    "T003",
    "invalid-mechanical-reduction",
    Severity.ERROR,
    fix="Write the reduction as one non-zero decimal number, e.g. 50 (or -50 when reversed).",
)
def check(doc: Document) -> Iterator[Hit]:
    for transmission in doc.transmissions:
        label = f"transmission {q(transmission.get('name'))}"
        for el in children(transmission, "mechanicalReduction"):
            yield from _check(el, None, el.text, f"the <mechanicalReduction> of {label}")
        for part in children(transmission):
            tag = str(part.tag)
            where = f"{_part(part)} of {label}"
            if tag in ("joint", "actuator"):
                for el in children(part, "mechanicalReduction"):
                    yield from _check(el, None, el.text, f"the <mechanicalReduction> of {where}")
            elif tag in WRIST_PARTS and part.get("mechanicalReduction") is not None:
                text = part.get("mechanicalReduction")
                yield from _check(
                    part, "mechanicalReduction", text, f"mechanicalReduction of {where}"
                )
    for block in children(doc.robot, "ros2_control"):
        for transmission in children(block, "transmission"):
            label = f"ros2_control transmission {q(transmission.get('name'))}"
            for part in [*children(transmission, "joint"), *children(transmission, "actuator")]:
                for el in children(part, "mechanical_reduction"):
                    what = f"the <mechanical_reduction> of {_part(part)} of {label}"
                    yield from _check(el, None, el.text, what, ros2=True)


def _part(el: etree._Element) -> str:
    return f"<{el.tag}> {q(el.get('name'))}"


def _check(
    el: etree._Element, attribute: str | None, text: str | None, what: str, ros2: bool = False
) -> Iterator[Hit]:
    raw = (text or "").strip()
    if has_xacro(raw):
        return
    value = parse_number(raw)
    if value is not None and value != 0:
        return
    if value == 0:
        message = f"{what} is {raw!r}: a reduction cannot be zero"
    elif ros2:
        message = f"{what} is {raw!r}, not one number (ros2_control uses 1 instead)"
    elif not raw:
        message = f"{what} is empty"
    else:
        prefix = LEADING.match(raw)
        reads = f" (std::stod reads {fmt(float(prefix.group(0)))})" if prefix else ""
        message = f"{what} is {raw!r}, not one number{reads}"
    yield Hit(el, message, attribute=attribute)
