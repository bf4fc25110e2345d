"""The mass Pinocchio sees differs from the sum of the URDF's `<mass>` values.

## What it does
Compares three totals: the sum of every link's `<mass value>`; what
`pinocchio.computeTotalMass(model)` returns on the fixed-base model built from
the file; and the model's full total, which adds `model.inertias[0]`.

- **info**, only when an expected mass or centre of mass is set (`--expect-mass`,
  `--expect-com`, `[tool.urdflint.expect]`: P003 and P004 are in play), when the
  naive total differs. Pinocchio puts the root link, and every link welded to it
  by fixed joints, on the *universe* joint. Its `computeTotalMass` and
  `centerOfMass` sum joints 1..n, so they leave those links out. The finding
  names those links, their mass and what the correct total is, so that the
  figures P003 and P004 state can be compared with a script's. The file is fine;
  without expectations the note is not emitted (every fixed-base arm with a
  massive base would get it), and `urdflint info` prints the full total anyway.
- **error**, always, when even the full total differs from the URDF's sum.
  Pinocchio then holds a link with a mass different from the one written, and
  the finding names the links.

## Why is this bad?
A fixed-base model of a mobile robot, of a humanoid, or of an arm whose base
link carries mass, "weighs" less than the robot in `computeTotalMass`. For
husky, 10.5 kg is counted of 56.6 kg. The centre of mass is off, and with them
gravity compensation, balance and payload estimates. No warning is given. The
fixed-to-world layout (RRBot, Gazebo tutorials: link `world`, a fixed joint,
then the robot) hides the first real link this way.

## How to fix
In code that uses Pinocchio, add `model.inertias[0]` (its mass and its lever) to
`computeTotalMass`/`centerOfMass`, or build with a free-flyer root
(`pin.buildModelFromXML(xml, pin.JointModelFreeFlyer())`) and evaluate at the
identity. urdflint's own totals (`urdflint info`, P003, P004) already include it.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.values import fmt

SHOWN = 4


@rule(
    "P002",
    "mass-accounting",
    Severity.INFO,
    needs=("pinocchio",),
    fix="Add model.inertias[0] to computeTotalMass/centerOfMass, or build with "
    "pin.JointModelFreeFlyer(); urdflint's totals include it.",
)
def check(doc: Document) -> Iterator[Hit]:
    from urdflint.engine.physics import close, urdf_masses

    physics = doc.physics
    if not physics.built:
        return
    expect = doc.settings.expect
    static = urdf_masses(doc)
    if not physics.mass_matches:
        wrong = [
            name
            for name in doc.link_map
            if not close(physics.link_masses.get(name, 0.0), static.get(name, 0.0))
        ]
        detail = "; ".join(
            f"link '{n}' has {fmt(static.get(n, 0.0))} kg in the URDF and "
            f"{fmt(physics.link_masses.get(n, 0.0))} kg in Pinocchio"
            for n in wrong[:SHOWN]
        )
        more = f" and {len(wrong) - SHOWN} more" if len(wrong) > SHOWN else ""
        first = doc.link_map[wrong[0]].element.find("inertial/mass") if wrong else None
        yield Hit(
            first,
            f"Pinocchio's model weighs {fmt(physics.mass)} kg but the URDF's <mass> values sum "
            f"to {fmt(physics.urdf_mass)} kg" + (f": {detail}{more}" if detail else ""),
            fix="Check the links named; urdflint's pre-checks should have caught what urdfdom "
            "misreads, so please report this file.",
            severity=Severity.ERROR,
        )
        return
    if close(physics.naive_mass, physics.urdf_mass) or (expect.mass is None and expect.com is None):
        return
    heavy = [n for n in physics.universe_links if static.get(n, 0.0) != 0.0]
    heavy.sort(key=lambda n: (n != physics.root, -abs(static[n])))
    root = physics.root
    parts = []
    for name in heavy[:SHOWN]:
        role = "the root link" if name == root else f"welded to the root link '{root}'"
        parts.append(f"'{name}' ({fmt(static[name])} kg, {role})")
    listed = ", ".join(parts) + (f" and {len(heavy) - SHOWN} more" if len(heavy) > SHOWN else "")
    universe = physics.mass - physics.naive_mass
    yield Hit(
        None,
        f"on the fixed-base model Pinocchio's computeTotalMass gives {fmt(physics.naive_mass)} kg, "
        f"not the URDF's {fmt(physics.urdf_mass)} kg: link{'s' if len(heavy) != 1 else ''} "
        f"{listed} {'sit' if len(heavy) != 1 else 'sits'} on the universe joint "
        f"(model.inertias[0], {fmt(universe)} kg), which computeTotalMass and centerOfMass "
        "leave out",
    )
