"""A `<ros2_control>` block has no name, a wrong type, or no hardware plugin.

## What it does
Checks each top-level `<ros2_control>` block:

- the `name` and `type` attributes are present, and `type` is `system`,
  `actuator` or `sensor` (compared exactly, after stripping blanks);
- the name is not used by an earlier block;
- it has a `<hardware>` element with a non-empty `<plugin>` (the last `<hardware>`
  counts, as in the parser);
- a `type="sensor"` block declares no `<command_interface>` on its joints or GPIOs.

## Why is this bad?
Every one of these stops the controller manager from loading the hardware:

- `parse_resource_from_xml` (hardware_interface `component_parser.cpp`) throws
  "no attribute 'name' in 'ros2_control' tag" / "no attribute 'type' ..." and
  "Missing <plugin> tag of <hardware> element"; without `<hardware>` (or with an
  empty `<plugin>`) the plugin name is empty and pluginlib cannot load it.
- `ResourceManager::load_and_initialize_components` loads a block only when its type
  is exactly `system`, `sensor` or `actuator`: a block typed `System` or `robot` is
  silently skipped, and `validate_storage` then reports its interfaces as missing
  ("Wrong state or command interface configuration"). A repeated name stops loading
  with "Hardware name X is duplicated".
- A sensor component (`SensorInterface`) exports state interfaces only, so the
  command interfaces of a `type="sensor"` block never exist and `validate_storage`
  fails.

## How to fix
Give every block a unique `name`, `type="system"` (or `actuator`/`sensor` for a
single actuator or a read-only device) and a
`<hardware><plugin>package/Class</plugin></hardware>`, e.g.
`mock_components/GenericSystem` or `gz_ros2_control/GazeboSimSystem`. Use a
`system` or `actuator` block for anything that is commanded.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import ros2_control as R
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity
from urdflint.model.structure import written_at


@rule(
    "R002",
    "invalid-ros2-control-hardware",
    Severity.ERROR,
    fix='Give the block a unique name, type="system" and a <hardware><plugin>...</plugin>.',
)
def check(doc: Document) -> Iterator[Hit]:
    seen: dict[str, R.Block] = {}
    for block in R.blocks(doc):
        yield from _attributes(doc, block, seen)
        yield from _hardware(block)
        if block.type == "sensor":
            for component in block.components:
                for interface in component.commands:
                    yield Hit(
                        interface.element,
                        f'{block.label} is type="sensor", which exports state interfaces only: '
                        f"command interface {interface.name!r} of <{component.kind}> "
                        f"{component.name!r} never exists",
                        fix='Use type="system" (or "actuator") for a block with commands.',
                    )


def _attributes(doc: Document, block: R.Block, seen: dict[str, R.Block]) -> Iterator[Hit]:
    el = block.element
    for attr in ("name", "type"):
        if el.get(attr) is None:
            yield Hit(
                el,
                f"{block.label} has no {attr} attribute: the ros2_control parser throws "
                f"\"no attribute '{attr}' in 'ros2_control' tag\"",
            )
    if block.type is not None and block.type not in R.TYPES:
        yield Hit(
            el,
            f"{block.label} has type {block.type!r}: the resource manager loads only "
            "'system', 'actuator' and 'sensor' blocks, so this hardware is never loaded",
            attribute="type",
            fix=f"Use type={_closest_type(block.type)!r}.",
        )
    if block.name is not None:
        first = seen.setdefault(block.name, block)
        if first is not block:
            yield Hit(
                el,
                f"{block.label} repeats the name of the block at {written_at(doc, first.element)}"
                ': the resource manager stops loading ("Hardware name is duplicated")',
                attribute="name",
                fix="Give each <ros2_control> block a unique name (e.g. with the xacro prefix).",
            )


def _hardware(block: R.Block) -> Iterator[Hit]:
    hardware = block.hardware
    if not hardware:
        yield Hit(
            block.element,
            f"{block.label} has no <hardware> element, so no hardware plugin is loaded",
            fix="Add <hardware><plugin>package/Class</plugin></hardware>.",
        )
        return
    last = hardware[-1]
    plugins = children(last, "plugin")
    if not plugins:
        yield Hit(
            last,
            f"the <hardware> of {block.label} has no <plugin>: the parser throws "
            '"Missing <plugin> tag of <hardware> element"',
            fix="Add <plugin>package/Class</plugin>, e.g. mock_components/GenericSystem.",
        )
    elif not R.text(plugins[0]):
        yield Hit(
            plugins[0],
            f"the hardware <plugin> of {block.label} is empty, so pluginlib has no class to load",
            fix="Name the hardware class, e.g. mock_components/GenericSystem.",
        )


def _closest_type(value: str) -> str:
    lowered = value.lower()
    return lowered if lowered in R.TYPES else "system"
