"""Will the robot tip over? The support polygon of a mobile base, the centre of mass over
it, and how far the arms reach (D003, ``urdflint info --statics``).

**The ground.** Gravity is -z of the root link's frame and the model stands at the zero
pose (every joint at 0: what a simulator spawns), or at ``--q``/``expect.q``. The ground is
the plane under the lowest point of the contact candidates' collision geometry.

**Contact candidates** (the heuristic; ``[tool.urdflint.stability] contact-links``
replaces it):

- ``wheel``: links whose name has the word ``wheel``/``wheels``, ``caster``/``castor`` (words
  split at ``_``, ``-``, digits and camelCase), and links on a ``continuous`` joint (an
  arm's roll joint qualifies too, but it is far above the ground and never touches);
- ``foot``: the words ``foot``/``feet``, ``toe`` or ``sole`` (``base_footprint`` is none);
- ``leg end``: leaf links at the end of at least two moving joints whose collision reaches
  lower than the root's rigid body's own collision (or than the centre of mass when it has
  none): humanoid ankles, legs without foot links. When these are the only candidates and
  another part of the robot is lower (baxter's arms hang below its base), the robot is not
  mobile.

A candidate's geometry is its rigid body's: up through fixed joints (not into the root's
body: a ``*_sole`` frame takes its ankle link's box), then every link welded below. **Not
mobile**, nothing to check: a root link named ``world`` welded to the robot (the Gazebo
tutorials' layout), or no candidate at all (an arm, a hand).

**Contact points.** For each collision shape of a candidate, its lowest points in the root
frame: a box's corners, a cylinder's rim points (32 per rim, the lowest included), a
sphere's or capsule's lowest point, a mesh's convex-hull vertices (read through the run's
mesh cache), each within 0.1 mm of that shape's lowest point (the lowest line of a lying
wheel, the four corners of a flat sole). A shape touches when its lowest point is within
``contact-tolerance`` (default 1 cm: a rigid base rocks onto a contact a few millimetres
higher instead of falling; minitaur's two motor housings differ by 5.7 mm) of the ground.
The **support polygon** is the convex hull of the touching points projected on the ground.
Nothing is judged when a candidate's mesh cannot be read (the polygon would miss it), or
when the collision of another link reaches more than the tolerance under the ground (an
arm hanging below the wheels at the zero pose: the robot does not stand on them).

**Fewer than three non-collinear contacts** (support narrower than 1 mm): a line (two
wheels on one axle: a Segway, a differential drive whose casters do not reach the ground)
or a point. Such a base has no static equilibrium to check: a self-balancing robot is built
so, while a caster that misses the ground is a defect. D003 says so in an info, naming the
candidates that do not touch and how high they are, never an error.

**Margin and tipping angle.** The margin is the signed distance from the centre of mass's
projection to the polygon's edge (positive inside); the tipping angle is
``atan(margin / h)``, ``h`` the height of the centre of mass above the ground: the smallest
tilt, about the nearest edge, that brings the centre of mass over it.

**Configurations** (:func:`sample`). The joints that move no touching contact (the arms,
the torso, the head; wheels and legs are held) are sampled within their limits
(:mod:`urdflint.engine.stability_sampling`: ``samples`` draws with a fixed seed, then a
coordinate search); a configuration whose collision geometry reaches more than the
tolerance under the ground pushes on the floor and is left out; the joints that change the
worst margin by less than 1 mm go back to 0. D003 samples only bases on wheels or
configured contacts: a legged robot moves its legs to stay up.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from urdflint.engine import stability_contacts as contacts
from urdflint.engine.stability_contacts import Candidates, Support
from urdflint.engine.stability_polygon import Point2, direction, margin

if TYPE_CHECKING:
    from urdflint.engine.stability_sampling import Kinematics, Reach
    from urdflint.model.document import Document

Vec = tuple[float, float, float]
OUTSIDE = 1e-6  # m: a centre of mass farther than this outside the polygon falls
SIMPLER = 0.001  # m: a joint goes back to 0 when the worst margin grows by less than this


@dataclass
class Stance:
    """The centre of mass over the support at one configuration (``values``: the joints set)."""

    values: dict[str, float]
    com: Vec
    margin: float  # m, positive inside
    nearest: Point2  # the nearest point of the polygon's edge
    height: float  # the centre of mass above the ground, m

    @property
    def tilt(self) -> float | None:
        """The tipping angle in degrees (negative: it falls), ``None`` when ``height <= 0``."""
        if not self.height > 0:
            return None
        return math.degrees(math.atan(self.margin / self.height))

    @property
    def direction(self) -> str:
        """The side of the polygon the centre of mass is over (outside) or nearest to
        (inside), in words: where the robot tips."""
        out = (self.com[0] - self.nearest[0], self.com[1] - self.nearest[1])
        return direction(out if self.margin < 0 else (-out[0], -out[1]))


@dataclass
class Stability:
    """The analysis of one document. ``mobile`` false: fixed to the world or nothing that
    touches the ground (``reason`` says which). ``reason`` with ``mobile`` true: why the
    stance is not judged. ``zero``: at the zero pose; ``given``: at ``--q`` when given;
    ``worst``: the sampled configuration nearest to tipping (``evaluated`` configurations,
    ``joints`` sampled; :func:`sample` fills it in)."""

    mobile: bool
    reason: str | None = None
    candidates: Candidates | None = None
    support: Support | None = None
    zero: Stance | None = None
    given: Stance | None = None
    given_support: Support | None = None
    worst: Stance | None = None
    evaluated: int = 0
    joints: list[str] = field(default_factory=list)
    seconds: float = 0.0
    sampled: bool = False  # ``worst`` looked for (:func:`sample`)


def analyse(doc: Document) -> Stability:
    """The stability of ``doc`` (computed once per document)."""
    found = doc.memo.get("stability")
    if found is None:
        start = time.perf_counter()
        found = doc.memo["stability"] = _analyse(doc)
        found.seconds = time.perf_counter() - start
    return found  # type: ignore[no-any-return]


def kinematics(doc: Document) -> Kinematics | None:
    """Pinocchio's model with one ``Data`` (once per document), ``None`` when not built."""
    from urdflint.engine.stability_sampling import MAX_NV, Kinematics

    physics = doc.physics
    if not physics.built or physics.com is None or physics.model.nv > MAX_NV:
        return None
    if "stability.kinematics" not in doc.memo:
        doc.memo["stability.kinematics"] = Kinematics(physics)
    return doc.memo["stability.kinematics"]  # type: ignore[no-any-return]


def _analyse(doc: Document) -> Stability:
    physics = doc.physics
    if not physics.built or physics.com is None:
        return Stability(False, physics.reason or physics.com_problem)
    kin = kinematics(doc)
    if kin is None:
        return Stability(False, f"{physics.model.nv} degrees of freedom: not analysed")
    root = physics.root
    com = kin.com(kin.q({}))
    poses = kin.poses()
    if _welded_to_world(doc, root):
        return Stability(False, f"the root link '{root}' is the world: the robot is fixed to it")
    found = candidates(doc, root, poses, com)
    if not found.links:
        why = "no wheel, caster, foot or leg end reaches the ground: a fixed-base robot"
        return Stability(False, why, found)
    tolerance = doc.settings.stability.contact_tolerance
    base = contacts.body(doc, root, found.links)
    support = contacts.support(doc, found.links, poses, tolerance, base)
    result = Stability(True, None, found, support)
    if not _judged(result):
        return result
    result.zero = stance(kin, result.support, {})  # type: ignore[arg-type]
    if physics.q:
        values = {n: v for n, v in physics.q.items() if n not in physics.mimics}
        kin.com(kin.q(values))
        moved = contacts.support(doc, found.links, kin.poses(), tolerance, base)
        result.given_support = moved
        if moved.kind == "polygon" and not moved.below and not moved.unreadable:
            result.given = stance(kin, moved, values)
    return result


def sample(doc: Document) -> Stability:
    """:func:`analyse` with ``worst`` filled in, when the zero pose stands (sampled once per
    document: D003 asks only for wheeled bases, the summary always)."""
    found = analyse(doc)
    if found.sampled or found.zero is None or found.zero.margin < -OUTSIDE:
        return found
    found.sampled = True
    kin = kinematics(doc)
    if kin is not None:
        start = time.perf_counter()
        _sample(doc, kin, found)
        found.seconds += time.perf_counter() - start
    return found


def _welded_to_world(doc: Document, root: str) -> bool:
    joints = doc.graph.child_joints.get(root, [])
    return root.lower() == "world" and all(j.type == "fixed" for j in joints)


def _judged(result: Stability) -> bool:
    """Whether the support is a polygon the robot stands on (``reason`` set otherwise; a
    robot whose only candidates are leg ends that are not its lowest part is not mobile)."""
    support, found = result.support, result.candidates
    assert support is not None and found is not None
    if support.unreadable:
        listed = ", ".join(f"'{n}'" for n in support.unreadable[:4])
        result.reason = f"the collision meshes of contact links {listed} cannot be read"
    elif support.kind == "none":
        result.reason = "no contact candidate has collision geometry"
    elif support.below:
        name, depth = max(support.below.items(), key=lambda item: item[1])
        if set(found.links.values()) == {"leg end"}:
            result.mobile, result.support = False, None
            result.reason = (
                f"no wheel, caster or foot, and link '{name}', not a leg end, is the lowest: "
                "a fixed-base robot"
            )
            return False
        result.reason = (
            f"the collision of link '{name}' reaches {depth * 1000:.0f} mm under the lowest "
            "point of the contact links: the robot does not stand on them at this pose"
        )
    elif support.kind != "polygon":
        result.reason = f"the support is a {support.kind}: no polygon"
    return result.reason is None


def candidates(doc: Document, root: str, poses: dict[str, Any], com: Vec) -> Candidates:
    """The configured contact links, else the heuristic's (see the module docstring)."""
    configured = doc.settings.stability.contact_links
    if configured:
        known = {n: "configured" for n in configured if n in doc.link_map}
        unknown = [n for n in configured if n not in doc.link_map]
        return Candidates(known, True, unknown)
    found = contacts.named_or_rolling(doc, root)
    base = [
        z
        for name in contacts.body(doc, root, found)
        if name in poses and (z := contacts.lowest_bound(doc, name, poses[name])) is not None
    ]
    level = min(base) if base else com[2]
    for name in contacts.leg_ends(doc, root):
        if name in found or name not in poses:
            continue
        z = contacts.lowest_bound(doc, name, poses[name])
        if z is not None and z < level:
            found[name] = "leg end"
    return Candidates(found)


def stance(kin: Kinematics, support: Support, values: dict[str, float]) -> Stance:
    """The centre of mass over ``support`` at ``values`` (the joints not given at 0)."""
    com = kin.com(kin.q(values))
    distance, nearest = margin(support.polygon, (com[0], com[1]))
    return Stance(dict(values), com, distance, nearest, com[2] - support.ground)


def moving_joints(doc: Document, links: dict[str, str] | list[str]) -> set[str]:
    """The joints that move one of ``links``: their chains from the root."""
    found: set[str] = set()
    for name in links:
        found.update(j.name for j in contacts.chain(doc, name) if j.name)
    return found


def _sample(doc: Document, kin: Kinematics, result: Stability) -> None:
    """The sampled configuration nearest to tipping: the contacts held (their chains are
    not sampled), configurations that push an arm into the floor left out, the joints that
    do not matter put back at 0."""
    from urdflint.engine.stability_sampling import Floor, ranges, search, simplify

    support = result.support
    assert support is not None
    joints = ranges(kin, moving_joints(doc, support.links))
    result.joints = [j[0] for j in joints]
    moved = {
        name
        for joint in result.joints
        if joint in doc.joint_map and (child := doc.joint_map[joint].child) is not None
        for name in doc.graph.subtree(child)
    }
    probes = {n: p for n in sorted(moved) if (p := contacts.probes(doc, n)) is not None}
    tolerance = doc.settings.stability.contact_tolerance
    floor = Floor(kin, probes, support.ground - tolerance)

    best = [math.inf]  # the floor is looked at only for what could become the worst

    def score(values: dict[str, float]) -> float:
        com = kin.com(kin.q(values))
        found = margin(support.polygon, (com[0], com[1]))[0]
        if found < best[0] + SIMPLER + 1e-9:
            if floor.hit():
                return math.inf
            best[0] = min(best[0], found)
        return found

    found = search(joints, doc.settings.stability.samples, score)
    if found is None or not math.isfinite(found.score):
        return
    result.evaluated = found.evaluated
    values = simplify(joints, found.values, score, found.score + SIMPLER)
    result.worst = stance(kin, support, values)


def reach(doc: Document) -> Reach | None:
    """How far the end links reach from the root link's origin (see ``stability_sampling``):
    the leaf links moved by a sampled joint, their origin and their collision geometry;
    ``None`` without any."""
    from urdflint.engine.stability_sampling import ranges
    from urdflint.engine.stability_sampling import reach as sample_reach

    kin = kinematics(doc)
    if kin is None:
        return None
    found = analyse(doc)
    held = found.support.links if found.mobile and found.support else []
    joints = ranges(kin, moving_joints(doc, held))
    sampled = {j[0] for j in joints}
    ends = [
        name
        for name in doc.graph.subtree(doc.physics.root)
        if not doc.graph.children(name)
        and name not in held
        and any(j.name in sampled for j in contacts.chain(doc, name))
    ]
    import numpy as np

    points = {}
    for name in ends:
        probe = contacts.probes(doc, name)
        points[name] = np.zeros((1, 3)) if probe is None else np.vstack([[0, 0, 0], probe[0]])
    return sample_reach(kin, joints, points, doc.settings.stability.samples)


# -- the summary (urdflint info --statics) --------------------------------------------------


def summary(doc: Document) -> dict[str, Any] | None:
    """The base's stability and the arms' reach as plain data (``urdflint info --statics``,
    :mod:`urdflint.engine.stability_text`); ``None`` when Pinocchio did not build the model."""
    from urdflint.engine.stability_text import summary as data

    if not doc.ok or not doc.physics.built:
        return None
    return data(doc, sample(doc), reach(doc))


def summary_text(data: dict[str, Any]) -> list[str]:
    """The lines of the "base" section of ``urdflint info --statics`` for :func:`summary`."""
    from urdflint.engine.stability_text import text

    return text(data)
