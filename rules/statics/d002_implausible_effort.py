"""A joint's effort limit is far above any torque its own load could need: a placeholder.

## What it does
Compares each revolute, continuous and prismatic joint's `effort` with what the links it
carries can ask of it, from two analytic bounds (Pinocchio's model, the root link fixed):

- **gravity**: the most gravity can load it in any configuration, `g × Σ mass × the
  farthest its centre of mass can get from the axis` (for a prismatic joint, the weight
  along the axis);
- **1 g**: the same with the axis level, the torque that accelerates what it carries at
  1 g, an allowance for dynamics and a modest payload.

It reports an effort of at least **1000** (N·m or N) that is more than **50 times** the
sum of the two. The payload given with `--payload` or `statics.payload` is included in
both bounds; `[tool.urdflint.rules.D002] ratio = 50` and `floor = 1000` change the
thresholds.

Why these thresholds: over every joint of 36 robots of a public corpus and the real PR2,
TIAGo, Universal Robots and Franka descriptions (696 joints with an effort), the efforts of
1000 or more that are real ratings (the PR2 and TIAGo torso lifts, 10000 N and 2000 N) are
at most 5.5 times this sum; the placeholders of 1000 or more (every joint of solo12 at
1000 N·m, Baxter's head pan at 50000 N·m, PR2's gripper joints at 1000, R2D2's head and
gripper at 1000) are at least 408 times it. Below 1000 no ratio separates the two: the
real fingers of Valkyrie (10 N·m), TIAGo's hand (2 N·m) or Atlas' ankles (740 N·m, a leg
in stance) are hundreds to thousands of times their hanging load, since a finger's
own weight is tiny and a leg's load is the robot's. So smaller efforts are never reported.

Not reported: a joint that carries no mass (there is nothing to compare with; I001 and
I013 report missing masses), or whose load sits on its axis (a wheel, a roll joint:
their effort drives contact, not a weight), and mimic joints.

## Why is this bad?
The effort limit is the one number every simulator and controller uses to protect the
joint: Gazebo and Gazebo Sim clamp forces to it, Isaac Sim makes it the drive's
`maxForce`, Drake and MuJoCo clamp actuation to it, ros_control and planners read it as
what the actuator can do. A placeholder like 1000 N·m on a finger clamps nothing: a
controller's spike or a badly tuned gain reaches the joint in full, grasps crush,
contacts explode, and torque-based planning believes the finger can lift a car. Nothing
loads differently, so it is an **info**: the model works, but its limit means nothing.

## How to fix
Write the actuator's rated torque (N·m) or force (N) after its gearbox, from the data
sheet. If the joint really is that strong for a load the model does not show (a lift
rated for a heavy payload), give the payload (`statics.payload`) or suppress D002 on it
with a reason.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from urdflint.rules.statics import effort as K

from urdflint.engine.registry import Hit, rule
from urdflint.model import joints as J
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.values import fmt

RATIO = 50.0
FLOOR = 1000.0  # N·m or N
LEVEL = 1e-6  # N·m or N: a 1 g load smaller than this is on the axis (a wheel)


@rule(
    "D002",
    "implausible-effort",
    Severity.INFO,
    needs=("pinocchio",),
    fix="Write the actuator's rated torque or force after its gearbox, from the data sheet.",
    options={"ratio": RATIO, "floor": FLOOR},
    effects={"": K.PLACEHOLDER},
)
def check(doc: Document, opts: dict[str, Any]) -> Iterator[Hit]:
    from urdflint.engine import statics as S

    found = S.of(doc)
    if not found.ok:
        return
    ratio, floor = float(opts["ratio"]), float(opts["floor"])
    for name, load in found.joints.items():
        effort = load.effort
        if effort is None or effort < floor or load.level <= LEVEL:
            continue
        allowance = load.bound + load.level
        if effort <= ratio * allowance:
            continue
        joint = doc.joint_map[name]
        lim = J.limit(joint)
        unit = load.unit
        yield Hit(
            lim.element if lim is not None else joint.element,
            f"{J.label(joint)} has effort {fmt(effort)} {unit}, {_times(effort / allowance)} times "
            f"what its own load can need: gravity at most {load.bound:.3g} {unit} in any "
            f"configuration, {load.level:.3g} {unit} to accelerate it at 1 g; "
            f"{fmt(effort)} looks like a placeholder",
            attribute="effort",
        )


def _times(ratio: float) -> str:
    return f"{ratio:.0f}" if ratio < 1e6 else f"{ratio:.3g}"
