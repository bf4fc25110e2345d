"""An element inside `<ros2_control>` that the ros2_control parser refuses.

## What it does
Reports what makes hardware_interface's `component_parser.cpp` throw while it reads
a top-level `<ros2_control>` block:

- a child other than `<hardware>`, `<joint>`, `<sensor>`, `<gpio>`,
  `<transmission>` and `<properties>` (`parse_resource_from_xml`: "invalid tag
  name"), including a `<ros2_control>` nested in another;
- a `<joint>`, `<sensor>`, `<gpio>`, `<command_interface>` or `<state_interface>`
  without a `name` (`parse_component_from_xml`, `parse_interfaces_from_xml`:
  "no attribute 'name' in ... tag");
- a `<param>` without a `name` (`parse_parameters_from_xml`: "no parameter name
  attribute set in param tag");
- an interface `size` that is not a positive integer (`parse_size_attribute`:
  "Could not parse size tag");
- a `<limits>` without `enable="true|false"` (Jazzy and later, `parse_bool`);
- a `<transmission>` without `<plugin>` ("Missing <plugin> tag of <transmission>
  element"), or one of its `<joint>`s without `name`, or a `<joint>`/`<actuator>`
  without `role` (`parse_transmission_joint_from_xml`). A transmission
  `<actuator>` without `name` is T005's.

## Why is this bad?
The parser throws a `std::runtime_error`, `parse_control_resources_from_urdf` fails,
and the controller manager (or gazebo_ros2_control / gz_ros2_control) cannot load
any hardware: no controller starts. A misspelt child such as `<joints>` or
`<command_interfaces>` is the usual cause.

## How to fix
Correct the tag name or add the missing attribute. The blocks' grammar is in the
ros2_control documentation ("Hardware Components - URDF") and in the demos
(ros-controls/ros2_control_demos).
"""

from __future__ import annotations

import re
from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model import ros2_control as R
from urdflint.model.document import Document, children, local_tag
from urdflint.model.finding import Severity
from urdflint.model.structure import closest

SIZE_RE = r"[1-9][0-9]*"
BOOLS = ("true", "false")


@rule(
    "R003",
    "malformed-ros2-control-element",
    Severity.ERROR,
    fix="Correct the tag name or add the missing attribute.",
)
def check(doc: Document) -> Iterator[Hit]:
    for block in R.blocks(doc):
        for child in children(block.element):
            tag = local_tag(child)
            if tag not in R.BLOCK_CHILDREN:
                match = closest(tag, sorted(R.BLOCK_CHILDREN))
                yield Hit(
                    child,
                    f"<{tag}> is not an element of {block.label}: the ros2_control parser "
                    f"throws \"invalid tag name '{tag}'\"",
                    fix=f"Did you mean <{match}>?" if match and tag != R.TAG else None,
                )
            elif tag == "transmission":
                yield from _transmission(child, block)
            else:
                yield from _element(child, block)


def _missing(el: etree._Element, attr: str, block: R.Block) -> Hit:
    tag = local_tag(el)
    return Hit(
        el,
        f"<{tag}> in {block.label} has no {attr} attribute: the ros2_control parser throws "
        f"\"no attribute '{attr}' in '{tag}' tag\"",
        fix=f'Add {attr}="...".',
    )


def _element(el: etree._Element, block: R.Block) -> Iterator[Hit]:
    """A <hardware>, <properties>, component or interface, and what it contains."""
    tag = local_tag(el)
    if (tag in R.COMPONENTS or tag in R.INTERFACE_TAGS) and el.get("name") is None:
        yield _missing(el, "name", block)
    if tag in R.INTERFACE_TAGS:
        size = el.get("size")
        if size is not None and not _is_size(size):
            yield Hit(
                el,
                f"<{tag}> {el.get('name')!r} in {block.label} has size {size!r}: the parser "
                'expects a positive integer and throws "Could not parse size tag"',
                attribute="size",
                fix='Write size="N" with N >= 1, or leave it out (1).',
            )
    for child in children(el):
        child_tag = local_tag(child)
        if child_tag == "param" and child.get("name") is None:
            yield Hit(
                child,
                f"<param> in {block.label} has no name attribute: the parser throws "
                '"no parameter name attribute set in param tag"',
                fix='Add name="..." to the <param>.',
            )
        elif child_tag == "limits" and tag in ("joint", *R.INTERFACE_TAGS):
            enable = (child.get("enable") or "").strip().lower()
            if enable not in BOOLS:
                yield Hit(
                    child,
                    f'<limits> in {block.label} needs enable="true" or "false" '
                    f"(got {child.get('enable')!r}): the parser throws",
                    fix='Write <limits enable="false"/> (or "true").',
                )
        elif child_tag in R.INTERFACE_TAGS and tag in R.COMPONENTS:
            yield from _element(child, block)


def _transmission(el: etree._Element, block: R.Block) -> Iterator[Hit]:
    if el.get("name") is None:
        yield _missing(el, "name", block)
    if not children(el, "plugin"):
        yield Hit(
            el,
            f"<transmission> {el.get('name')!r} in {block.label} has no <plugin>: the parser "
            'throws "Missing <plugin> tag of <transmission> element"',
            fix="Add <plugin>transmission_interface/SimpleTransmission</plugin>.",
        )
    for part in [*children(el, "joint"), *children(el, "actuator")]:
        if local_tag(part) == "joint" and part.get("name") is None:
            yield _missing(part, "name", block)
        if part.get("role") is None:
            yield _missing(part, "role", block)
    for param in children(el, "param"):
        if param.get("name") is None:
            yield Hit(param, f"<param> in {block.label} has no name attribute: the parser throws")


def _is_size(text: str) -> bool:
    return re.fullmatch(SIZE_RE, text.strip()) is not None
