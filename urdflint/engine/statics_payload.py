"""The payload the weakest joint allows at full reach (``urdflint info --statics``).

The largest point mass ``m`` at the tool link (the configured payload link, else the end
of the longest chain) such that every actuated joint that carries the tool still holds
in every configuration the search finds. A point mass enters the generalized gravity
linearly, ``τ(q, m) = τ₀(q) + m·h(q)``, so each sample ``s`` of a joint with effort
``E`` allows ``m ≤ (E - τ₀)/h`` (or ``(E + τ₀)/(-h)``): the minimum over samples and
joints is the candidate. The joint that sets it is then refined by the same gradient
search with that mass on the tool; a configuration that exceeds ``E`` adds its own
constraint and the candidate shrinks, until the refinement agrees (a few rounds).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from urdflint.engine.statics import JointLoad, Statics
    from urdflint.model.document import Document

ROUNDS = 8
AGREE = 1e-6  # relative: a refined torque this close to the limit holds
NEAR = 1.5  # the joints whose sample limit is within this factor of the candidate are refined


@dataclass(frozen=True)
class Allowed:
    """``mass`` kg more at ``link`` (``inf``: gravity never limits it); ``joint`` is the one
    that sets it, ``None`` when nothing does; ``already`` when it cannot hold without one."""

    mass: float
    link: str
    joint: str | None
    already: bool = False


def allowed(doc: Document, statics: Statics) -> Allowed | None:
    """The payload the weakest joint allows at the tool link, or ``None`` when there is no
    tool link or no actuated joint with an effort limit carries it."""
    problem = statics.problem
    if not statics.ok or problem is None or statics.tool is None or statics.unknown_link:
        return None
    import pinocchio as pin

    from urdflint.engine.statics_model import Problem

    model = problem.model
    if not model.existFrame(statics.tool, pin.FrameType.BODY):
        return None
    body = model.frames[model.getFrameId(statics.tool, pin.FrameType.BODY)].parentJoint
    support = set(model.supports[body])
    joints = [
        load
        for load in statics.joints.values()
        if load.effort
        and load.effort > 0
        and not load.passive
        and problem.coords[problem.index[load.name]].jid in support
    ]
    if not joints:
        return None
    for load in joints:
        if statics.load(load.name).needed > load.effort:  # type: ignore[operator]
            return Allowed(0.0, statics.tool, load.name, already=True)
    unit = replace(
        statics.settings, payload=statics.settings.payload + 1.0, payload_link=statics.tool
    )
    plus = Problem(doc, pin, problem.np, unit)
    thetas, taus = statics.sampled()
    slopes = problem.np.array([plus.gravity(t) for t in thetas]) - taus
    limits = {
        load.name: _limit(problem.np, taus[:, load.vi], slopes[:, load.vi], load.effort or 0.0)
        for load in joints
    }
    return _settle(doc, statics, joints, limits, (thetas, taus, slopes, plus))


def _limit(np: Any, tau: Any, slope: Any, effort: float) -> float:
    """The largest mass every sample allows: ``|τ + m h| ≤ effort`` for ``m ≥ 0``."""
    up = np.where(slope > 0, (effort - tau) / np.where(slope > 0, slope, 1.0), math.inf)
    down = np.where(slope < 0, (effort + tau) / np.where(slope < 0, -slope, 1.0), math.inf)
    return float(max(0.0, min(np.min(up, initial=math.inf), np.min(down, initial=math.inf))))


def _settle(
    doc: Document, statics: Statics, joints: list[JointLoad], limits: dict[str, float], data: Any
) -> Allowed:
    """Refine the joints near the limit with that mass on the tool until they agree."""
    import pinocchio as pin

    from urdflint.engine.statics_model import Problem

    np = statics.problem.np  # type: ignore[union-attr]
    thetas, taus, slopes, plus = data
    tool: str = statics.tool  # type: ignore[assignment]
    for _ in range(ROUNDS):
        name = min(limits, key=lambda n: (limits[n], n))
        mass = limits[name]
        if not math.isfinite(mass):
            return Allowed(math.inf, tool, None)
        settings = replace(statics.settings, payload=statics.settings.payload + mass)
        loaded = Problem(doc, pin, np, replace(settings, payload_link=tool))
        failed = False
        for load in joints:
            if limits[load.name] > mass * NEAR:
                continue
            column = np.abs(taus[:, load.vi] + mass * slopes[:, load.vi])
            theta = _worst(loaded, load, thetas[int(np.argmax(column))])
            if theta is not None:
                tau = float(statics.problem.gravity(theta)[load.vi])  # type: ignore[union-attr]
                slope = float(plus.gravity(theta)[load.vi]) - tau
                found = _limit(np, np.array([tau]), np.array([slope]), load.effort)  # type: ignore[arg-type]
                limits[load.name] = min(mass * (1 - AGREE), found)
                failed = True
        if not failed:
            return Allowed(mass, tool, name)
    name = min(limits, key=lambda n: (limits[n], n))
    return Allowed(limits[name], tool, name)


def _worst(loaded: Any, load: JointLoad, start: Any) -> Any:
    """A configuration where ``load``'s joint exceeds its effort with the mass, or ``None``."""
    from urdflint.engine.statics import refine

    value, theta = refine(loaded, load, start)
    return theta if value > load.effort * (1 + AGREE) else None  # type: ignore[operator]
