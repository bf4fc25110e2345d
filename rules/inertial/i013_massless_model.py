"""The root link has no mass and nothing welded to it has any: Gazebo loses the whole model.

## What it does
Under a Gazebo target (`gazebo-classic`, `gz-sim`), reports the root link of
the tree when neither it nor any link merged into it through fixed joints has a
mass: no `<inertial>`, or `<mass value="0">`. That covers a massless root whose
children all hang from movable joints (a fixed-base arm whose `base_link` was
left without mass) and a single-link robot with mass 0. A root named `world`
is not reported: sdformat treats it as the world and converts its children one
by one (I001 and I002 judge them). Roots with a negative mass are I002's. A model
made only of frames (no `<inertial>`, `<visual>` or `<collision>` anywhere, down to a
lone empty link, as sdformat's own test `mass_no_inertial`) is reported too: Gazebo
refuses it all the same (observed, sdformat 12.3), while MuJoCo, Drake, PyBullet and
Pinocchio load it.

It is an **error** when the root declares its mass 0 (`<mass value="0"/>`,
PyBullet's way of pinning a base) or is the only link, and a **warning** when
the root of a multi-link model has no `<inertial>` at all: the layout of
kinematic examples, of models meant for RViz or Pinocchio only, and of roots
whose inertial was deleted to silence KDL's root-inertia warning (I011). Gazebo
loses the model all the same; the warning only reflects that nothing says the
model was meant for Gazebo. The finding is on the root's `<mass>` when it has
one, else on the link.

## Why is this bad?
sdformat's URDF converter (`CreateSDF` in `parser_urdf.cc`) starts at the root
link and returns at the first massless link without converting anything below
it. With a massless root it therefore writes a model with no link at all, and
loading it fails: sdformat's DOM reports "A model must have at least one link."
Gazebo Classic and Gazebo Sim spawn nothing. Since sdformat 9.10.1, 12.7.2 and
13.5.0 the converter also prints "urdf2sdf: link[X] has no <inertial> block
defined" (or "has a mass value of less than or equal to zero") and "[N] child
links ignored"; before, it said nothing.

Other consumers accept such a model (observed): Pinocchio 4.1 builds it (the
root sits on the universe joint; with no mass anywhere `centerOfMass` is NaN);
MuJoCo 4.0 makes the root static and fuses it into the world; PyBullet 3.2.7
reads a root with mass 0 as a static (fixed) base, its documented convention,
and gives a root without `<inertial>` 1 kg; Drake 1.51 loads it as a free body
and fails at the first simulation step of a single massless link ("An internal
mass matrix ... is not positive-definite"). A model written for PyBullet (mass 0
to pin the base) therefore loads there and vanishes in Gazebo.

## How to fix
Give the real base link its mass, or keep a massless root (for example
`base_footprint`, which KDL prefers) and attach the base link, with its mass, to
it with a `fixed` joint: Gazebo merges the two and keeps the mass. To pin the
robot to the world in Gazebo, add a link named `world` and a fixed joint to the
base link.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import GAZEBO_MASSLESS, bodies
from urdflint.model.document import Document
from urdflint.model.effects import single
from urdflint.model.finding import Severity
from urdflint.model.targets import GAZEBO, gazebo_label


@rule(
    "I013",
    "massless-model",
    Severity.ERROR,
    fix="Give the base link its mass, or fix a massive base link to a massless root.",
    targets=GAZEBO,
    effects=single(K.MASSLESS_MODEL),
)
def check(doc: Document) -> Iterator[Hit]:
    root = doc.graph.root
    if root == "world":
        yield from _world(doc)
        return
    if root is None:
        return
    if doc.recovered and not any(
        link.inertial is not None or link.visuals or link.collisions for link in doc.links
    ):
        return  # frames recovered from a broken file: what is missing may be cut off
    b = bodies(doc)
    members = [name for name, _, _ in b.members(root)]
    masses = [i.mass for n in members if (i := b.inertials.get(n)) is not None]
    if any(m is None or m != 0 for m in masses):
        return  # some mass (or one urdflint cannot read, or a negative one: I002's)
    inertial = b.inertials.get(root)
    below = len(doc.graph.subtree(root)) - 1
    link = doc.link_map[root]
    what = "mass 0 kg" if inertial is not None else "no <inertial>"
    welded = " and nothing welded to it has mass" if len(members) > 1 else ""
    if below:
        lost = f"the whole model ({below + 1} links)"
        who = f"root link '{root}'"
    else:
        lost, who = "the whole model", f"the only link, '{root}',"
    yield Hit(
        inertial.mass_element if inertial is not None else link.element,
        f"{who} has {what}{welded}, so {gazebo_label(doc.targets)} drops it and with it "
        f'{lost}: sdformat finds no link to load ("A model must have at least one link")',
        attribute="value" if inertial is not None and inertial.mass_element is not None else None,
        severity=Severity.ERROR if inertial is not None or not below else Severity.WARNING,
    )


def _world(doc: Document) -> Iterator[Hit]:
    """A root named ``world`` is the world frame to sdformat, which does not lump into it:
    each link welded to it is a body of its own, dropped with its subtree when massless.
    When every one is, no link is left (observed: "A model must have at least one link")."""
    b = bodies(doc)
    below = [j.child for j in doc.graph.child_joints.get("world", []) if j.child in doc.link_map]
    masses = [b.mass(name) for name in below]
    if not below or any(m is None or m < 0 or m > GAZEBO_MASSLESS for m in masses):
        return  # some mass (or one unreadable, or a negative one: I002's)
    if not any(link.inertial is not None for link in doc.links):
        return  # a kinematics-only model: I001 says it once
    label = gazebo_label(doc.targets)
    yield Hit(
        doc.link_map["world"].element,
        f"no link welded to 'world' has mass, so {label} drops them all ('world' is the world "
        "frame to it; a mass on it is ignored) and finds no link to load",
        fix="Give the links below 'world' their real masses.",
    )
