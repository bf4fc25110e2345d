"""Pinocchio at many configurations: the centre of mass and the link poses
(:class:`Kinematics`), the configuration where the centre of mass comes nearest to leaving
the support polygon (:func:`worst`) and how far the end links reach (:func:`reach`).

Sampling is deterministic: ``samples`` configurations drawn uniformly within the joint
limits by ``numpy.random.default_rng(SEED)`` (a continuous joint over -pi..pi), then two
passes of coordinate search from the best one (each sampled joint tried at
:data:`GRID` evenly spaced values of its range, the others held). Mimic joints follow
their leader. Pinocchio and numpy are imported inside the functions.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

SEED = 0
GRID = 9  # values per joint in each coordinate-search pass
PASSES = 2
MAX_NV = 300  # larger models are not sampled (Pinocchio's Data holds nv x nv matrices)

Range = tuple[str, float, float]  # joint, lower, upper


class Kinematics:
    """Pinocchio's fixed-base model of one document, with one ``Data``: the whole robot's
    centre of mass (the universe joint's inertia included, see ``physics``) and the link
    frames in the root link's frame, at a configuration given as joint values."""

    def __init__(self, physics: Any) -> None:
        import pinocchio as pin

        self.pin = pin
        self.model = model = physics.model
        self.data = model.createData()
        self.mimics: dict[str, tuple[str, float, float]] = physics.mimics
        universe = model.inertias[0]
        self.fixed_mass = float(universe.mass)
        self.fixed_moment = [float(c) * self.fixed_mass for c in universe.lever]
        self.moving_mass = float(physics.naive_mass)  # joints 1..n
        self.frames = {
            f.name: i for i, f in enumerate(model.frames) if f.type == pin.FrameType.BODY
        }
        self.neutral = pin.neutral(model)
        self.slots: dict[str, tuple[int, bool]] = {}  # joint -> (index in q, continuous)
        for name in list(model.names)[1:]:
            joint = model.joints[model.getJointId(name)]
            if joint.nq == 1 or (joint.nq == 2 and joint.nv == 1):
                self.slots[name] = (joint.idx_q, joint.nq == 2)

    def q(self, values: dict[str, float]) -> Any:
        """The configuration vector: neutral, ``values`` set, mimic joints following."""
        q = self.neutral.copy()
        full = dict(values)
        for name, (leader, multiplier, offset) in self.mimics.items():
            full[name] = multiplier * values.get(leader, 0.0) + offset
        slots = self.slots
        for name, value in full.items():
            slot = slots.get(name)
            if slot is None:
                continue
            if slot[1]:  # continuous: (cos, sin)
                q[slot[0]], q[slot[0] + 1] = math.cos(value), math.sin(value)
            else:
                q[slot[0]] = value
        return q

    def com(self, q: Any) -> tuple[float, float, float]:
        """The whole robot's centre of mass at ``q`` (also places the joints for :meth:`poses`)."""
        pin, moment = self.pin, list(self.fixed_moment)
        if self.moving_mass > 0:
            moving = pin.centerOfMass(self.model, self.data, q)
            moment = [moment[k] + self.moving_mass * float(moving[k]) for k in range(3)]
        else:
            pin.forwardKinematics(self.model, self.data, q)
        total = self.moving_mass + self.fixed_mass
        return (moment[0] / total, moment[1] / total, moment[2] / total)

    def poses(self, links: list[str] | None = None) -> dict[str, Any]:
        """4x4 poses of ``links`` (default: every link) at the last :meth:`com` configuration."""
        self.pin.updateFramePlacements(self.model, self.data)
        names = self.frames if links is None else [n for n in links if n in self.frames]
        return {n: self.data.oMf[self.frames[n]].homogeneous for n in names}


def ranges(kin: Kinematics, skip: set[str]) -> list[Range]:
    """The one-axis joints to sample (not mimics, not in ``skip``) and their ranges."""
    model, found = kin.model, []
    for name in list(model.names)[1:]:
        if name in kin.mimics or name in skip:
            continue
        joint = model.joints[model.getJointId(name)]
        if joint.nq == 2 and joint.nv == 1:
            found.append((name, -math.pi, math.pi))
        elif joint.nq == 1:
            lo = float(model.lowerPositionLimit[joint.idx_q])
            hi = float(model.upperPositionLimit[joint.idx_q])
            if math.isfinite(lo) and math.isfinite(hi) and lo < hi:
                found.append((name, lo, hi))
    return found


def draws(joints: list[Range], samples: int) -> list[dict[str, float]]:
    """``samples`` configurations drawn uniformly within the ranges (seed :data:`SEED`)."""
    import numpy as np

    if not joints or samples <= 0:
        return []
    unit = np.random.default_rng(SEED).random((samples, len(joints)))
    lo = np.array([j[1] for j in joints])
    hi = np.array([j[2] for j in joints])
    values = lo + unit * (hi - lo)
    names = [j[0] for j in joints]
    return [dict(zip(names, (float(v) for v in row), strict=True)) for row in values]


Score = Callable[[dict[str, float]], float]


@dataclass
class Search:
    """The lowest score found, at which configuration, and how many were evaluated."""

    score: float
    values: dict[str, float]
    evaluated: int


def search(joints: list[Range], samples: int, score: Score) -> Search | None:
    """The configuration with the lowest ``score``: the samples, then coordinate search."""
    drawn = draws(joints, samples)
    if not drawn:
        return None
    best = Search(math.inf, {}, 0)
    for values in drawn:
        value = score(values)
        best.evaluated += 1
        if value < best.score:
            best.score, best.values = value, values
    for _ in range(PASSES):
        for name, lo, hi in joints:
            for k in range(GRID):
                trial = {**best.values, name: lo + (hi - lo) * k / (GRID - 1)}
                value = score(trial)
                best.evaluated += 1
                if value < best.score:
                    best.score, best.values = value, trial
    return best


@dataclass
class Reach:
    """How far the end links (their origins and collision geometry) get from the root link's
    origin over the configurations evaluated: the farthest (``distance`` m, ``link``, at
    ``values``) and the axis-aligned box of every point seen (``lower``, ``upper``, root
    frame)."""

    samples: int
    links: list[str]
    distance: float
    link: str
    values: dict[str, float]
    lower: tuple[float, float, float]
    upper: tuple[float, float, float]


def reach(kin: Kinematics, joints: list[Range], ends: dict[str, Any], samples: int) -> Reach | None:
    """The reach of the ``ends`` (link -> points in its frame: its origin and its collision
    geometry's) over the zero pose, ``samples`` configurations and the coordinate search that
    maximises the distance."""
    import numpy as np

    names = [n for n in ends if n in kin.frames]
    if not names:
        return None
    seen: list[Any] = []
    farthest: dict[str, Any] = {"distance": -1.0}
    last: dict[str, Any] = {}
    points = np.vstack([ends[n] for n in names])  # every end point, link by link
    starts = np.cumsum([0] + [len(ends[n]) for n in names[:-1]])
    index = np.repeat(np.arange(len(names)), [len(ends[n]) for n in names])

    def score(values: dict[str, float]) -> float:
        kin.com(kin.q(values))
        poses = kin.poses(names)
        stacked = np.stack([poses[n] for n in names])[index]
        placed = np.einsum("ijk,ik->ij", stacked[:, :3, :3], points) + stacked[:, :3, 3]
        seen.append(np.vstack([placed.min(axis=0), placed.max(axis=0)]))
        per_link = np.maximum.reduceat(np.einsum("ij,ij->i", placed, placed), starts)
        k = int(np.argmax(per_link))
        best = float(np.sqrt(per_link[k]))
        last.update(distance=best, link=names[k], values=dict(values))
        if best > farthest["distance"]:
            farthest.update(last)
        return -best

    score({})
    found = search(joints, samples, score)
    if found is not None:  # the joints that do not matter back at 0, the distance kept
        values = simplify(joints, farthest["values"], score, -farthest["distance"] + 0.001)
        score(values)
        farthest = dict(last)
    everything = np.vstack(seen)
    lower = tuple(float(v) for v in everything.min(axis=0))
    upper = tuple(float(v) for v in everything.max(axis=0))
    evaluated = 1 + (found.evaluated if found else 0)
    return Reach(evaluated, names, farthest["distance"], farthest["link"], farthest["values"],
                 lower, upper)  # type: ignore[arg-type]  # fmt: skip


def simplify(joints: list[Range], values: dict[str, float], score: Score, limit: float) -> dict:
    """``values`` with every joint that does not matter back at 0 (when 0 is within its
    range): the score must stay at or under ``limit``."""
    found = {k: v for k, v in values.items() if v != 0.0}
    for name, lo, hi in joints:
        if name in found and lo <= 0.0 <= hi:
            trial = {k: v for k, v in found.items() if k != name}
            if score(trial) <= limit:
                found = trial
    return found


class Floor:
    """Whether the collision geometry of ``links`` reaches under ``level`` at the last
    configuration :class:`Kinematics` computed (such a configuration pushes on the floor:
    it is not a stance). ``probes``: per link, points in its frame and the radius below
    each (see ``stability_contacts.probes``)."""

    def __init__(self, kin: Kinematics, probes: dict[str, tuple[Any, Any]], level: float) -> None:
        import numpy as np

        self.kin, self.level, self.links = kin, level, list(probes)
        self.points = np.vstack([probes[n][0] for n in self.links]) if probes else None
        self.radii = np.concatenate([probes[n][1] for n in self.links]) if probes else None
        self.index = np.concatenate(
            [np.full(len(probes[n][0]), k) for k, n in enumerate(self.links)]
        ) if probes else None  # fmt: skip

    def hit(self) -> bool:
        import numpy as np

        if self.points is None:
            return False
        poses = self.kin.poses(self.links)
        rows = np.stack([poses[n][2] for n in self.links])[self.index]  # z row of each pose
        z = np.einsum("ij,ij->i", rows[:, :3], self.points) + rows[:, 3] - self.radii
        return bool(z.min() < self.level)
