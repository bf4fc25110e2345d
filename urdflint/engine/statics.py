"""Statics: the largest gravity torque (or force) each joint must hold, over its range.

For every revolute, continuous and prismatic joint of the fixed-base Pinocchio model
(``doc.physics``; mimic followers and floating or planar joints are not coordinates of the
search, see :mod:`urdflint.engine.statics_model`), :func:`of` finds the largest ``|τ_j|``
of the generalized gravity ``τ = g(q)`` over the configurations the limits allow, and an
analytic upper bound of it. Computed once per document (kept in ``doc.memo``), for the D
rules, ``urdflint info --statics`` and the language server's hover.

**Why this method.** ``τ_j(q)`` depends on the joint's ancestors (they turn its axis
against gravity) and its descendants (they move its load); the other branches do not
matter, and sampling them costs nothing since one ``computeGeneralizedGravity`` call
gives every joint's torque. It is a sum of products of sines and cosines: smooth, with
several local maxima, usually at a limit or where the load is level with the axis. So:

1. **sample** every coordinate uniformly within its limits (seeded, deterministic):
   :data:`PER_COORDINATE` samples per coordinate, at least :data:`MIN_SAMPLES` and at most
   :data:`MAX_SAMPLES`, plus the neutral configuration. A 7-DOF arm takes 448 samples;
2. **refine** the :data:`STARTS` best samples of each joint by projected gradient ascent
   on ``|τ_j|`` with ``computeGeneralizedGravityDerivatives`` (the chain rule through
   mimic joints), steps scaled to each range, clipped to the limits, halved when they do
   not improve, at most :data:`MAX_STEPS` evaluations per start;
3. **bound** it analytically (:func:`urdflint.engine.statics_model.bound`): what no
   configuration can exceed. When a sample reaches the bound the search is over; when
   the bound is below the effort limit the joint is *proven* to hold, with no search.

The figure found is a configuration's true torque, so it is a lower bound of the
maximum (the search can miss a narrow peak, never invent one); :func:`witness` rounds
the configuration to readable values, keeps only the joints whose value changes the
torque, and evaluates the torque again there, so a message's number is exact at the
configuration it states. The bounds are computed for every joint at once; the samples,
and each joint's refinement, only when its load is first asked (:meth:`Statics.load`):
``check`` asks only for the joints whose bound is above their effort limit.

With a fixed base the root link is the world: a mobile base does not tip (out of scope
here), a leg hangs in the air instead of carrying the robot, which is a lower bound of
what it needs in stance.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from urdflint.engine.statics_settings import StaticsSettings
from urdflint.model import joints as J

if TYPE_CHECKING:
    from urdflint.engine.statics_model import Problem
    from urdflint.model.document import Document

SEED = 26
MIN_SAMPLES, MAX_SAMPLES, PER_COORDINATE = 256, 2048, 64
STARTS = 3  # the best samples refined per joint
MAX_STEPS = 60  # gravity evaluations per refined start
MIN_STEP = 1e-4  # of each range: a smaller step changes the torque by less than 1e-8
SETTLE = 1e-9  # relative: a sample this close to the bound is the maximum
MAX_DOF = 200  # the search is skipped on larger models (the bound is still given)
ROUND = (0, 1, 2, 3, 4, 6)  # decimals tried when the witness configuration is rounded
TINY = 1e-9  # N·m or N: less is rounding noise (a joint whose axis is vertical)
MINOR = 0.01  # relative: a joint that changes the torque less is not shown (set to 0)
LOSS = 0.002  # relative: how much of the torque setting those joints to 0 may give up
KEEP = 1e-5  # relative: how much of the torque rounding one joint's value may give up


@dataclass
class JointLoad:
    """One joint's gravity load: the bound, the effort limit, and once searched
    (:meth:`Statics.load`) the largest load found and where."""

    name: str
    kind: str  # revolute, continuous, prismatic
    bound: float  # no configuration exceeds it, N·m or N
    level: float  # nor any orientation of the axis: the load at 1 g of acceleration
    effort: float | None  # the <limit effort>, None when absent or not a number
    related: tuple[int, ...] = ()  # the coordinates its load depends on
    vi: int = 0  # its index in Pinocchio's velocity vector
    passive: bool = False  # no <transmission> or <ros2_control> command names it
    needed: float | None = None  # the largest |τ| found, exact at ``at`` (None: not yet)
    at: dict[str, float] = field(default_factory=dict)  # the joint values that decide it
    theta: Any = None  # every coordinate of that configuration (the others at 0)

    @property
    def unit(self) -> str:
        return J.units(self.kind)[1]

    @property
    def proven(self) -> bool:
        """The bound is within the effort limit: the joint holds in every configuration."""
        return bool(self.effort) and self.bound <= self.effort * (1 + 1e-12)  # type: ignore[operator]

    @property
    def margin(self) -> float | None:
        """effort / needed (``inf`` for a joint that needs nothing), once searched."""
        if not self.effort or self.needed is None:
            return None
        return self.effort / self.needed if self.needed > 0 else math.inf


@dataclass
class Statics:
    """The gravity loads of one document (``ok`` false: ``reason`` says why not).

    The bounds are computed at once; the samples when a joint's load is first asked
    (:meth:`load`), and each joint's refinement then, for that joint only: a check whose
    effort limits are all above their bounds samples nothing.
    """

    ok: bool
    reason: str | None = None
    missing: bool = False  # Pinocchio is not installed
    settings: StaticsSettings = field(default_factory=StaticsSettings)
    root: str | None = None
    tool: str | None = None  # where the payload sits
    unknown_link: str | None = None  # the configured payload link the model does not have
    joints: dict[str, JointLoad] = field(default_factory=dict)
    problem: Problem | None = None
    samples: Any = None  # (coordinates, torques) of the samples, once taken
    seconds: float = 0.0  # time spent so far

    def sampled(self) -> tuple[Any, Any]:
        """(coordinates, generalized gravity) of every sample, taken on first use."""
        if self.samples is None and self.problem is not None:
            start = time.perf_counter()
            self.samples = sample(self.problem)
            self.seconds += time.perf_counter() - start
        return self.samples  # type: ignore[no-any-return]

    def load(self, name: str) -> JointLoad:
        """Joint ``name``'s load, searched (samples taken on first use, then refined) and
        made readable (:func:`witness`)."""
        found = self.joints[name]
        if found.needed is None and self.problem is not None:
            samples = self.sampled()
            start = time.perf_counter()
            search(self.problem, found, *samples)
            witness(self.problem, found)
            self.seconds += time.perf_counter() - start
        return found


def of(doc: Document) -> Statics:
    """The statics of ``doc`` with its settings, computed once."""
    found = doc.memo.get("statics")
    if found is None:
        found = doc.memo["statics"] = compute(doc, settings_of(doc))
    return found  # type: ignore[no-any-return]


def settings_of(doc: Document) -> StaticsSettings:
    return getattr(doc.settings, "statics", None) or StaticsSettings()


def compute(doc: Document, settings: StaticsSettings) -> Statics:
    """The problem and every joint's bound; the search runs on demand (:meth:`Statics.load`)."""
    start = time.perf_counter()
    physics = doc.physics
    result = Statics(False, settings=settings, root=getattr(physics, "root", None))
    if not physics.built:
        result.reason, result.missing = physics.reason, physics.missing
        return result
    bad = _unphysical_mass(doc)
    if bad is not None:  # gravity would pull upwards, or nowhere: the I rules report it
        result.reason = f"link '{bad}' has a negative or invalid mass"
        return result
    import numpy as np
    import pinocchio as pin

    from urdflint.engine.statics_model import Problem, bound
    from urdflint.engine.statics_roles import actuated

    if settings.payload_link and settings.payload_link not in doc.link_map:
        result.unknown_link = settings.payload_link
    problem = Problem(doc, pin, np, settings)
    result.ok, result.problem, result.tool = True, problem, problem.tool
    driven = actuated(doc)
    for c in problem.coords:
        lim = J.limit(doc.joint_map[c.name])
        result.joints[c.name] = JointLoad(
            c.name,
            c.kind,
            *bound(problem, c.jid),
            lim.effort if lim is not None else None,
            related=tuple(problem.related(c.jid)),
            vi=problem.model.joints[c.jid].idx_v,
            passive=driven is not None and c.name not in driven,
        )
    result.seconds = time.perf_counter() - start
    return result


def _unphysical_mass(doc: Document) -> str | None:
    """The first link whose mass is negative or not a finite number."""
    from urdflint.model.inertia import read_inertial

    for link in doc.links:
        inertial = read_inertial(link.element)
        mass = inertial.mass if inertial is not None else None
        if mass is not None and not (math.isfinite(mass) and mass >= 0.0):
            return link.name
    return None


def sample(problem: Problem) -> tuple[Any, Any]:
    """Uniform samples of every coordinate within its limits (the first one neutral), and
    the generalized gravity at each."""
    np = problem.np
    n = len(problem.coords)
    count = min(MAX_SAMPLES, max(MIN_SAMPLES, PER_COORDINATE * n)) if n <= MAX_DOF else 1
    rng = np.random.default_rng(SEED)
    thetas = problem.lo + problem.width * rng.random((count, n))
    thetas[0] = problem.clip(np.zeros(n))
    pin, model, data = problem.pin, problem.model, problem.data
    taus = np.array(
        [pin.computeGeneralizedGravity(model, data, q) for q in problem.q_matrix(thetas)]
    )
    return thetas, taus


def search(problem: Problem, load: JointLoad, thetas: Any, taus: Any) -> None:
    """Fill ``load.needed`` and ``load.theta``: the best samples, refined."""
    np = problem.np
    column = np.abs(taus[:, load.vi])
    order = np.argsort(-column, kind="stable")[:STARTS]
    load.needed, load.theta = float(column[order[0]]), thetas[order[0]].copy()
    settled = load.bound * (1 - SETTLE)
    if len(problem.coords) <= MAX_DOF and load.needed < settled:
        for index in order:
            value, theta = refine(problem, load, thetas[index])
            if value > load.needed:
                load.needed, load.theta = value, theta
            if load.needed >= settled:
                break


def refine(problem: Problem, load: JointLoad, theta: Any) -> tuple[float, Any]:
    """Projected gradient ascent on ``|τ|`` of ``load`` from ``theta``."""
    np = problem.np
    mask = np.zeros(len(problem.coords), dtype=bool)
    mask[list(load.related)] = True
    scale = np.where(mask, problem.width, 0.0)
    theta = np.array(theta, dtype=float)
    tau = problem.gravity(theta)[load.vi]
    value, step, evaluations = abs(float(tau)), 0.1, 0
    while evaluations < MAX_STEPS and step > MIN_STEP:
        grad = problem.gravity_gradient(theta)[load.vi] * math.copysign(1.0, tau) * scale
        grad[(theta <= problem.lo) & (grad < 0)] = 0.0
        grad[(theta >= problem.hi) & (grad > 0)] = 0.0
        top = float(np.max(np.abs(grad))) if grad.size else 0.0
        if top <= 0.0:
            break
        while evaluations < MAX_STEPS and step > MIN_STEP:
            trial = problem.clip(theta + step * scale * grad / top)
            t = problem.gravity(trial)[load.vi]
            evaluations += 1
            if abs(float(t)) > value:
                theta, tau, value = trial, t, abs(float(t))
                step = min(step * 2, 0.5)
                break
            step /= 2
    return value, theta


def witness(problem: Problem, load: JointLoad) -> None:
    """The configuration ``load.theta`` made readable, ``load.needed`` evaluated there.

    Each value is rounded (to 0, a limit, or fewer decimals) where that gives up less than
    :data:`KEEP` of the torque; a joint that changes the torque by less than
    :data:`MINOR` over its range is set to 0 (its neutral value) as long as the torque
    stays within :data:`LOSS` of the best and above the effort limit it exceeded. The
    joints shown (``load.at``) are those that change it more, and those not at 0.
    """
    np = problem.np
    theta = np.array(load.theta, dtype=float)

    def value(t: Any) -> float:
        return abs(float(problem.gravity(t)[load.vi]))

    best = value(theta)
    theta = _rounded(problem, load, theta, value, best * (1 - KEEP) - 1e-12)
    floor = max(best * (1 - LOSS), load.effort if load.effort and best > load.effort else 0.0)
    major = set()
    for i in load.related:
        if _influence(problem, theta, i, value) > MINOR * best:
            major.add(i)
            continue
        trial = theta.copy()
        trial[i] = min(max(0.0, problem.coords[i].lo), problem.coords[i].hi)
        if value(trial) > floor:
            theta = trial
    load.theta, load.needed = theta, value(theta)
    if load.needed <= TINY:
        load.needed, load.at = 0.0, {}
        return
    load.at = {
        problem.coords[i].name: float(theta[i]) + 0.0
        for i in load.related
        if i in major or theta[i] != 0
    }


def _rounded(problem: Problem, load: JointLoad, theta: Any, value: Any, keep: float) -> Any:
    """``theta`` with each related value rounded where ``value`` stays at least ``keep``."""
    for i in load.related:
        c = problem.coords[i]
        neutral = min(max(0.0, c.lo), c.hi)
        for option in (neutral, c.lo, c.hi, *(round(float(theta[i]), d) for d in ROUND)):
            trial = theta.copy()
            trial[i] = min(max(option, c.lo), c.hi)
            if value(trial) >= keep:
                theta = trial
                break
    return theta


def _influence(problem: Problem, theta: Any, i: int, value: Any) -> float:
    """How much coordinate ``i`` changes ``value`` over its range, from ``theta``."""
    c = problem.coords[i]
    here = value(theta)
    delta = min(c.hi - c.lo, 2 * math.pi) / 8
    probes = (c.lo, c.hi, (c.lo + c.hi) / 2, theta[i] - delta, theta[i] + delta)
    moved = 0.0
    for probe in probes:
        trial = theta.copy()
        trial[i] = min(max(probe, c.lo), c.hi)
        moved = max(moved, abs(value(trial) - here))
    return moved


def describe(statics: Statics, load: JointLoad) -> str:
    """``at shoulder=0, elbow=1.2 (the other joints at 0; 2 kg payload at 'tool0')``: where
    ``load.needed`` is reached, and the settings that shape it."""
    from urdflint.engine.statics_settings import EARTH
    from urdflint.model.values import fmt

    shown = ", ".join(f"{name}={fmt(value)}" for name, value in load.at.items())
    where = f"at {shown}" if shown else "in every configuration"
    notes = []
    if len(load.at) < len(load.related):
        notes.append("the other joints at 0")
    settings = statics.settings
    if settings.payload and statics.tool and not statics.unknown_link:
        notes.append(f"{fmt(settings.payload)} kg payload at '{statics.tool}'")
    if settings.gravity != EARTH:
        notes.append("gravity (" + ", ".join(fmt(g + 0.0) for g in settings.gravity) + ") m/s²")
    return where + (f" ({'; '.join(notes)})" if notes else "")
