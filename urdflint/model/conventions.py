"""Frame names and relative poses for the REP naming-convention rules (N).

The REPs name frames, and multi-robot models prefix those names (REP 199's
``robot_base_link``, a xacro's ``${prefix}base_link``): :func:`named` accepts a frame
name with such a prefix. The poses are the zero-configuration transforms of the
joints' ``<origin>`` (URDF's ``Rz(yaw) Ry(pitch) Rx(roll)``), composed along the tree.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from urdflint.model.inertia import IDENTITY, ZERO, Mat, Vec, apply, matmul, rpy_matrix, transpose
from urdflint.model.values import fmt, vector

if TYPE_CHECKING:
    from urdflint.model.document import Document, Joint
    from urdflint.model.graph import Graph

Pose = tuple[Mat, Vec]  # rotation, translation: a child frame expressed in its parent
SEPARATORS = "_/}"  # what ends a prefix: robot_, ns/, ${prefix}
ANGLE_TOL = 0.01  # rad: 1.57 for pi/2 is 0.0008 away, a wrong axis is 1.57 away
LENGTH_TOL = 1e-4  # m


def named(name: str | None, frame: str) -> bool:
    """``name`` is ``frame`` or ``frame`` behind a prefix (``left_tool0``, ``${p}tool0``)."""
    if not name or not name.endswith(frame):
        return False
    head = name[: -len(frame)]
    return not head or head[-1] in SEPARATORS


def prefixes(doc: Document, frame: str) -> list[str]:
    """The prefixes the robot's links put before ``frame`` (``""`` for ``frame`` itself)."""
    found = [link.name for link in doc.links if link.name and named(link.name, frame)]
    return list(dict.fromkeys(name[: -len(frame)] for name in found if name))


def joint_pose(joint: Joint) -> Pose | None:
    """The joint's ``<origin>`` as a pose, ``None`` when it is malformed."""
    origin = joint.find("origin")
    xyz = vector(origin, "xyz", 3, ZERO)
    rpy = vector(origin, "rpy", 3, ZERO)
    if xyz is None or rpy is None:
        return None
    return rpy_matrix(rpy), xyz  # type: ignore[arg-type, return-value]


def compose(a: Pose, b: Pose) -> Pose:
    """``b`` expressed in ``a``'s parent: ``a * b``."""
    rotation = matmul(a[0], b[0])
    moved = apply(a[0], b[1])
    return rotation, (moved[0] + a[1][0], moved[1] + a[1][1], moved[2] + a[1][2])


def invert(a: Pose) -> Pose:
    back = transpose(a[0])
    moved = apply(back, a[1])
    return back, (-moved[0], -moved[1], -moved[2])


def path_up(graph: Graph, link: str) -> list[Joint]:
    """The joints from ``link`` up to its root, nearest first (stops on a loop)."""
    joints: list[Joint] = []
    seen = {link}
    joint = graph.parent_joint(link)
    while joint is not None and joint.parent is not None and joint.parent not in seen:
        joints.append(joint)
        seen.add(joint.parent)
        joint = graph.parent_joint(joint.parent)
    return joints


def _pose_below(joints: list[Joint]) -> Pose | None:
    """The pose of the first joint's child in the last joint's parent."""
    pose: Pose = (IDENTITY, ZERO)
    for joint in joints:
        step = joint_pose(joint)
        if step is None:
            return None
        pose = compose(step, pose)
    return pose


def relative(doc: Document, base: str, target: str, *, rigid: bool = True) -> Pose | None:
    """The pose of ``target`` in ``base``'s frame, through their common ancestor.

    ``None`` when they are not in one tree, when an origin on the way is malformed or,
    with ``rigid``, when a joint on the way is not ``fixed`` (the pose would depend on
    the joint's position).
    """
    graph = doc.graph
    up_base, up_target = path_up(graph, base), path_up(graph, target)
    above_base = [base] + [j.parent for j in up_base]
    above_target = [target] + [j.parent for j in up_target]
    common = next((name for name in above_target if name in above_base), None)
    if common is None:
        return None
    from_base = up_base[: above_base.index(common)]
    from_target = up_target[: above_target.index(common)]
    if rigid and any(j.type != "fixed" for j in (*from_base, *from_target)):
        return None
    base_pose, target_pose = _pose_below(from_base), _pose_below(from_target)
    if base_pose is None or target_pose is None:
        return None
    return compose(invert(base_pose), target_pose)


def angle(a: Mat, b: Mat) -> float:
    """The angle of the rotation that takes ``a`` to ``b`` (radians, 0 to pi)."""
    r = matmul(transpose(a), b)
    cosine = (r[0][0] + r[1][1] + r[2][2] - 1.0) / 2.0
    return math.acos(max(-1.0, min(1.0, cosine)))


def column(r: Mat, axis: int) -> Vec:
    """The direction of the child's ``axis`` (0 x, 1 y, 2 z) in the parent frame."""
    return (r[0][axis], r[1][axis], r[2][axis])


def rpy_of(r: Mat) -> Vec:
    """Roll, pitch and yaw of a rotation matrix (URDF convention)."""
    pitch = math.asin(max(-1.0, min(1.0, -r[2][0])))
    if abs(r[2][0]) < 1.0 - 1e-9:
        return math.atan2(r[2][1], r[2][2]), pitch, math.atan2(r[1][0], r[0][0])
    return 0.0, pitch, math.atan2(-r[0][1], r[1][1])  # gimbal lock: yaw absorbs roll


def fmt_angles(values: Vec) -> str:
    """``-pi/2 0 -pi/2`` for multiples of pi/2, else numbers (``0.3 0 1.2``)."""
    return " ".join(_fmt_angle(v) for v in values)


def _fmt_angle(value: float) -> str:
    quarters = value / (math.pi / 2)
    if abs(quarters - round(quarters)) < 1e-6:
        return {0: "0", 1: "pi/2", -1: "-pi/2", 2: "pi", -2: "-pi"}.get(round(quarters), fmt(value))
    return fmt(value + 0.0)


def fmt_axis(v: Vec) -> str:
    """An axis as a readable direction: ``+x``, ``-z``, or its components."""
    for index, label in enumerate("xyz"):
        if abs(abs(v[index]) - 1.0) < 1e-6:
            return ("+" if v[index] > 0 else "-") + label
    return "(" + " ".join(fmt(round(c, 4) + 0.0) for c in v) + ")"
