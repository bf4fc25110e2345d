"""Collision geometry of two non-adjacent links overlaps at the zero pose.

## What it does
Places every `<collision>` in the world at the zero configuration (or at `--q
JOINT=VALUE` / `expect.q`; a mimic joint follows its leader, `multiplier * leader +
offset`) and reports each pair of links whose collision shapes interpenetrate by
`min-depth` millimetres or more (default 1 mm), once per pair, on the second link's
deepest `<collision>`, with the depth. Links welded into one rigid body by `fixed`
joints, the parent and child of one joint, and pairs an SRDF disables
(`<disable_collisions>`) or a `<drake:collision_filter_group>` ignores are not pairs.

Boxes, spheres, cylinders and capsules are taken as written; a mesh as its convex hull
(what MuJoCo, PyBullet and Drake collide with; the message says so). The depth is
coal's (hpp-fcl, installed with Pinocchio) exact signed distance. Without coal, a numpy
fallback is exact for spheres and boxes (separating-axis test) and uses the oriented
bounding box of a cylinder, capsule or mesh: such findings say "bounding boxes" and are
at most info. Meshes need trimesh; without it, or when a mesh cannot be read (C004-C006),
its collision is left out.

The severity follows the selected targets (`--target`): a warning when one of them
collides the pair at the start, else info.

- MuJoCo (observed, 4.0): every geom has `contype = conaffinity = 1`, so all bodies
  collide except a parent and its child (`filterparent`); the URDF import fuses links
  welded by fixed joints (`fusestatic`), so a link fixed to the parent of the other link
  counts as its parent. The import also welds the root link to the world, which is never
  filtered against its children: a pair of the root's body and a link welded to its child
  collides while the base is fixed and is filtered once a free joint is added (a legged
  robot): info. (The root's own children collide with it too while it is welded; those
  adjacent pairs are never reported.) At t = 0 the contact forces push the bodies apart:
  in a test arm a joint swung by a radian in 0.4 s with no command. MuJoCo does not read
  the SRDF; a pair the SRDF disables is skipped all the same, as declared by design.
- Drake (observed, 1.51): `MultibodyPlant` filters only bodies joined by a joint and
  bodies welded together; a link fixed to a neighbour's parent still collides with it
  (warning, also for those "body-adjacent" pairs).
- Gazebo Classic and Gazebo Sim: links of one model collide only with
  `<self_collide>` (default false: `<selfCollide>true</selfCollide>` in a
  `<gazebo reference>`, or in the robot-level `<gazebo>`); warning then, for primitives
  (Gazebo collides the triangles of a mesh, not its hull: info).
- ROS (MoveIt): the planning scene reports the start state in collision until the pair
  is disabled; the Setup Assistant disables pairs in collision at the default pose
  ("Default") and adjacent ones. Warning when an SRDF is found (it does not disable the
  pair), info otherwise; info for meshes (MoveIt checks the triangles, not the hull).
- PyBullet: self-collision is off unless `URDF_USE_SELF_COLLISION` (observed, 3.2.7:
  then parent-child pairs only are excluded); Isaac Sim's importer has
  `self_collision` off by default; Pinocchio collides only the pairs a program adds.
  Info.

Cross-checked against MuJoCo's contacts at `qpos0` on corpus robots (mir100, solo12,
abb_irb2400, unitree_z1, baxter, atlas, pal_hey5): the same pairs and the same depths to
0.1 mm, meshes included (MuJoCo also collides convex hulls).

At most 5,000 candidate pairs (overlapping bounding boxes) are measured: a model whose
links pile up at the pose (hundreds at one place) gets one info finding saying how many
were left unmeasured.

## Why is this bad?
A simulator that collides the two bodies starts with a deep contact: the solver pushes
them apart at the first step, the robot jumps or explodes, or joints are driven
against their controllers (agilexrobotics/piper_ros#1, Genesis#1000). A motion planner
finds the start state in collision and refuses to plan
(Universal_Robots_ROS2_Driver#413).

## How to fix
If the overlap is by design (a cover, a finger inside a palm), disable the pair:
`<disable_collisions link1="a" link2="b" reason="Default"/>` in the SRDF for MoveIt,
`<contact><exclude body1="a" body2="b"/></contact>` in MuJoCo, a
`<drake:collision_filter_group>` for Drake. Otherwise move or shrink the collision
geometry so the links only touch at the zero pose. Raise `min-depth` to ignore small
overlaps:

```toml
[tool.urdflint.rules.C013]
min-depth = 5.0  # millimetres
```
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

from urdflint.engine.registry import Hit, rule
from urdflint.model import targets as T
from urdflint.model.document import Document, children, local_tag
from urdflint.model.effects import Effect, kept
from urdflint.model.finding import Severity

if TYPE_CHECKING:
    from urdflint.sources.self_collision import Overlap

PUSHED = "collides the two bodies: the contact pushes them apart at the first step"
WORLD = (
    "collides them while the root is welded to the world, as the URDF import does: the world "
    "body is not filtered against its children (a free joint on the root filters the pair)"
)
PLANNING = "reports the start state in collision until the SRDF disables the pair"
TRUE = ("true", "1")


@rule(
    "C013",
    "self-collision",
    Severity.WARNING,
    fix="If the overlap is by design, disable the pair (SRDF <disable_collisions>); "
    "otherwise move or shrink the collision geometry.",
    options={"min-depth": 1.0},
    needs=("numpy",),
)
def check(doc: Document, opts: dict[str, Any]) -> Iterator[Hit]:
    from urdflint.sources.self_collision import overlaps  # numpy: imported when it runs

    min_depth = max(float(opts["min-depth"]), 0.0) / 1000.0
    disabled = srdf_pairs(doc)
    filtered = drake_filtered(doc)
    found, method = overlaps(doc, max(min_depth, 1e-9), disabled | filtered)
    if "candidate pairs" in method:
        yield Hit(None, f"self-collision: {method.split('; ', 1)[1]}", severity=Severity.INFO)
    if not found:
        return
    pose = _pose(doc)
    colliding = self_colliding(doc)
    for overlap in found:
        effects = target_effects(doc, overlap, bool(disabled), colliding)
        severity = max((e.level for e in effects.values()), default=Severity.INFO)
        if overlap.approximate:
            severity = Severity.INFO
        yield Hit(
            overlap.element,
            _message(overlap, pose, method, effects),
            fix=_fix(overlap),
            severity=severity,
            effects={t: e for t, e in effects.items() if e.level is Severity.WARNING} or None,
        )


def _pose(doc: Document) -> str:
    from urdflint.sources.self_collision import joint_values

    values = {k: v for k, v in joint_values(doc).items() if v != 0.0}
    if not values:
        return "at the zero pose"
    shown = ", ".join(f"{k}={v:.6g}" for k, v in sorted(values.items()))
    return f"at the configuration {shown}"


def _message(overlap: Overlap, pose: str, method: str, effects: dict[str, Effect]) -> str:
    text = (
        f"collision geometry of links '{overlap.first}' and '{overlap.second}' overlaps by "
        f"{overlap.depth * 1000:.1f} mm {pose}"
    )
    notes = []
    if overlap.approximate:
        notes.append("bounding boxes of cylinders and meshes: coal is not installed")
    elif overlap.mesh:
        notes.append("meshes as their convex hulls")
    if notes:
        text += f" ({'; '.join(notes)})"
    warned = [T.LABELS[t] for t, e in effects.items() if e.level is Severity.WARNING]
    if warned:
        verb = "collides" if len(warned) == 1 else "collide"
        text += f"; {' and '.join(warned)} {verb} them from the start"
    return text


def _fix(overlap: Overlap) -> str:
    pair = f'link1="{overlap.first}" link2="{overlap.second}"'
    return (
        f"If the overlap is by design, disable the pair in the SRDF: <disable_collisions {pair} "
        f'reason="Default"/> (MuJoCo: <exclude body1="{overlap.first}" '
        f'body2="{overlap.second}"/>); otherwise move or shrink the collision geometry.'
    )


def target_effects(
    doc: Document, overlap: Overlap, srdf: bool, colliding: dict[str, bool]
) -> dict[str, Effect]:
    """What each selected target does with the pair (warnings) or may do (info)."""
    found: dict[str, Effect] = {}
    warn, info = Severity.WARNING, Severity.INFO
    model = colliding.get("", False)
    gazebo = any(colliding.get(link, model) for link in (overlap.first, overlap.second))
    for target in T.ordered(doc.targets):
        if target == "drake" or (target == "mujoco" and not overlap.body_adjacent):
            found[target] = kept(PUSHED, warn)
        elif target == "mujoco" and overlap.root:
            found[target] = kept(WORLD, info)
        elif target in T.GAZEBO and gazebo and not overlap.body_adjacent:
            found[target] = kept(PUSHED + " (<self_collide>)", info if overlap.mesh else warn)
        elif target == "ros" and not overlap.body_adjacent:
            found[target] = kept(PLANNING, warn if srdf and not overlap.mesh else info)
        elif target == "pybullet":
            found[target] = kept("collides them with URDF_USE_SELF_COLLISION", info)
    return found


def srdf_pairs(doc: Document) -> set[frozenset[str]]:
    """The pairs the robot's SRDF disables (none while the SRDF reader is absent)."""
    try:
        from urdflint.sources.srdf import disabled_pairs  # type: ignore[import-not-found,unused-ignore]
    except ImportError:
        return set()
    try:
        return set(disabled_pairs(doc))
    except Exception:  # an unreadable SRDF: the M rules report it
        return set()


def self_colliding(doc: Document) -> dict[str, bool]:
    """`<selfCollide>`/`<self_collide>` of each `<gazebo reference>` link; "" for the model
    (a robot-level `<gazebo>`): a link without its own value takes the model's."""
    found: dict[str, bool] = {}
    for gazebo in doc.gazebo:
        for child in children(gazebo):
            if local_tag(child) in ("selfCollide", "self_collide"):
                found[gazebo.get("reference") or ""] = (child.text or "").strip().lower() in TRUE
    return found


def _local(el: Any) -> str:
    """``member`` for ``<drake:member>`` (with or without a declared namespace)."""
    return local_tag(el).rpartition(":")[2]


def drake_filtered(doc: Document) -> set[frozenset[str]]:
    """Link pairs a `<drake:collision_filter_group>` ignores."""
    members: dict[str, set[str]] = {}
    ignores: dict[str, set[str]] = {}
    for group in doc.robot:
        if not isinstance(group.tag, str) or _local(group) != "collision_filter_group":
            continue
        name = group.get("name") or ""
        for child in children(group):
            if _local(child) == "member" and child.get("link"):
                members.setdefault(name, set()).add(str(child.get("link")))
            elif _local(child) == "ignored_collision_filter_group" and child.get("name"):
                ignores.setdefault(name, set()).add(str(child.get("name")))
    pairs: set[frozenset[str]] = set()
    for name, others in ignores.items():
        for other in others:
            for a in members.get(name, ()):
                pairs.update(frozenset((a, b)) for b in members.get(other, ()) if a != b)
    return pairs
