"""The centre of mass of a mobile robot leaves its support polygon: it tips over.

## What it does
For a robot that stands on wheels, casters or feet, finds where it touches the ground and
checks that the centre of mass of the whole robot (Pinocchio, every link included) lies
over the support polygon:

- **the contacts**: the lowest collision points (in the root link's frame, gravity along
  -z, at the zero pose) of the links named like a wheel, caster or foot, of the links on a
  continuous joint, and of leg ends hanging below the base; only those within 1 cm of the
  lowest one touch. `[tool.urdflint.stability] contact-links = [...]` names them instead
  (`contact-tolerance`, `samples`: see the README's "Stability and reach"). The support
  polygon is their convex hull on the ground;
- **error** at the zero pose, what a simulator spawns (and at `--q` / `expect.q` when
  given, the contacts recomputed there): the centre of mass is outside the polygon. The
  finding, on the root link, gives the distance in mm and the side (`+x (front)`), the
  centre of mass, the polygon and the contact links. The robot falls at spawn;
- **warning** when the zero pose stands but a reachable configuration does not: the
  joints that move no contact (arms, torso, head) are sampled within their limits (a
  fixed seed, then a coordinate search; configurations that push a link into the floor
  are left out), and the worst one is given with its joint values (those that do not
  matter back at 0) and its margin. Not for feet: a legged robot moves its legs to stay
  up, so leaning its torso out is for its controller, not a defect of the model;
- **info** when the contacts are in one line or at one point (two wheels on one axle):
  there is no static balance to check. A self-balancing robot is built so; a caster that
  does not reach the ground gives the same picture, so the finding names the candidates
  that do not touch and how high they are.

Nothing is checked for a robot fixed to the world (a root link named `world`), without
wheels, casters, feet or legs (an arm, a hand), when another part of the robot reaches
under the contacts at the zero pose, or when a contact link's mesh cannot be read.
A configured contact link the model does not have is a warning.

## Why is this bad?
Gazebo, Gazebo Sim, Isaac Sim, PyBullet and Drake spawn a mobile robot with a free base:
a centre of mass outside the support polygon tips it over in the first second, before
any controller runs. A centre of mass placed by a wrong `<inertial><origin>` (a sign
flip, a CAD frame) or a heavy arm mounted too far forward does this. Importing with a
fixed base hides it (PyBullet's `useFixedBase=True`, Isaac Sim's `fix_base`, and
MuJoCo's URDF import, which welds the root link to the world) until the robot is
simulated free or built. The warning is the same fall with the arm stretched out: the
robot tips when it reaches, with no payload yet.

## How to fix
Check the `<inertial><origin>` of the heavy links (`urdflint info` lists masses and the
centre of mass), then the geometry the robot stands on: a caster whose collision does not
reach the ground, wheels placed at the wrong height. If the robot really is so, widen
the base, add a counterweight, or limit the arm's joints. Name the contact links in
`[tool.urdflint.stability] contact-links` when the heuristic picks the wrong ones.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from urdflint.engine.registry import Hit, rule
from urdflint.model.effects import kept
from urdflint.model.finding import Severity
from urdflint.model.values import fmt

if TYPE_CHECKING:
    from urdflint.engine.stability import Stability, Stance
    from urdflint.engine.stability_contacts import Support
    from urdflint.model.document import Document

SHOWN = 6  # joints listed in the warning
GAZEBO_SPAWN = kept(
    "spawned with a free base, the robot tips over in the first second; a fixed joint to a "
    "`world` link would hide it",
    Severity.ERROR,
)
SPAWN = {
    "gazebo-classic": GAZEBO_SPAWN,
    "gz-sim": GAZEBO_SPAWN,
    "isaac": kept("with fix_base off (a mobile robot) it tips over; fix_base hides it"),
    "pybullet": kept("loadURDF's default useFixedBase=False: it tips over; True hides it"),
    "drake": kept("the root body is free unless welded to the world: on a ground, it tips"),
    "mujoco": kept(
        "the URDF import welds the root link to the world, which hides it; with a floating "
        "joint from a `world` link it tips over"
    ),
}
REACH = {
    target: kept("the robot tips over when the arm reaches out (no payload yet)")
    for target in ("gazebo-classic", "gz-sim", "isaac", "pybullet", "drake", "mujoco")
}


def point(values: tuple[float, ...]) -> str:
    return "(" + ", ".join(fmt(round(v, 4) + 0.0) for v in values) + ")"


def polygon(support: Support) -> str:
    return ", ".join(point(p) for p in support.polygon)


def links(names: list[str]) -> str:
    shown = ", ".join(f"'{n}'" for n in names[:SHOWN])
    return shown + (f" and {len(names) - SHOWN} more" if len(names) > SHOWN else "")


def joints(values: dict[str, float]) -> str:
    shown = [f"{n}={fmt(round(v, 3))}" for n, v in values.items() if round(v, 3) != 0.0]
    more = f" and {len(shown) - SHOWN} more" if len(shown) > SHOWN else ""
    return ", ".join(shown[:SHOWN]) + more if shown else "every joint at 0"


def falls(stance: Stance, support: Support, root: str, where: str) -> str:
    """The error's message: the margin, the side, the centre of mass and the polygon."""
    return (
        f"the centre of mass {point(stance.com)} m projects {fmt(round(-stance.margin * 1000, 1))}"
        f" mm outside the support polygon, towards {stance.direction}: the robot falls {where};"
        f" the polygon {polygon(support)} m (root link '{root}' frame, the ground "
        f"{fmt(round(stance.height, 4))} m under the centre of mass) spans the lowest "
        f"collision points of {links(support.links)}"
    )


@rule(
    "D003",
    "tips-over",
    Severity.ERROR,
    needs=("pinocchio", "trimesh"),
    fix="Check the heavy links' <inertial><origin> and the geometry the robot stands on; "
    "or widen the base, add a counterweight, limit the arm.",
    effects={"": SPAWN, "reach": REACH, "line": {}},
)
def check(doc: Document) -> Iterator[Hit]:
    from urdflint.engine import stability

    physics = doc.physics
    if not physics.built or physics.root not in doc.link_map:
        return
    found = stability.analyse(doc)
    if found.candidates is not None and found.candidates.unknown:
        for name in found.candidates.unknown:
            yield Hit(
                None,
                f"the stability configuration's contact-links names link '{name}', which the "
                "model does not have",
                fix="Spell the link as the URDF does.",
                severity=Severity.WARNING,
            )
    if not found.mobile or found.support is None:
        return
    yield from _stances(doc, found, physics.root)


def _stances(doc: Document, found: Stability, root: str) -> Iterator[Hit]:
    from urdflint.engine import stability
    from urdflint.engine.stability import OUTSIDE

    element = doc.link_map[root].element
    support = found.support
    assert support is not None
    if support.kind in ("line", "point") and not (support.below or support.unreadable):
        yield Hit(element, _line(support), severity=Severity.INFO, variant="line")
        return
    fell = False
    if found.zero is not None and found.zero.margin < -OUTSIDE:
        fell = True
        yield Hit(element, falls(found.zero, support, root, "at spawn (zero pose)"))
    given, moved = found.given, found.given_support
    if given is not None and moved is not None and given.margin < -OUTSIDE:
        fell = True
        where = f"in the configuration given with --q ({joints(given.values)})"
        yield Hit(element, falls(given, moved, root, where))
    if fell or not stability_wheeled(found):
        return
    worst = stability.sample(doc).worst
    if worst is None or worst.margin >= -OUTSIDE:
        return
    zero = found.zero
    assert zero is not None
    yield Hit(
        element,
        f"at {joints(worst.values)} the centre of mass {point(worst.com)} m leaves the support "
        f"polygon by {fmt(round(-worst.margin * 1000, 1))} mm towards {worst.direction}: the "
        f"robot tips over; the worst of {found.evaluated} configurations of "
        f"{len(found.joints)} joint{'s' if len(found.joints) != 1 else ''} sampled within their "
        f"limits (margin at the zero pose: "
        f"{fmt(round(zero.margin * 1000, 1))} mm; polygon {polygon(support)} m)",
        severity=Severity.WARNING,
        variant="reach",
    )


def stability_wheeled(found: Stability) -> bool:
    """Whether the robot stands on wheels or casters (or configured contacts), not feet."""
    support, candidates = found.support, found.candidates
    if support is None or candidates is None:
        return False
    return all(candidates.links.get(n) in ("wheel", "configured") for n in support.links)


def _line(support: Support) -> str:
    lifted = sorted(support.lifted.items(), key=lambda item: item[1])
    near = [(n, h) for n, h in lifted if h < 0.1]  # a caster, not an arm's roll joint
    missing = "; ".join(
        [f"'{n}' is {fmt(round(h * 1000, 1))} mm above the ground" for n, h in near[:SHOWN]]
        + [f"'{n}' has no collision geometry" for n in support.bare[:SHOWN]]
    )
    return (
        f"the robot touches the ground along a {support.kind}, not a polygon (the lowest "
        f"collision points of {links(support.links)}): it has no static balance to check; a "
        "self-balancing base is built so, a caster that misses the ground gives the same "
        "picture" + (f" ({missing})" if missing else "")
    )
