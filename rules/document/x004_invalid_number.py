"""A numeric attribute holds something that is not a finite decimal number.

## What it does
Checks every numeric attribute URDF defines: `<mass value>`, the six
`<inertia>` components, `<origin xyz/rpy>`, `<axis xyz>`, `<limit>` (lower,
upper, effort, velocity and the URDF 1.2 acceleration, deceleration, jerk),
`<dynamics>`, `<safety_controller>`, `<calibration>`, `<mimic multiplier/offset>`,
geometry sizes (box size, radius, length, mesh scale) and `<color rgba>`.
A value must be a plain decimal float (`1`, `-0.5`, `1e-3`); `nan`, `inf`,
`1_000`, `1,5`, `0x10` and empty values are reported. A one-number attribute
must hold exactly one number (`radius="0.1 0.2"` is reported) and must not end
with whitespace (`value="1.0 "`): urdfdom's `strToDouble` requires the whole
string to be consumed. Values with `${...}` or `$(...)` are left to X008.

## Why is this bad?
urdfdom (and with it ROS, `check_urdf`, sdformat's URDF import and Pinocchio)
cannot read the value ("mass [..] is not a float", "Unable to parse component
[..] to a double", "effort value (nan) is not a valid float", "Material [X] has
malformed color rgba values"). What it does next depends on where the value is
(observed with `check_urdf` 3.0.1): in a `<joint>` it refuses the whole model
("joint xml is not initialized correctly"); in an `<inertial>` it keeps the link
with mass 0 and without any of its visuals and collisions; in a `<visual>` or
`<collision>` it drops that element and the link's collisions after it; in a
colour it loads the material without its colour. Python parsers (urdf_parser_py,
yourdfpy) are worse: `float()` accepts `nan`, `inf` and `1_0` (a mass of `1_0`
loads as 10 kg), so the robot loads and its dynamics turn to NaN later. Every
other urdflint rule skips values it cannot read, so fix these first.

## How to fix
Write the value as a decimal number with a `.` decimal point, separating the
components of a vector with spaces (`xyz="0 0 0.1"`, not `"0,0,0.1"`).
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K
from urdflint.rules import lumping as L

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.schema import Kind, malformed, owner, typed_values
from urdflint.model.values import has_xacro


@rule(
    "X004",
    "invalid-number",
    Severity.ERROR,
    fix='Write a plain decimal number (space-separated for vectors), e.g. xyz="0 0 0.1".',
    effects={"": K.INVALID_NUMBER, "mass": K.INVALID_MASS},
)
def check(doc: Document) -> Iterator[Hit]:
    for el, attr, kind, value in typed_values(doc.robot):
        if kind is Kind.STRING or has_xacro(value):
            continue
        why = malformed(value, kind)
        if why is not None:
            yield Hit(
                el,
                f"<{el.tag}> {attr} {value!r} of {owner(el)} {why}",
                attribute=attr,
                variant="mass" if el.tag == "mass" else "",
                effects=L.invalid_mass(doc, el) if el.tag == "mass" else None,
            )
