"""A parsed view of the `<ros2_control>` blocks shared by the R rules.

It reads what hardware_interface's ``component_parser.cpp`` reads
(``parse_control_resources_from_urdf`` and ``parse_resource_from_xml``, ros2_control
Humble to Rolling): only the `<ros2_control>` elements that are direct children of
`<robot>`, and in each the `<hardware>` (its first `<plugin>`), `<joint>`,
`<sensor>`, `<gpio>` and `<transmission>` children with their `<command_interface>`,
`<state_interface>` and `<param>` elements. Names are stripped of surrounding
whitespace, as the parser's ``ros2_control::strip`` does.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from urdflint.model.document import children

if TYPE_CHECKING:
    from lxml import etree

    from urdflint.model.document import Document

TAG = "ros2_control"
TYPES = ("system", "actuator", "sensor")  # ResourceManager::load_and_initialize_components
COMPONENTS = ("joint", "sensor", "gpio")
# What parse_resource_from_xml accepts under <ros2_control>; anything else throws
# "invalid tag name". <properties> is read since Jazzy.
BLOCK_CHILDREN = frozenset({"hardware", "properties", *COMPONENTS, "transmission"})
INTERFACE_TAGS = {"command_interface": "command", "state_interface": "state"}
# hardware_interface/types/hardware_interface_type_values.hpp (Rolling); Humble has the
# first four only.
STANDARD = ("position", "velocity", "effort", "acceleration")
KNOWN = frozenset(
    {*STANDARD, "torque", "force", "current", "temperature", "jerk"}
    | {"proportional", "integral", "derivative", "integral_clamp_max", "integral_clamp_min"}
    | {"feedforward"}
)
NUMERIC_TYPES = frozenset({"double", "float32"})  # data_type values whose initial_value is stod


@dataclass(frozen=True, slots=True)
class Interface:
    """A `<command_interface>` or `<state_interface>` of a component."""

    element: etree._Element
    kind: str  # "command" or "state"
    name: str | None
    params: dict[str, etree._Element] = field(default_factory=dict)  # the last <param> per name

    @property
    def data_type(self) -> str:
        return (self.element.get("data_type") or "double").strip()


@dataclass(frozen=True, slots=True)
class Component:
    """A `<joint>`, `<sensor>` or `<gpio>` of a block."""

    element: etree._Element
    kind: str
    name: str | None
    interfaces: tuple[Interface, ...]

    @property
    def commands(self) -> list[Interface]:
        return [i for i in self.interfaces if i.kind == "command"]

    @property
    def states(self) -> list[Interface]:
        return [i for i in self.interfaces if i.kind == "state"]


@dataclass(frozen=True, slots=True)
class Block:
    """One top-level `<ros2_control>` element."""

    element: etree._Element
    name: str | None
    type: str | None
    components: tuple[Component, ...]

    @property
    def joints(self) -> list[Component]:
        return [c for c in self.components if c.kind == "joint"]

    @property
    def hardware(self) -> list[etree._Element]:
        return children(self.element, "hardware")

    @property
    def transmissions(self) -> list[etree._Element]:
        return children(self.element, "transmission")

    @property
    def label(self) -> str:
        return f"<ros2_control> {self.name!r}" if self.name is not None else "<ros2_control>"


def stripped(el: etree._Element, attr: str = "name") -> str | None:
    value = el.get(attr)
    return value.strip() if value is not None else None


def _interface(el: etree._Element) -> Interface:
    params: dict[str, etree._Element] = {}
    for param in children(el, "param"):
        key = stripped(param)
        if key is not None:
            params[key] = param  # parse_parameters_from_xml: a repeated name overwrites
    return Interface(el, INTERFACE_TAGS[str(el.tag)], stripped(el), params)


def _component(el: etree._Element) -> Component:
    interfaces = tuple(_interface(c) for c in children(el) if c.tag in INTERFACE_TAGS)
    return Component(el, str(el.tag), stripped(el), interfaces)


def block(el: etree._Element) -> Block:
    components = tuple(_component(c) for c in children(el) if c.tag in COMPONENTS)
    return Block(el, stripped(el), stripped(el, "type"), components)


def blocks(doc: Document) -> list[Block]:
    """The blocks ros2_control reads: the `<ros2_control>` children of `<robot>`."""
    return [block(el) for el in children(doc.robot, TAG)]


def misplaced(doc: Document) -> list[etree._Element]:
    """`<ros2_control>` elements nested anywhere below `<robot>` but not directly in it."""
    robot = doc.robot
    return [el for el in robot.iter(TAG) if el.getparent() is not robot]


def text(el: etree._Element | None) -> str:
    """An element's text stripped (the parser's ``get_text_for_element``)."""
    return (el.text or "").strip() if el is not None else ""
