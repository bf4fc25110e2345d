"""An interface's `initial_value`, `min` or `max` is not a number, or is out of range.

## What it does
Reads the `<param>`s that hardware_interface itself interprets on the interfaces of
a top-level `<ros2_control>` block (`parse_interfaces_from_xml` in
`component_parser.cpp`):

- `initial_value` of a `double` (the default `data_type`) or `float32` interface
  that is not a finite decimal number: an error;
- `min`/`max` of a joint's command interface that is not a number: a warning;
- `min` above `max` on a joint's command interface: a warning;
- `initial_value` of a joint's `position` interface outside the URDF
  `<limit lower upper>` of a revolute or prismatic joint: a warning.

Parameters still holding `${...}` (an unexpanded xacro file) are not judged.

## Why is this bad?
- `initial_value` is converted with `hardware_interface::stod` when the interface
  `Handle` is built (Jazzy and later; Humble's mock_components `GenericSystem` does
  the same), which throws "Invalid initial value: 'X' parsed for interface", and the
  hardware component fails to export its interfaces.
- For `min`/`max`, `retrieve_min_max_interface_values` catches the failed
  conversion, prints "Error parsing the limits for the interface ... Skipping it" and
  ignores the limit: the joint runs with the URDF limits only (or none).
  `update_interface_limits` intersects `[min, max]` with the URDF limits (position)
  or takes `min(|min|, max)` (velocity, effort), so an inverted range leaves no
  valid command, or a negative maximum.
- A joint that starts outside its limits (mock hardware and gz_ros2_control start
  from `initial_value`) makes MoveIt refuse to plan from the start state and the
  joint limiters of Jazzy and later clamp the first commands.

## How to fix
Write plain decimal numbers (`0.0`, `-1.57`), compute expressions in xacro
(`${pi/2}`), keep `min` below `max`, and choose an initial position inside the
joint's limits.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model import ros2_control as R
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.values import fmt, has_xacro, parse_number

EPS = 1e-9


@rule(
    "R007",
    "invalid-ros2-control-interface-param",
    Severity.ERROR,
    fix="Write the parameter as one decimal number within the joint's limits.",
)
def check(doc: Document) -> Iterator[Hit]:
    for block in R.blocks(doc):
        for component in block.components:
            for interface in component.interfaces:
                what = f"{interface.kind} interface {interface.name!r} of {component.name!r}"
                yield from _initial(doc, component, interface, what)
                if component.kind == "joint" and interface.kind == "command":
                    yield from _min_max(interface, what)


def _initial(
    doc: Document, component: R.Component, interface: R.Interface, what: str
) -> Iterator[Hit]:
    param = interface.params.get("initial_value")
    if param is None or interface.data_type not in R.NUMERIC_TYPES:
        return
    raw = R.text(param)
    if has_xacro(raw):
        return
    value = parse_number(raw)
    if value is None:
        yield Hit(
            param,
            f"initial_value {raw!r} of the {what} is not a number: ros2_control throws "
            '"Invalid initial value" and the hardware fails to load',
        )
        return
    joint = doc.joint_map.get(component.name or "")
    if component.kind != "joint" or interface.name != "position" or joint is None:
        return
    if joint.type not in J.BOUNDED:
        return
    lim = J.limit(joint)
    if lim is None or lim.lower is None or lim.upper is None or lim.lower > lim.upper:
        return
    if value < lim.lower - EPS or value > lim.upper + EPS:
        unit = J.units(joint.type)[0]
        yield Hit(
            param,
            f"initial_value {fmt(value)} {unit} of the {what} is outside the joint's limits "
            f"[{fmt(lim.lower)}, {fmt(lim.upper)}] {unit}: the joint starts out of bounds",
            severity=Severity.WARNING,
            fix="Choose an initial position inside the URDF limits.",
        )


def _min_max(interface: R.Interface, what: str) -> Iterator[Hit]:
    values: dict[str, float] = {}
    for key in ("min", "max"):
        param = interface.params.get(key)
        if param is None:
            continue
        raw = R.text(param)
        if has_xacro(raw):
            return
        value = parse_number(raw)
        if value is None:
            yield Hit(
                param,
                f"{key} {raw!r} of the {what} is not a number: ros2_control prints "
                '"Error parsing the limits" and ignores the limit',
                severity=Severity.WARNING,
            )
            return
        values[key] = value
    if len(values) == 2 and values["min"] > values["max"]:
        param = interface.params["min"]
        yield Hit(
            param,
            f"min {fmt(values['min'])} of the {what} is above its max {fmt(values['max'])}: "
            "the limits are inverted",
            severity=Severity.WARNING,
            fix="Swap min and max.",
        )
