"""The configuration ``q`` the centre of mass is computed at: ``--q``/``expect.q``, mimics
following their leaders, neutral elsewhere."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from urdflint.engine.physics.result import QProblem

if TYPE_CHECKING:
    from urdflint.model.document import Document, Joint

Mimics = dict[str, tuple[str, float, float]]  # joint -> (leader, multiplier, offset)


def joint_label(joint: Joint) -> str:
    return f"{joint.type} joint '{joint.name}'" if joint.type else f"joint '{joint.name}'"


def configuration(
    doc: Document, pin: Any, model: Any, mimics: Mimics
) -> tuple[Any, dict[str, float], list[QProblem]]:
    """The configuration for ``settings.expect.q`` (neutral elsewhere), and what was wrong."""
    values, problems = requested(doc, model, mimics)
    applied = _follow_mimics(values, mimics)
    q = _q(pin, model, applied)
    applied = {k: v for k, v in applied.items() if k in values or v != 0.0}
    return q, applied, problems


def requested(doc: Document, model: Any, mimics: Mimics) -> tuple[dict[str, float], list[QProblem]]:
    """The ``expect.q`` positions that can be applied, and a problem for each other entry."""
    problems: list[QProblem] = []
    values: dict[str, float] = {}
    movable = set(model.names[1:])
    for name, value in dict(doc.settings.expect.q).items():
        problem = _problem(doc, model, mimics, movable, name)
        if problem is None:
            values[name] = value
        else:
            problems.append(problem)
    return values, problems


def _problem(
    doc: Document, model: Any, mimics: Mimics, movable: set[str], name: str
) -> QProblem | None:
    """Why joint ``name`` cannot be set (``None``: it can)."""
    from urdflint.model.structure import did_you_mean

    joint = doc.joint_map.get(name)
    if joint is None:
        fix = did_you_mean(name, model.names[1:], "joint")
        return QProblem(
            name,
            f"--q/expect.q names joint '{name}', which the model does not have",
            None,
            fix,
        )
    if name not in movable:
        return QProblem(
            name,
            f"--q/expect.q sets {joint_label(joint)}, which has no position",
            joint.element,
        )
    if name in mimics:
        leader = mimics[name][0]
        return QProblem(
            name,
            f"--q/expect.q sets {joint_label(joint)}, which mimics '{leader}'; "
            f"set '{leader}' instead",
            joint.element,
        )
    if (nv := model.joints[model.getJointId(name)].nv) != 1:
        return QProblem(
            name,
            f"--q/expect.q sets {joint_label(joint)}, which has {nv} "
            "degrees of freedom; only one-axis joints can be set",
            joint.element,
        )
    return None


def _follow_mimics(values: dict[str, float], mimics: Mimics) -> dict[str, float]:
    """``values`` with every mimic joint's position (``multiplier * leader + offset``) added."""

    def position(name: str, depth: int = 0) -> float:
        if name in mimics and depth < 64:
            leader, multiplier, offset = mimics[name]
            return multiplier * position(leader, depth + 1) + offset
        return values.get(name, 0.0)

    applied = dict(values)
    for name in mimics:
        applied[name] = position(name)
    return applied


def _q(pin: Any, model: Any, applied: dict[str, float]) -> Any:
    """Pinocchio's neutral configuration with the ``applied`` positions set."""
    q = pin.neutral(model)
    for name, value in applied.items():
        if not model.existJointName(name):
            continue
        joint = model.joints[model.getJointId(name)]
        if joint.nq == 1:
            q[joint.idx_q] = value
        elif joint.nq == 2 and joint.nv == 1:  # continuous: (cos, sin)
            q[joint.idx_q] = math.cos(value)
            q[joint.idx_q + 1] = math.sin(value)
    return q
