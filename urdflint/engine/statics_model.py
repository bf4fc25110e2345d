"""The statics problem of one document: its coordinates, their ranges, and the bound.

:class:`Problem` holds a copy of the fixed-base Pinocchio model (``doc.physics.model``)
with the configured gravity and payload, and maps the *independent coordinates* (one per
revolute, continuous or prismatic joint that is not a mimic follower) to Pinocchio's
configuration: a mimic follower takes ``multiplier * leader + offset`` (chains of mimics
composed), a continuous joint its ``(cos, sin)`` pair, every other joint (floating,
planar) stays neutral. Ranges are the URDF's ``lower``/``upper`` (a missing bound is 0,
as urdfdom reads it; an inverted pair is sorted), ``[-π, π]`` for continuous joints.

:func:`bound` is the analytic upper bound of a joint's gravity torque or force (see its
docstring). numpy and Pinocchio are imported by the caller and handed in.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from urdflint.engine.statics_roles import tool_link
from urdflint.model import joints as J

if TYPE_CHECKING:
    from urdflint.engine.statics_settings import StaticsSettings
    from urdflint.model.document import Document


@dataclass(frozen=True)
class Coordinate:
    """One independent coordinate: a one-axis joint that is not a mimic follower."""

    name: str
    jid: int  # Pinocchio joint id
    kind: str  # revolute, continuous, prismatic
    lo: float
    hi: float


class Problem:
    """The model (gravity and payload applied), its coordinates and the maps to ``q``."""

    def __init__(self, doc: Document, pin: Any, np: Any, settings: StaticsSettings) -> None:
        physics = doc.physics
        self.pin, self.np, self.doc = pin, np, doc
        self.model = pin.Model(physics.model)
        self.model.gravity = pin.Motion(np.array(settings.gravity, dtype=float), np.zeros(3))
        self.tool = settings.payload_link or tool_link(doc)
        self.payload = settings.payload
        if self.payload and self.tool is not None:
            add_point_mass(pin, np, self.model, self.tool, self.payload)
        self.data = self.model.createData()
        self.mimics: dict[str, tuple[str, float, float]] = physics.mimics
        self.coords = _coordinates(doc, self.model, physics.mimics)
        self.index = {c.name: i for i, c in enumerate(self.coords)}
        self.axes: dict[int, tuple[Any, bool]] = {}
        self.lo = np.array([c.lo for c in self.coords], dtype=float)
        self.hi = np.array([c.hi for c in self.coords], dtype=float)
        self.width = np.maximum(self.hi - self.lo, 0.0)
        self._maps()

    # -- q from the coordinates ------------------------------------------------------------

    def _maps(self) -> None:
        """Index arrays: each 1-DOF joint's q (and v) entry from one coordinate, linearly."""
        np, model = self.np, self.model
        rows: list[tuple[int, int, int, float, float, bool]] = []  # qi, vi, ti, mult, off, cont
        for jid in range(1, model.njoints):
            joint, name = model.joints[jid], model.names[jid]
            if joint.nv != 1:
                continue
            ti, mult, off = self.source(name)
            rows.append((joint.idx_q, joint.idx_v, ti, mult, off, joint.nq == 2))
        self.neutral = self.pin.neutral(model)
        self.B = np.zeros((model.nv, len(self.coords)))  # dv/dθ
        for _, vi, ti, mult, _, _ in rows:
            if ti >= 0:
                self.B[vi, ti] = mult
        table = [r for r in rows if r[2] >= 0]
        fixed = [r for r in rows if r[2] < 0]
        self._lin = self._columns([r for r in table if not r[5]])
        self._cont = self._columns([r for r in table if r[5]])
        for qi, _, _, _, off, cont in fixed:  # a follower of no coordinate: at its offset
            if cont:
                self.neutral[qi], self.neutral[qi + 1] = math.cos(off), math.sin(off)
            else:
                self.neutral[qi] = off
        self.continuous = np.array([c.kind == "continuous" for c in self.coords], dtype=bool)

    def _columns(self, rows: list[tuple[int, int, int, float, float, bool]]) -> tuple:
        """(q indices, coordinate indices, multipliers, offsets) as arrays."""
        np = self.np
        return (
            np.array([r[0] for r in rows], dtype=int),
            np.array([r[2] for r in rows], dtype=int),
            np.array([r[3] for r in rows], dtype=float),
            np.array([r[4] for r in rows], dtype=float),
        )

    def source(self, name: str) -> tuple[int, float, float]:
        """(coordinate index or -1, multiplier, offset) of joint ``name``'s position."""
        mimics = self.mimics
        mult, off, seen = 1.0, 0.0, set()
        while name in mimics and name not in seen and name not in self.index:
            seen.add(name)
            leader, m, o = mimics[name]
            mult, off = mult * m, mult * o + off
            name = leader
        if name in self.index:
            return self.index[name], mult, off
        return -1, 0.0, off

    def q_matrix(self, thetas: Any) -> Any:
        """Pinocchio configurations (rows) for coordinate vectors (rows)."""
        np = self.np
        q = np.tile(self.neutral, (thetas.shape[0], 1))
        qi, ti, mult, off = self._lin
        q[:, qi] = thetas[:, ti] * mult + off
        qi, ti, mult, off = self._cont
        angle = thetas[:, ti] * mult + off
        q[:, qi] = np.cos(angle)
        q[:, qi + 1] = np.sin(angle)
        return q

    def q(self, theta: Any) -> Any:
        """Pinocchio's configuration for one coordinate vector."""
        np = self.np
        q = self.neutral.copy()
        qi, ti, mult, off = self._lin
        q[qi] = theta[ti] * mult + off
        qi, ti, mult, off = self._cont
        angle = theta[ti] * mult + off
        q[qi] = np.cos(angle)
        q[qi + 1] = np.sin(angle)
        return q

    def gravity(self, theta: Any) -> Any:
        """The generalized gravity (every joint's holding torque or force) at ``theta``."""
        return self.pin.computeGeneralizedGravity(self.model, self.data, self.q(theta))

    def gravity_gradient(self, theta: Any) -> Any:
        """d(gravity)/dθ: an ``nv × coordinates`` matrix."""
        q = self.q(theta)
        return self.pin.computeGeneralizedGravityDerivatives(self.model, self.data, q) @ self.B

    def clip(self, theta: Any) -> Any:
        """``theta`` within the limits (continuous joints wrapped to [-π, π])."""
        np = self.np
        wrapped = np.remainder(theta + math.pi, 2 * math.pi) - math.pi
        return np.where(self.continuous, wrapped, np.clip(theta, self.lo, self.hi))

    def related(self, jid: int) -> list[int]:
        """The coordinates joint ``jid``'s load depends on: its ancestors', its own and its
        descendants' (a follower's leader for a follower among them), in model order."""
        model = self.model
        joints = set(model.supports[jid]) | set(model.subtrees[jid])
        found = {i for i, c in enumerate(self.coords) if c.jid in joints}
        for name in (model.names[j] for j in joints if j):
            ti, _, _ = self.source(name)
            if ti >= 0:
                found.add(ti)
        return sorted(found)


def _coordinates(doc: Document, model: Any, mimics: dict[str, Any]) -> list[Coordinate]:
    found = []
    for jid in range(1, model.njoints):
        name = model.names[jid]
        joint = doc.joint_map.get(name)
        if model.joints[jid].nv != 1 or name in mimics or joint is None:
            continue
        kind = joint.type if joint.type in J.ACTUATED else "revolute"
        if kind == "continuous" or model.joints[jid].nq == 2:
            found.append(Coordinate(name, jid, "continuous", -math.pi, math.pi))
            continue
        lim = J.limit(joint)
        lower = (lim.lower if lim is not None else None) or 0.0
        upper = (lim.upper if lim is not None else None) or 0.0
        lo, hi = sorted((lower, upper))
        found.append(Coordinate(name, jid, kind, lo, hi))
    return found


# -- the tool link and the payload ------------------------------------------------------------


def add_point_mass(pin: Any, np: Any, model: Any, link: str, mass: float) -> bool:
    """Add ``mass`` kg at the origin of ``link`` to the body that carries it (in place)."""
    if not model.existFrame(link, pin.FrameType.BODY):
        return False
    frame = model.frames[model.getFrameId(link, pin.FrameType.BODY)]
    point = pin.Inertia(mass, np.array(frame.placement.translation), np.zeros((3, 3)))
    model.inertias[frame.parentJoint] = model.inertias[frame.parentJoint] + point
    return True


# -- the analytic bound -------------------------------------------------------------------------


def bound(problem: Problem, jid: int) -> tuple[float, float]:
    """Upper bounds of ``|τ|`` of joint ``jid``: over every configuration, and over every
    orientation of its axis (as if it were level: the joint's load at 1 g of acceleration).

    A revolute joint holds ``a · Σ_b (c_b - p) × m_b g`` for the bodies ``b`` it carries:
    at most ``|g⊥| Σ_b m_b d_b``, with ``d_b`` the largest distance of body ``b``'s centre
    of mass from the axis. ``d_b`` is at most the distance of the first joint below from
    the axis (constant: it turns about it) plus the length of every later joint offset,
    the reach of every prismatic joint on the way and the body's own COM offset
    (triangle inequality). A prismatic joint holds ``a · g Σ_b m_b``: at most
    ``|g·a| Σ m_b``. ``|g⊥|`` (``|g·a|``) is the axis' component of gravity when no
    revolute joint above can turn the axis, else ``|g|``; the second bound uses ``|g|``.
    """
    np, model = problem.np, problem.model
    g = np.array(model.gravity.linear)
    axis, linear = _axis(problem, jid)
    fixed_axis = all(_axis(problem, k)[1] for k in model.supports[jid][1:-1])
    if linear:
        along = abs(float(g @ axis))
        total = sum(model.inertias[k].mass for k in model.subtrees[jid])
    else:
        along = float(np.linalg.norm(g - (g @ axis) * axis))
        total = _moment(problem, jid)
    full = float(np.linalg.norm(g))
    return (along if fixed_axis else full) * total, full * total


def _moment(problem: Problem, jid: int) -> float:
    """``Σ_b m_b d_b`` over the bodies revolute joint ``jid`` carries (see :func:`bound`)."""
    np, model = problem.np, problem.model
    local = _local_axis(problem, jid)
    total = 0.0
    for k in model.subtrees[jid]:
        inertia = model.inertias[k]
        if inertia.mass == 0.0:
            continue
        path = _path(model, jid, k)  # joints below jid down to k
        if not path:
            total += inertia.mass * _perp(np, inertia.lever, local)
            continue
        reach = _perp(np, model.jointPlacements[path[0]].translation, local)
        reach += sum(float(np.linalg.norm(model.jointPlacements[p].translation)) for p in path[1:])
        reach += sum(_extent(problem, p) for p in path)
        total += inertia.mass * (reach + float(np.linalg.norm(inertia.lever)))
    return total


def _path(model: Any, top: int, k: int) -> list[int]:
    path = []
    while k != top and k > 0:
        path.append(k)
        k = model.parents[k]
    return path[::-1]


def _perp(np: Any, v: Any, axis: Any) -> float:
    v = np.asarray(v, dtype=float)
    return float(np.linalg.norm(v - (v @ axis) * axis))


def _extent(problem: Problem, jid: int) -> float:
    """How far prismatic joint ``jid`` moves its child from its origin (0 for the others)."""
    if not _axis(problem, jid)[1]:
        return 0.0
    name = problem.model.names[jid]
    if name in problem.index:
        c = problem.coords[problem.index[name]]
        return max(abs(c.lo), abs(c.hi))
    ti, mult, off = problem.source(name)
    if ti < 0:
        return abs(off)
    return abs(mult) * max(abs(problem.lo[ti]), abs(problem.hi[ti])) + abs(off)


def _local_axis(problem: Problem, jid: int) -> Any:
    """The joint's axis (unit) in its own frame, from its motion subspace at neutral."""
    np, joint = problem.np, problem.model.joints[jid]
    data = joint.createData()
    joint.calc(data, problem.pin.neutral(problem.model))
    s = np.array(data.S).reshape(6, -1)[:, 0]
    part = s[:3] if np.linalg.norm(s[3:]) < 1e-12 else s[3:]
    n = np.linalg.norm(part)
    return part / n if n > 0 else part


def _axis(problem: Problem, jid: int) -> tuple[Any, bool]:
    """The joint's axis in the root frame at neutral, and whether it is prismatic."""
    if jid not in problem.axes:
        problem.axes[jid] = _world_axis(problem, jid)
    return problem.axes[jid]  # type: ignore[no-any-return]


def _world_axis(problem: Problem, jid: int) -> tuple[Any, bool]:
    np, pin, model = problem.np, problem.pin, problem.model
    if model.joints[jid].nv != 1:
        return np.zeros(3), False
    joint = model.joints[jid]
    data = joint.createData()
    joint.calc(data, pin.neutral(model))
    s = np.array(data.S).reshape(6, -1)[:, 0]
    linear = bool(np.linalg.norm(s[3:]) < 1e-12)
    placement = pin.SE3.Identity()
    k = jid
    while k > 0:
        placement = model.jointPlacements[k] * placement
        k = model.parents[k]
    local = s[:3] if linear else s[3:]
    n = np.linalg.norm(local)
    return (placement.rotation @ local) / (n if n > 0 else 1.0), linear
