"""A joint's effort limit is below the gravity torque it must hold somewhere in its range.

## What it does
For every revolute, continuous and prismatic joint with a positive `effort`, computes
with Pinocchio the largest torque (N·m) or force (N) gravity puts on it over the
configurations the joint limits allow (continuous joints: every angle), with the root
link fixed, and reports the joint when that exceeds its effort limit. The finding sits on
the `effort` attribute of the `<limit>` (in the xacro file and macro that write it), and
states the torque and the configuration: the joint values that decide it (the joint's
ancestors turn its axis against gravity, its descendants move its load), the others at
0. The torque is evaluated again at exactly those values.

How the maximum is found (`urdflint info --statics` shows it for every joint): every
joint is sampled within its limits, the best samples of each joint are refined by
gradient ascent (`computeGeneralizedGravityDerivatives`) within the limits, and an
analytic bound (the mass it carries times the farthest its centre of mass can be from the
axis) proves most joints safe without any search. Mimic joints follow their leader.

Gravity is `(0, 0, -9.81)` m/s² in the root link's frame; a wall- or ceiling-mounted
arm sets `--gravity 9.81,0,0` (or `[tool.urdflint.statics] gravity = [9.81, 0, 0]`). A
payload at the tool is added with `--payload 2` (kg, at the end of the longest chain or
the hand it ends in) or `--payload 2@tool0`, or `statics.payload = "2@tool0"`.

Not reported:

- a joint whose effort is 0 or absent (J010 and J001 report those), a mimic joint;
- a passive joint: when the model declares its actuators (`<transmission>` or
  `<ros2_control>` command interfaces), a joint none of them names (a suspension, a
  caster) has no motor for the limit to hold back;
- a leg carrying the robot. With the root fixed, a leg hangs: the torque computed is what
  it needs to lift itself, a lower bound of what it needs in stance, which depends on the
  gait and is out of scope here. A leg reported cannot even lift itself.

When every link the joint carries has gravity turned off in its `<gazebo>` block (PR2
does this for its spring-counterbalanced arms), the message says so: Gazebo does not see
the load, the other simulators do.

## Why is this bad?
Gazebo Classic clamps every force a controller commands to `±effort`, Gazebo Sim (DART)
makes it the joint's force limit, Isaac Sim the drive's `maxForce`, Drake (with a
`<transmission>`) clamps the actuation to it, MuJoCo makes it the joint's
`actuatorfrcrange`, and ros_control saturates effort commands to it. A joint asked to hold
more sags in simulation whatever its controller's gains, and a trajectory that passes
through that configuration cannot be followed. Usually the value is a typo or a wrong unit
(30 for 300), copied from another joint, or the peak torque of the motor without its
gearbox; sometimes the real robot has a counterbalance spring or a brake the URDF does not
model.

## How to fix
Write the actuator's rated torque after its gearbox (N·m, N for a prismatic joint), from
the data sheet. If the real joint is counterbalanced, model the spring (a `<dynamics>`
stiffness where the simulator supports one, or gravity compensation in the controller)
and suppress D001 on it with a reason. The unsafe fix (`urdflint fix --unsafe-fixes`) raises
the effort to the torque needed × 1.25 (a quarter more to accelerate), rounded up to two
digits: a value to check against the data sheet, not a rating. A payload or gravity set for
the check (`--payload`, `--gravity`) that the robot is not meant for is fixed in the
configuration.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from urdflint.rules.statics import effort as K

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model.document import Document
from urdflint.model.edits import Repair, SetAttribute
from urdflint.model.effects import Effect
from urdflint.model.finding import Severity
from urdflint.model.values import fmt

if TYPE_CHECKING:
    from lxml import etree

    from urdflint.engine.statics import JointLoad, Statics

HEADROOM = 1.25  # the fix's effort: the gravity torque plus a quarter to accelerate
WEIGHTLESS = 0.99  # of the mass a joint carries: with gravity off, Gazebo sees no load


@rule(
    "D001",
    "effort-cannot-hold",
    Severity.WARNING,
    needs=("pinocchio",),
    fix="Write the actuator's rated torque after its gearbox, from the data sheet.",
    effects={"": K.CANNOT_HOLD},
    by_target=True,
)
def check(doc: Document) -> Iterator[Hit]:
    from urdflint.engine import statics as S

    found = S.of(doc)
    if not found.ok:
        return  # P001 says why Pinocchio has no model
    if found.unknown_link is not None:
        yield _unknown_link(doc, found)
    for name, load in found.joints.items():
        if not load.effort or load.effort <= 0 or load.passive or load.proven:
            continue
        load = found.load(name)
        effort = load.effort or 0.0
        if load.needed is None or load.needed <= effort * (1 + 1e-9):
            continue
        joint = doc.joint_map[name]
        lim = J.limit(joint)
        yield Hit(
            lim.element if lim is not None else joint.element,
            _message(doc, found, load, J.label(joint)),
            attribute="effort",
            effects=_effects(doc, name),
            repair=_raise(lim.element, load) if lim is not None else None,
        )


def _raise(element: etree._Element, load: JointLoad) -> Repair:
    """The unsafe fix: the effort limit raised to the torque needed times :data:`HEADROOM`,
    rounded up to 2 significant digits."""
    value = _round_up((load.needed or 0.0) * HEADROOM)
    return Repair(
        "unsafe",
        f"raise the effort limit to {fmt(value)} {load.unit} (the {shown(load.needed or 0.0, 0)} "
        f"{load.unit} gravity needs × {HEADROOM}, headroom to accelerate; check the "
        "actuator's data sheet)",
        (SetAttribute(element, "effort", fmt(value)),),
    )


def _round_up(value: float) -> float:
    """``value`` rounded up to two significant digits (61.9 → 62, 123.4 → 130)."""
    import math

    if value <= 0:
        return value
    step = 10 ** (math.floor(math.log10(value)) - 1)
    return math.ceil(value / step - 1e-9) * step


def _message(doc: Document, found: Statics, load: JointLoad, label: str) -> str:
    from urdflint.engine.statics import describe

    unit, needed, effort = load.unit, load.needed or 0.0, load.effort or 0.0
    return (
        f"{label} needs {shown(needed, effort)} {unit} to hold what it carries against gravity "
        f"{describe(found, load)}, above its effort limit {fmt(effort)} {unit}"
        + _weightless_note(doc, load.name)
    )


def shown(value: float, other: float) -> str:
    """``value`` with enough digits (at least 3) to tell it from ``other``."""
    for digits in range(3, 10):
        text = f"{value:.{digits}g}"
        if text != f"{other:.{digits}g}":
            return text
    return fmt(value)


def _weightless_note(doc: Document, name: str) -> str:
    if not _all_weightless(doc, name):
        return ""
    return (
        "; the <gazebo> blocks turn gravity off for the links it carries, so Gazebo does not "
        "see this load, the other simulators do"
    )


def _all_weightless(doc: Document, name: str) -> bool:
    """Whether the links with gravity off in ``<gazebo>`` make (nearly) all the mass the
    joint carries."""
    from urdflint.engine.statics_roles import carried, weightless
    from urdflint.model.inertia import read_inertial

    off = weightless(doc)
    if not off:
        return False
    total = without = 0.0
    for link in carried(doc, name):
        entry = doc.link_map.get(link)
        inertial = read_inertial(entry.element) if entry is not None else None
        mass = inertial.mass if inertial is not None and inertial.mass else 0.0
        total += mass
        without += mass if link in off else 0.0
    return total > 0 and without >= WEIGHTLESS * total


def _effects(doc: Document, name: str) -> dict[str, Effect] | None:
    if not _all_weightless(doc, name):
        return None
    return {
        **K.CANNOT_HOLD,
        "gazebo-classic": K.GAZEBO_WEIGHTLESS,
        "gz-sim": K.GAZEBO_WEIGHTLESS,
    }


def _unknown_link(doc: Document, found: Statics) -> Hit:
    from urdflint.model.structure import did_you_mean

    link = found.unknown_link or ""
    hint = did_you_mean(link, list(doc.link_map), "link")
    return Hit(
        None,
        f"the payload link '{link}' (--payload, statics.payload) is not a link of the model; "
        "the gravity torques are computed without the payload",
        fix=hint or "Name a link of the model after @ in the payload.",
        severity=Severity.ERROR,
    )
