"""The numbers of a built Pinocchio model: degrees of freedom, masses and centre of mass."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from urdflint.engine.physics.configuration import configuration
from urdflint.engine.physics.result import Physics, Vec
from urdflint.model.inertia import read_inertial
from urdflint.model.values import fmt, number

if TYPE_CHECKING:
    from urdflint.model.document import Document


def urdf_masses(doc: Document) -> dict[str, float]:
    """Each link's readable ``<mass>`` (links without one are left out)."""
    found: dict[str, float] = {}
    for name, link in doc.link_map.items():
        inertial = read_inertial(link.element)
        if inertial is not None and inertial.mass is not None:
            found[name] = inertial.mass
    return found


def compute(
    doc: Document, pin: Any, model: Any, result: Physics, static: dict[str, float]
) -> Physics:
    """Fill ``result`` from the built ``model``: DOF, masses, configuration and COM."""
    result.built = True
    result.model = model
    result.joint_names = list(model.names)[1:]
    result.mimics = _mimics(doc, set(result.joint_names))
    mimic_nv = sum(model.joints[model.getJointId(j)].nv for j in result.mimics)
    result.dof = int(model.nv) - mimic_nv
    result.naive_mass = float(pin.computeTotalMass(model))
    result.mass = float(sum(model.inertias[i].mass for i in range(model.njoints)))
    result.link_masses = link_masses(model)
    result.universe_links = [
        f.name
        for f in model.frames
        if f.type == pin.FrameType.BODY and f.parentJoint == 0 and f.name in doc.link_map
    ]
    q, result.q, result.q_problems = configuration(doc, pin, model, result.mimics)
    negative = sorted(n for n, m in static.items() if m < 0)
    if negative:
        listed = ", ".join(f"'{n}' ({fmt(static[n])} kg)" for n in negative)
        plural = len(negative) > 1
        result.com_problem = (
            f"link{'s' if plural else ''} {listed} {'have' if plural else 'has'} negative mass"
        )
    elif not result.mass > 0:
        result.com_problem = f"the total mass is {fmt(result.mass)} kg"
    else:
        result.com = _com(pin, model, q)
        if result.com is None:
            result.com_problem = "the centre of mass is not a finite number"
    return result


def _mimics(doc: Document, names: set[str]) -> dict[str, tuple[str, float, float]]:
    """``joint -> (leader, multiplier, offset)`` for mimic joints Pinocchio built."""
    found: dict[str, tuple[str, float, float]] = {}
    for joint in doc.joints:
        el = joint.find("mimic")
        if el is None or joint.name not in names or joint.type == "fixed":
            continue
        leader = el.get("joint")
        if leader is None:
            continue
        found[joint.name] = (  # type: ignore[index]
            leader,
            number(el, "multiplier", 1.0) or 0.0,
            number(el, "offset", 0.0) or 0.0,
        )
    return found


def link_masses(model: Any) -> dict[str, float]:
    """Each link's own mass as Pinocchio holds it.

    A link behind a fixed joint keeps its inertia on that joint's frame; a link on a
    moving joint (or the root, on the universe joint) has the joint's inertia minus
    what the fixed joints lumped into it.
    """
    import pinocchio as pin

    frames = model.frames
    lumped = [0.0] * model.njoints
    for index, frame in enumerate(frames):
        if frame.type == pin.FrameType.FIXED_JOINT and index != 0:
            lumped[frame.parentJoint] += frame.inertia.mass
    found: dict[str, float] = {}
    for frame in frames:
        if frame.type != pin.FrameType.BODY:
            continue
        parent = frames[frame.parentFrame] if frame.parentFrame < len(frames) else None
        if (
            parent is not None
            and parent.type == pin.FrameType.FIXED_JOINT
            and frame.parentFrame != 0
        ):
            found[frame.name] = float(parent.inertia.mass)
        else:
            j = frame.parentJoint
            found[frame.name] = float(model.inertias[j].mass - lumped[j])
    return found


def _com(pin: Any, model: Any, q: Any) -> Vec | None:
    """The COM of every body, the universe joint's included, in the root link frame.

    Forward kinematics joint by joint: ``model.createData()`` would allocate
    nv x nv matrices, gigabytes for a model with thousands of joints.
    """
    placements = [pin.SE3.Identity()] * model.njoints
    total = 0.0
    moment = [0.0, 0.0, 0.0]
    for i in range(model.njoints):
        if i:
            joint = model.joints[i]
            data = joint.createData()
            joint.calc(data, q)
            placements[i] = placements[model.parents[i]] * model.jointPlacements[i] * data.M
        inertia = model.inertias[i]
        if inertia.mass == 0.0:
            continue
        c = placements[i].act(inertia.lever)
        total += inertia.mass
        for k in range(3):
            moment[k] += inertia.mass * float(c[k])
    if not total > 0:
        return None
    com = (moment[0] / total, moment[1] / total, moment[2] / total)
    return com if all(math.isfinite(x) for x in com) else None
