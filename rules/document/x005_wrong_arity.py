"""A vector attribute has the wrong count of numbers.

## What it does
Checks that `<origin xyz/rpy>`, `<axis xyz>`, `<box size>`, `<mesh scale>` (and
PyBullet's `<plane normal>`, `<specular rgb>`) hold exactly 3 numbers and
`<color rgba>` exactly 4. Only the count is checked here: a value with a
malformed token (`xyz="0,0,1"`) is reported once, by X004, even if its count
is also wrong.

## Why is this bad?
urdfdom (and with it ROS, sdformat's URDF import and Pinocchio) cannot read the
vector ("Parser found 2 elements but 3 expected while parsing vector", "Mesh
scale was specified, but could not be parsed") and, as observed with `check_urdf`
3.0.1, refuses the whole model when it is a joint's `<origin>`, keeps a link with
mass 0 and without its visuals and collisions when it is in the `<inertial>`, and
drops the `<visual>` or `<collision>` (with the link's later collisions) when it
is there. An RGB colour without alpha, the classic `rgba` mistake, is worse
because it is silent: urdfdom reads `rgba="1 0 0"` as opaque black (0 0 0 1)
without a message. PyBullet accepts a single scalar mesh scale ("Scale should be
a vector3, not single scalar. Workaround activated.") and warns "Couldn't parse
vector3" but loads a short origin or box size, so a file that works in PyBullet
can fail everywhere else.

## How to fix
Write all components, separated by spaces: `scale="0.001 0.001 0.001"` rather
than `scale="0.001"`, `rgba="1 0 0 1"` rather than `rgba="1 0 0"`.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.schema import Kind, owner, typed_values, wrong_arity
from urdflint.model.values import has_xacro

VECTORS = frozenset(kind for kind in Kind if kind.arity >= 2)


@rule(
    "X005",
    "wrong-arity",
    Severity.ERROR,
    fix="Write every component, separated by spaces (3 for xyz/rpy/size/scale, 4 for rgba).",
)
def check(doc: Document) -> Iterator[Hit]:
    for el, attr, kind, value in typed_values(doc.robot):
        if kind not in VECTORS or has_xacro(value):
            continue
        count = wrong_arity(value, kind)
        if count is None:
            continue
        numbers = "number" if count == 1 else "numbers"
        yield Hit(
            el,
            f"<{el.tag}> {attr} {value!r} of {owner(el)} has {count} {numbers}, not {kind.arity}",
            attribute=attr,
        )
