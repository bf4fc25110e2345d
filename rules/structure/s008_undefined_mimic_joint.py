"""A `<mimic>` element names no joint, an undefined joint, itself, or a mimic cycle.

## What it does
Reports the `<mimic>` element of a joint when its `joint` attribute is missing,
names no defined joint, names the joint itself, or when mimic references form
a cycle (`a` mimics `b` and `b` mimics `a`). A cycle is reported once, on the
first of its joints in the file.

## Why is this bad?
urdfdom refuses a `<mimic>` without `joint` ("joint mimic: no mimic joint
specified"), and so do MuJoCo ("required attribute missing: 'joint'") and
Drake ("mimic element is missing the required 'joint' attribute"). urdfdom
never checks the target, so `check_urdf`, Pinocchio and PyBullet load a mimic
of a missing joint or of itself, and ROS tools then have nothing to follow:
`joint_state_publisher` and MoveIt compute a follower's position from its
leader. Drake refuses both ("mimic element specifies joint 'K' which does
not exist", "Joints cannot mimic themselves"); MuJoCo refuses a joint that
mimics itself ("element 'J' is repeated in equality constraint") and ignores
a mimic of a missing joint with a misleading warning ("mimic requires
revolute, continuous, or prismatic joints"). A mimic cycle loads in every
consumer tried (Drake and MuJoCo add both constraints), but none of its
joints is a leader: nothing drives them, they only constrain each other.

## How to fix
Point `joint` at the leader joint (check its spelling); a leader must not
itself follow one of its followers.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import did_you_mean, q


@rule(
    "S008",
    "undefined-mimic-joint",
    Severity.ERROR,
    fix="Point the mimic at an existing leader joint that does not follow this one.",
    effects={"undefined": K.MIMIC_UNDEFINED},
)
def check(doc: Document) -> Iterator[Hit]:
    leaders: dict[str, str] = {}  # follower name -> leader name, for resolvable mimics
    for joint in doc.joints:
        mimic = joint.find("mimic")
        if mimic is None:
            continue
        target = (mimic.get("joint") or "").strip()
        if not target:
            yield Hit(mimic, f"<mimic> of joint {q(joint.name)} names no joint")
        elif target == joint.name:
            yield Hit(mimic, f"joint {q(joint.name)} mimics itself")
        elif target not in doc.joint_map:
            yield Hit(
                mimic,
                f"joint {q(joint.name)} mimics joint {target!r}, which is not defined",
                fix=did_you_mean(target, doc.joint_map, "joint"),
                variant="undefined",
            )
        elif joint.name is not None and doc.joint_map.get(joint.name) is joint:
            leaders[joint.name] = target
    yield from _cycles(doc, leaders)


def _cycles(doc: Document, leaders: dict[str, str]) -> Iterator[Hit]:
    done: set[str] = set()
    for start in leaders:  # document order
        path: list[str] = []
        current: str | None = start
        while current is not None and current not in done and current not in path:
            path.append(current)
            current = leaders.get(current)
        if current is not None and current in path:
            cycle = path[path.index(current) :]
            first = min(cycle, key=lambda name: list(leaders).index(name))
            names = " -> ".join(repr(name) for name in [*_rotate(cycle, first), first])
            mimic = doc.joint_map[first].find("mimic")
            yield Hit(mimic, f"mimic references form a cycle: {names}")
        done.update(path)


def _rotate(cycle: list[str], first: str) -> list[str]:
    index = cycle.index(first)
    return cycle[index:] + cycle[:index]
