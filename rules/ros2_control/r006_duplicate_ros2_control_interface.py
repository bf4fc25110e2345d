"""The same command or state interface is declared twice in the ros2_control blocks.

## What it does
Builds the key of every interface the top-level `<ros2_control>` blocks declare,
`<component name>/<interface name>` as ros2_control does (joints, sensors and GPIOs
share one namespace), separately for command and state interfaces, and reports the
second declaration of a key. An error when the two are in different blocks (one
finding per pair of blocks, on the first repeated interface, counting and naming the
others: a MoveIt config that adds a `FakeSystem` block beside the description's own
block repeats every interface), a warning when both are in the same block. A joint
listed in two blocks with different interfaces (state in one, command in the other) is
legal and not reported.

## Why is this bad?
The resource manager stores interfaces in one map per kind keyed by that name.
Since Jazzy, `ResourceStorage::add_state_interface` and `insert_command_interface`
(hardware_interface `resource_manager.cpp`) throw "Tried to insert StateInterface
with already existing key" when a second hardware component exports the same key,
and the component fails to load; Humble's `emplace` silently keeps the first one,
so the second hardware never receives the commands or never publishes the state.
Within one block, the default export of Jazzy and later
(`parse_state_interface_descriptions` into a map) keeps one of the two
declarations and drops the other's `<param>`s, while plugins that export from
`info_.joints` themselves create the key twice and hit the same exception.

## How to fix
Declare each interface once: a joint (or sensor, GPIO) belongs to one hardware
component, and each of its interfaces is listed once. Rename a sensor or GPIO whose
name is also a joint's.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import ros2_control as R
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import written_at


@rule(
    "R006",
    "duplicate-ros2-control-interface",
    Severity.ERROR,
    fix="Declare each interface of a joint, sensor or GPIO once, in one block.",
)
def check(doc: Document) -> Iterator[Hit]:
    seen: dict[tuple[str, str], tuple[R.Block, R.Interface]] = {}
    shared: dict[tuple[int, int], list[tuple[R.Interface, str, R.Block, R.Interface]]] = {}
    for block in R.blocks(doc):
        for component in block.components:
            if component.name is None:
                continue
            for interface in component.interfaces:
                if interface.name is None:
                    continue
                key = f"{component.name}/{interface.name}"
                first = seen.setdefault((interface.kind, key), (block, interface))
                if first[1] is interface:
                    continue
                other, earlier = first
                if other is block:
                    yield Hit(
                        interface.element,
                        f"{interface.kind} interface {key!r} is declared twice in {block.label} "
                        f"(first at {written_at(doc, earlier.element)})",
                        severity=Severity.WARNING,
                    )
                else:  # one finding per pair of blocks, on the first repeated interface
                    pair = shared.setdefault((id(block), id(other)), [])
                    pair.append((interface, key, other, earlier))
    for repeated in shared.values():
        yield _across(doc, repeated)


def _across(doc: Document, repeated: list[tuple[R.Interface, str, R.Block, R.Interface]]) -> Hit:
    interface, key, other, earlier = repeated[0]
    block_label = next(b.label for b in R.blocks(doc) if interface in _interfaces(b))
    where = written_at(doc, earlier.element)
    if len(repeated) == 1:
        what = f"{interface.kind} interface {key!r} of {block_label} is"
    else:
        keys = [f"{i.kind} {k}" for i, k, _, _ in repeated]
        listed = ", ".join(keys[:3]) + (f" and {len(keys) - 3} more" if len(keys) > 3 else "")
        what = f"{len(repeated)} interfaces of {block_label} ({listed}) are"
    return Hit(
        interface.element,
        f"{what} also declared by {other.label} (first at {where}): the resource manager "
        "refuses a second interface with the same name",
    )


def _interfaces(block: R.Block) -> list[R.Interface]:
    return [i for c in block.components for i in c.interfaces]
