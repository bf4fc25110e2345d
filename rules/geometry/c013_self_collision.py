"""Collision geometry of two links that an engine collides overlaps at the zero pose.

## What it does
Places every `<collision>` in the world at the zero configuration (or at `--q
JOINT=VALUE` / `expect.q`; a mimic joint follows its leader, `multiplier * leader +
offset`) and reports each pair of links whose collision shapes interpenetrate by
`min-depth` millimetres or more (default 1 mm), once per pair, on the second link's
deepest `<collision>`, with the depth. Links welded into one rigid body by `fixed`
joints are never a pair. The parent and child of one joint, and a pair the SRDF disables
(`<disable_collisions>`, read by MoveIt only), are reported only when a selected target
collides them all the same (MuJoCo collides the root's body with its children, and ignores
the SRDF).

Boxes, spheres, cylinders and capsules are taken as written; a mesh as its convex hull
(what MuJoCo, PyBullet and Drake collide with; the message says so). The depth is
coal's (hpp-fcl, installed with Pinocchio) exact signed distance. Without coal, a numpy
fallback is exact for spheres and boxes (separating-axis test) and uses the oriented
bounding box of a cylinder, capsule or mesh: such findings say "bounding boxes" and are
at most info. Meshes need trimesh; without it, or when a mesh cannot be read (C004-C006),
its collision is left out.

The severity follows the selected targets (`--target`): a warning when one of them
collides the pair at the start, else info. Each engine's contact filtering was read in its
source and checked against its contacts at rest (`bench/contact_agreement.py`: MuJoCo's
`data.contact` after `mj_forward` at `qpos0`, Drake's `ComputePointPairPenetration()` at
the default context, PyBullet's `getContactPoints` after `performCollisionDetection`):

- MuJoCo (observed, 4.0): the URDF import gives every collision `contype = conaffinity
  = 1` (a URDF cannot change them); bodies are filtered when welded together (`fixed`
  joints; `fusestatic`, on for URDF, fuses them), when both have no degree of freedom, or
  when one is the other's parent, unless either is the world body. The import welds the
  root link to the world (fused into it): the root's body collides with its children,
  joint-adjacent or not (FANUC's `link_1` against `base_link`, 5 to 79 mm in 14 of 33
  arms; Solo12's shoulders, 44 mm). `<mujoco><option><flag filterparent="disable"/>` in
  the URDF collides parents and children too, `contact="disable"` nothing;
  `<compiler fusestatic="false">` keeps the root's body, still welded to the world. MuJoCo
  ignores the SRDF and `<drake:collision_filter_group>`: a pair either one disables is
  still reported for it (the message says so). At t = 0 the contact forces push the bodies
  apart: in a test arm a joint swung by a radian in 0.4 s with no command.
- Drake (observed, 1.51): `MultibodyPlant` filters bodies welded together and the two
  links of each joint, except a joint from `world` or a `floating` one; a link fixed to a
  neighbour's parent still collides with it. A `<drake:collision_filter_group>` filters its
  pairs for Drake only (only the `drake:` spelling: Drake reads no unprefixed
  `<collision_filter_group>`, as in old iiwa files, and then collides the pair).
- Gazebo Classic and Gazebo Sim: links connected by a joint (after fixed-joint lumping)
  never collide; others only with `<self_collide>`. Classic takes a link's own
  (`<selfCollide>` or `<self_collide>` in its `<gazebo reference>`, moved to the lumped
  body by sdformat) else the model's; Gazebo Sim only the model's (gz-physics). The
  model's is `<self_collide>` in the robot-level `<gazebo>`: sdformat 12 drops a
  robot-level `<selfCollide>` (observed). Warning then, for primitives (Gazebo collides the
  triangles of a mesh, not its hull: info).
- ROS (MoveIt): the planning scene reports the start state in collision until the pair
  is disabled; the Setup Assistant disables pairs in collision at the default pose
  ("Default") and adjacent ones. Warning when an SRDF is found (it does not disable the
  pair), info otherwise; info for meshes (MoveIt checks the triangles, not the hull).
- PyBullet (observed, 3.2.7): no self-collision unless `URDF_USE_SELF_COLLISION`; with it
  every pair but a parent and child of one joint collides (`_EXCLUDE_ALL_PARENTS` leaves
  out every ancestor, `_INCLUDE_PARENT` adds parents). Info. Isaac Sim's importer has
  `self_collision` off by default; Pinocchio collides only the pairs a program adds.

Cross-checked on 84 files (the 36 corpus robots, 33 ros-industrial FANUC arms, Drake's
iiwa14 spheres, the fixtures and tests): every pair an engine collides at rest by 1.5 mm or
more is reported for its target, and every pair reported for it is one it collides: MuJoCo
82 of 82 body pairs, meshes included (MuJoCo also collides convex hulls); Drake 71 of 71
(STL and Collada meshes converted to OBJ, which Drake 1.51 requires of collision meshes,
C009); PyBullet 105 of 105 with `URDF_USE_SELF_COLLISION` (its depths exceed the others' by
up to 2 mm: it pads each mesh hull by a 1 mm margin; pairs of links welded together, which
it collides too, are left out: no motion follows). Depths agree to 0.1 mm for primitives.

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
If the overlap is by design (a cover, a finger inside a palm, a base hull around the
first joint), disable the pair: `<disable_collisions link1="a" link2="b"
reason="Default"/>` in the SRDF for MoveIt, `<contact><exclude body1="a" body2="b"/>
</contact>` in the MJCF for MuJoCo (the root's body is `world`), a
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
from urdflint.model.document import Document
from urdflint.model.effects import Effect, kept
from urdflint.model.finding import Severity

if TYPE_CHECKING:
    from urdflint.sources.contact_filters import Filters
    from urdflint.sources.self_collision import Overlap

PUSHED = "collides the two bodies: the contact pushes them apart at the first step"
WORLD = (
    "collides them: its URDF import welds the root link to the world body, which it never "
    "filters against the bodies below (a free joint on the root, in MJCF, filters the pair)"
)
ROOT_NOTE = "MuJoCo welds the root link to the world, never filtered against its children"
SELF_COLLIDE = PUSHED + " (<self_collide>)"
PYBULLET = "collides them with URDF_USE_SELF_COLLISION (off by default)"
PLANNING = "reports the start state in collision until the SRDF disables the pair"


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
    pairs = Pairs(doc)
    found, method = overlaps(doc, max(min_depth, 1e-9), pairs.wanted)
    if "candidate pairs" in method:
        yield Hit(None, f"self-collision: {method.split('; ', 1)[1]}", severity=Severity.INFO)
    if not found:
        return
    pose = _pose(doc)
    for overlap in found:
        effects = pairs.effects(overlap.first, overlap.second, overlap.mesh)
        severity = max((e.level for e in effects.values()), default=Severity.INFO)
        if overlap.approximate:
            severity = Severity.INFO
        yield Hit(
            overlap.element,
            _message(overlap, pose, effects, pairs),
            fix=_fix(overlap, pairs.filters),
            severity=severity,
            effects={t: e for t, e in effects.items() if e.level is Severity.WARNING} or None,
        )


class Pairs:
    """The link pairs C013 measures, and what each selected target does with one."""

    def __init__(self, doc: Document) -> None:
        from urdflint.sources.contact_filters import Filters

        self.doc = doc
        self.filters = Filters(doc)
        self.disabled = srdf_pairs(doc)

    def wanted(self, a: str, b: str) -> bool:
        """Links of two rigid bodies: any pair, but one joined by a joint or disabled by the
        SRDF only when a selected target collides it all the same."""
        relation = self.filters.relation(a, b)
        if relation.same_body:
            return False
        if relation.joint is None and frozenset((a, b)) not in self.disabled:
            return True
        return bool(self.effects(a, b, False))

    def effects(self, a: str, b: str, mesh: bool) -> dict[str, Effect]:
        """What each selected target does with the pair: a warning when it collides the two
        links as it loads the model, info when only an option makes it collide them."""
        found: dict[str, Effect] = {}
        warn, info = Severity.WARNING, Severity.INFO
        filters = self.filters
        relation = filters.relation(a, b)
        disabled = frozenset((a, b)) in self.disabled
        for target in T.ordered(self.doc.targets):
            if target == "mujoco" and filters.mujoco(relation):
                found[target] = kept(WORLD if relation.roots else PUSHED, warn)
            elif target == "drake" and filters.drake(a, b, relation):
                found[target] = kept(PUSHED, warn)
            elif target in T.GAZEBO and filters.gazebo(target, a, b, relation):
                found[target] = kept(SELF_COLLIDE, info if mesh else warn)
            elif target == "ros" and not (relation.body_adjacent or disabled):
                found[target] = kept(PLANNING, warn if self.disabled and not mesh else info)
            elif target == "pybullet" and filters.pybullet(relation):
                found[target] = kept(PYBULLET, info)
        return found

    def notes(self, a: str, b: str, effects: dict[str, Effect]) -> list[str]:
        """Why a pair that looks filtered is collided all the same."""
        found = []
        mujoco = effects.get("mujoco")
        if (
            mujoco is not None
            and mujoco.detail == WORLD
            and self.filters.relation(a, b).body_adjacent
        ):
            found.append(ROOT_NOTE)
        if frozenset((a, b)) in self.disabled and any(t != "ros" for t in effects):
            found.append("the SRDF disables the pair for MoveIt only")
        return found


def _pose(doc: Document) -> str:
    from urdflint.sources.self_collision import joint_values

    values = {k: v for k, v in joint_values(doc).items() if v != 0.0}
    if not values:
        return "at the zero pose"
    shown = ", ".join(f"{k}={v:.6g}" for k, v in sorted(values.items()))
    return f"at the configuration {shown}"


def _message(overlap: Overlap, pose: str, effects: dict[str, Effect], pairs: Pairs) -> str:
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
    why = pairs.notes(overlap.first, overlap.second, effects)
    return text + (f" ({'; '.join(why)})" if why else "")


def _fix(overlap: Overlap, filters: Filters) -> str:
    pair = f'link1="{overlap.first}" link2="{overlap.second}"'
    first, second = (filters.mujoco_body(link) for link in (overlap.first, overlap.second))
    return (
        f"If the overlap is by design, disable the pair in the SRDF: <disable_collisions {pair} "
        f'reason="Default"/> (MuJoCo: <exclude body1="{first}" body2="{second}"/>); otherwise '
        "move or shrink the collision geometry."
    )


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
