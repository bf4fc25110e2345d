"""An `<inertial>` lacks its `<mass>`, its `<inertia>` or one of their attributes.

## What it does
Reads a link's `<inertial>` the way urdfdom does and reports:

- an `<inertial>` without `<mass>` or without `<inertia>` (on the `<inertial>`);
- a `<mass>` without `value` (on the `<mass>`);
- an `<inertia>` without one or more of `ixx`, `ixy`, `ixz`, `iyy`, `iyz`
  and `izz` (on the `<inertia>`, naming all that are missing).

URDF gives none of them a default, not even zero products of inertia. Values
that are present but malformed are X004's.

## Why is this bad?
urdfdom rejects the `<inertial>` ("Inertial element must have a mass
element", "Inertial: mass element must have value attribute", "Inertial
element must have inertia element", "Inertial: inertia element missing ixy
attribute") and stops reading the link. It then keeps the link anyway, with
nothing after the inertial. `check_urdf` (urdfdom 3.0.1 and 6.0.0) prints those
errors, then "Could not parse inertial element for Link [X]", and still ends
with "Successfully Parsed XML". Every consumer of urdfdom gets a damaged link:

- The link has no visuals and no collisions. Pinocchio 4.1 builds no
  geometry for it, RViz draws nothing, MoveIt does not check it for collisions,
  and Gazebo's converter, which reads the same urdfdom model, gives it nothing
  to collide with.
- Its mass is 0 when `<mass>` is the problem. When `<inertia>` is, the mass is
  kept but the tensor is zero. KDL, Pinocchio and Gazebo then see a massless
  or inertia-less body.

The only sign of all this is a log line that scrolls past at startup. Parsers
of their own are stricter (observed): PyBullet 3.2.7 refuses the model ("failed
to parse link", "Cannot load URDF file") when `<mass>`, its value or `<inertia>`
is missing, though it reads a missing product of inertia as 0; MuJoCo 4.0
refuses all of them ("XML Error: missing element: 'mass'", "required attribute
missing: 'ixy'").

## How to fix
Write the complete element, with every attribute in SI units:
`<mass value=".."/>` and
`<inertia ixx=".." ixy="0" ixz="0" iyy=".." iyz="0" izz=".."/>` inside the `<inertial>`.
Products of inertia must be written even when they are zero.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import q

ORDER = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")  # urdfdom's order
DROPPED = "urdfdom loads the link without its visuals and collisions"


@rule(
    "I012",
    "incomplete-inertial",
    Severity.ERROR,
    fix="Write <mass value> and <inertia> with all six of ixx, ixy, ixz, iyy, iyz and izz.",
)
def check(doc: Document) -> Iterator[Hit]:
    for link in doc.links:
        inertial = link.inertial  # urdfdom reads the first one only
        if inertial is None:
            continue
        who = f"link {q(link.name)}"
        mass, inertia = inertial.find("mass"), inertial.find("inertia")
        absent = [f"<{tag}>" for tag, el in (("mass", mass), ("inertia", inertia)) if el is None]
        if absent:
            yield Hit(
                inertial,
                f"<inertial> of {who} has no {' and no '.join(absent)}; {DROPPED}"
                + (" and with mass 0" if mass is None else " and a zero inertia tensor"),
            )
        if mass is not None and mass.get("value") is None:
            yield Hit(mass, f"<mass> of {who} has no value; {DROPPED} and with mass 0")
        missing = [c for c in ORDER if inertia is not None and inertia.get(c) is None]
        if missing:
            names = (
                ", ".join(missing[:-1]) + " and " + missing[-1] if len(missing) > 1 else missing[0]
            )
            yield Hit(
                inertia,
                f"<inertia> of {who} has no {names}; {DROPPED} and a zero inertia tensor",
            )
