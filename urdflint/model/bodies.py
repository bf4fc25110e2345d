"""Fixed-joint lumping, and what each target does with welded and with massless links.

sdformat's fixed-joint lumping builds rigid bodies (a link plus every link merged
into it through fixed joints). Gazebo and Pinocchio simulate those lumped bodies, and
MuJoCo fuses static bodies too (``fusestatic``, on by default for URDF). So degenerate
but physically possible values (point masses, tiny frames) are judged on the body.
Impossible values (a negative mass or moment, a tensor that is not positive definite or
breaks A + B >= C) are always reported on the link itself; :func:`impossible_severity`
says how bad they are for the selected targets. :func:`massless_verdict` says what the
targets do with a link that has no mass. The maths are in :mod:`urdflint.model.inertia`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from urdflint.model.finding import Severity
from urdflint.model.gazebo_spec import preserved_joints
from urdflint.model.geometry import shapes
from urdflint.model.inertia import (
    IDENTITY,
    TINY_MOMENT,
    ZERO,
    Mat,
    Vec,
    apply,
    eigenvalues,
    judge,
    matmul,
    read_inertial,
    rotate,
    rpy_matrix,
)
from urdflint.model.targets import DEFAULT_TARGETS, GAZEBO, gazebo_label
from urdflint.model.values import vector

if TYPE_CHECKING:
    from urdflint.model.document import Document

# sdformat before 9.10.1 / 12.7.2 / 13.5.0: math::equal(mass, 0.0), tolerance 1e-6; later: mass <= 0
GAZEBO_MASSLESS = 1e-6
MOVABLE = frozenset({"revolute", "continuous", "prismatic", "floating", "planar"})
# Targets that lump a welded link into its parent before anything checks its inertia:
# sdformat's ReduceFixedJoints sums the inertials, and only the lumped link is validated.
# MuJoCo fuses static bodies too, but validates every body before (mujoco 4.0: "inertia
# must satisfy A + B >= C", naming the welded link); Drake and PyBullet keep welded links.
LUMPING = frozenset(GAZEBO)
# Targets that never read a link's inertia: ROS (robot_state_publisher and KDL's kinematics,
# MoveIt's RobotModel) loads any tensor and uses none.
INERTIA_BLIND = frozenset({"ros"})
MUJOCO_DENSITY = 1000.0  # kg/m^3, MuJoCo's default geom density


# -- Gazebo's lumped bodies ---------------------------------------------------------------


class Bodies:
    """The links of one document grouped as sdformat's fixed-joint lumping groups them."""

    def __init__(self, doc: Document) -> None:
        self.doc = doc
        self.graph = doc.graph
        self.kept = preserved_joints(doc)
        self.inertials = {name: read_inertial(link.element) for name, link in doc.link_map.items()}
        self._members: dict[str, list] = {}
        self._inertia: dict[str, tuple[float, Vec, Mat] | None] = {}

    def merged(self, name: str) -> bool:
        """Whether ``name`` is lumped into its parent (fixed joint, not kept, parent not world)."""
        joint = self.graph.parent_joint(name)
        return (
            joint is not None
            and joint.type == "fixed"
            and joint.name not in self.kept
            and joint.parent not in (None, "world")
        )

    def body_of(self, name: str) -> str:
        seen = {name}
        while self.merged(name):
            parent = self.graph.parent_link(name)
            if parent is None or parent in seen:
                break
            seen.add(parent)
            name = parent
        return name

    def members(self, body: str) -> list[tuple[str, Mat, Vec] | tuple[str, None, None]]:
        """``(link, R, p)`` of the body's links in its frame (``None``: unreadable origin)."""
        if body not in self._members:
            self._members[body] = self._collect(body)
        return self._members[body]

    def _collect(self, body: str) -> list[tuple[str, Mat, Vec] | tuple[str, None, None]]:
        found: list = [(body, IDENTITY, ZERO)]
        seen = {body}
        index = 0
        while index < len(found):
            name, rot, pos = found[index]
            index += 1
            for joint in self.graph.child_joints.get(name, []):
                child = joint.child
                if child is None or child in seen or not self.merged(child):
                    continue
                seen.add(child)
                origin = joint.find("origin")
                xyz, rpy = vector(origin, "xyz", 3, ZERO), vector(origin, "rpy", 3, ZERO)
                if rot is None or xyz is None or rpy is None:
                    found.append((child, None, None))
                else:
                    found.append((child, matmul(rot, rpy_matrix(rpy)), _add(apply(rot, xyz), pos)))  # type: ignore[arg-type]
        return found

    def mass(self, body: str) -> float | None:
        """Total mass of the body's links; ``None`` when one of them is unreadable."""
        total = 0.0
        for name, _, _ in self.members(body):
            inertial = self.inertials.get(name)
            if inertial is not None:
                if inertial.mass is None:
                    return None
                total += inertial.mass
        return total

    def inertia(self, body: str) -> tuple[float, Vec, Mat] | None:
        """``(mass, centre of mass, tensor about it)`` of the lumped body, in the body's frame."""
        if body not in self._inertia:
            self._inertia[body] = self._combine(body)
        return self._inertia[body]

    def _combine(self, body: str) -> tuple[float, Vec, Mat] | None:
        parts: list[tuple[float, Vec, Mat]] = []
        for name, rot, pos in self.members(body):
            inertial = self.inertials.get(name)
            if inertial is None:
                continue
            if rot is None or pos is None or inertial.mass is None or inertial.matrix is None:
                return None
            if inertial.xyz is None or inertial.rpy is None:
                return None
            frame = matmul(rot, rpy_matrix(inertial.rpy))
            parts.append(
                (inertial.mass, _add(apply(rot, inertial.xyz), pos), rotate(inertial.matrix, frame))
            )
        total = sum(m for m, _, _ in parts)
        if total <= 0.0:
            return None
        com = tuple(sum(m * c[i] for m, c, _ in parts) / total for i in range(3))
        tensor = [[0.0] * 3 for _ in range(3)]
        for m, c, t in parts:
            d = [c[i] - com[i] for i in range(3)]
            dd = sum(x * x for x in d)
            for i in range(3):
                for j in range(3):
                    tensor[i][j] += t[i][j] + m * ((dd if i == j else 0.0) - d[i] * d[j])
        return total, com, tuple(tuple(row) for row in tensor)  # type: ignore[return-value]

    def body_is_sound(self, name: str) -> bool:
        """Whether the body ``name`` belongs to has mass and valid, not tiny, principal moments."""
        found = self.inertia(self.body_of(name))
        if found is None or found[0] <= GAZEBO_MASSLESS:
            return False
        moments = eigenvalues(found[2])
        return judge(moments) == "valid" and min(moments) >= TINY_MOMENT

    def excused(self, name: str) -> bool:
        """Whether degenerate values on ``name`` are harmless or better reported elsewhere.

        True when the lumped body is sound anyway, or when the link carries under 1% of
        the body's mass (a dummy root or frame): the heavier links that leave the body
        without a valid inertia are the ones reported.
        """
        if self.body_is_sound(name):
            return True
        own, total = self.inertials.get(name), self.mass(self.body_of(name))
        return own is not None and own.mass is not None and bool(total) and own.mass < 0.01 * total  # type: ignore[operator]

    def negligible(self, name: str) -> bool:
        """A merged link whose mass and inertia are under 1% of its body's (a sensor frame)."""
        own, body = self.inertials.get(name), self.inertia(self.body_of(name))
        if (
            not self.merged(name)
            or own is None
            or own.mass is None
            or own.tensor is None
            or body is None
        ):
            return False
        return own.mass < 0.01 * body[0] and sum(own.tensor[:3]) < 0.01 * sum(
            body[2][i][i] for i in range(3)
        )


def bodies(doc: Document) -> Bodies:
    """The (cached) lumped bodies of ``doc``, kept on the document: a weak mapping from the
    document would never let it go (its value refers to the document)."""
    found: Bodies | None = doc.__dict__.get("_lumped_bodies")
    if found is None:
        found = doc.__dict__["_lumped_bodies"] = Bodies(doc)
    return found


def impossible_severity(doc: Document, name: str) -> Severity:
    """How bad a physically impossible value on link ``name`` is for the selected targets.

    An error, except on a link welded to its parent by a fixed joint when every selected
    target lumps it before checking (Gazebo Classic and Sim): then only the lumped body
    counts, and the value is a warning while that body is sound. MuJoCo, Drake and
    PyBullet check each link on its own, so for them it is always an error. ROS reads no
    inertia (:data:`INERTIA_BLIND`), so beside Gazebo it changes nothing.
    """
    b = bodies(doc)
    weighing = selected(doc) - INERTIA_BLIND
    if not b.merged(name) or not weighing <= LUMPING:
        return Severity.ERROR
    return Severity.WARNING if b.body_is_sound(name) else Severity.ERROR


def selected(doc: Document) -> frozenset[str]:
    """The document's targets (the default ones when none is selected)."""
    return doc.targets or frozenset(DEFAULT_TARGETS)


@dataclass(frozen=True, slots=True)
class Verdict:
    """What the selected targets do with a link that has no mass, and how bad that is.

    ``kind`` is ``drop`` (Gazebo drops the link and its subtree), ``merge`` (Gazebo merges
    its geometry, without mass, into its parent), ``infer`` (MuJoCo makes up a mass from its
    collision geometry), ``fuse`` (MuJoCo does so and fuses it into its parent) or
    ``refuse`` (MuJoCo refuses the model); several, joined by ``+``.
    """

    severity: Severity
    consequence: str
    kind: str = ""


def massless_verdict(doc: Document, name: str, declared: bool = True) -> Verdict | None:
    """What the selected targets do with link ``name``, which has no mass of its own.

    ``declared``: the link has an ``<inertial>`` (with mass 0), not none at all.
    ``None`` when no target loses anything.
    """
    found: list[Verdict | None] = []
    targets = selected(doc)
    if targets & LUMPING:
        found.append(gazebo_verdict(doc, name))
    if "mujoco" in targets:
        found.append(mujoco_verdict(doc, name, declared))
    verdicts = [v for v in found if v is not None]
    if len(verdicts) < 2:
        return verdicts[0] if verdicts else None
    return Verdict(
        max(v.severity for v in verdicts),
        "; ".join(v.consequence for v in verdicts),
        "+".join(v.kind for v in verdicts),
    )


def gazebo_verdict(doc: Document, name: str) -> Verdict | None:
    """Gazebo's handling of link ``name`` when it has no mass of its own (``None``: harmless).

    A root link whose lumped body has no mass at all is I013's (the whole model is lost).
    """
    b = bodies(doc)
    graph = b.graph
    label = gazebo_label(doc.targets)
    link = doc.link_map[name]
    if b.merged(name):
        if link.visuals or link.collisions:
            merged = f"{label} merges it into '{b.body_of(name)}' as geometry without mass"
            return Verdict(Severity.INFO, merged, "merge")
        return None
    total = b.mass(name)
    joint = graph.parent_joint(name)
    if total is None or total > GAZEBO_MASSLESS or (joint is None and name == "world"):
        return None
    below = graph.subtree(name)[1:]
    if joint is None:
        if not below or name != graph.root or total <= 0:
            return None
        return Verdict(Severity.WARNING, f"{label} drops it and with it the whole model", "drop")
    if below:
        lost = f"the {len(below)} link{'s' if len(below) > 1 else ''} below it"
        consequence = f"{label} drops it, its joint '{joint.name}' and {lost}"
    else:
        consequence = f"{label} drops it and its joint '{joint.name}'"
    moving = joint.type in MOVABLE or any(
        j.type in MOVABLE for n in below for j in graph.parent_joints.get(n, [])
    )
    if moving:
        return Verdict(Severity.ERROR, consequence, "drop")
    if any(doc.link_map[n].visuals or doc.link_map[n].collisions for n in [name, *below]):
        return Verdict(Severity.WARNING, consequence, "drop")
    return None


def mujoco_verdict(doc: Document, name: str, declared: bool = True) -> Verdict | None:
    """MuJoCo's handling of link ``name`` without mass (``None``: harmless).

    MuJoCo's URDF import (observed with mujoco 4.0) makes the root link and every link
    welded to it static (fused into the world, mass irrelevant), fuses links under fixed
    joints into their parent, computes the inertia of a link *without* ``<inertial>``
    from its collision geometry at 1000 kg/m³ (``inertiafromgeom="auto"``; visuals are
    discarded), and refuses a moving body left without mass.
    """
    graph = doc.graph
    joint = graph.parent_joint(name)
    if joint is None or _static(doc, name):
        return None
    infer = mujoco_compiler(doc, "inertiafromgeom", "auto")
    guessed = _collides(doc, name) and (infer == "true" or (infer == "auto" and not declared))
    if joint.type == "fixed":
        if not guessed:
            return None
        fused = (
            f"MuJoCo gives it the mass of its collision geometry "
            f"({MUJOCO_DENSITY:.0f} kg/m³) and fuses it into '{joint.parent}'"
        )
        return Verdict(Severity.INFO, fused, "fuse")
    if guessed and not _fused_mass(doc, name, "false"):  # a welded child's mass is used
        made_up = (
            "MuJoCo makes up its mass and inertia from its collision geometry "
            f"({MUJOCO_DENSITY:.0f} kg/m³)"
        )
        return Verdict(Severity.WARNING, made_up, "infer")
    if guessed or _fused_mass(doc, name, infer):
        return None
    refused = (
        'MuJoCo refuses the model ("mass and inertia of moving bodies must be larger '
        'than mjMINVAL")'
    )
    return Verdict(Severity.ERROR, refused, "refuse")


def mujoco_compiler(doc: Document, attribute: str, default: str) -> str:
    """An attribute of ``<mujoco><compiler>`` in the URDF (MuJoCo's own extension)."""
    for compiler in doc.robot.findall("mujoco/compiler"):
        value = compiler.get(attribute)
        if value is not None:
            return value.strip().lower()
    return default


def _collides(doc: Document, name: str) -> bool:
    """Whether link ``name`` has a collision shape MuJoCo can compute an inertia from."""
    return any(shape.valid for shape in shapes(doc.link_map[name].element, "collision"))


def _static(doc: Document, name: str) -> bool:
    """Whether only fixed joints lie between link ``name`` and its root."""
    seen = {name}
    joint = doc.graph.parent_joint(name)
    while joint is not None:
        if joint.type != "fixed" or joint.parent is None or joint.parent in seen:
            return False
        seen.add(joint.parent)
        joint = doc.graph.parent_joint(joint.parent)
    return True


def _fused_mass(doc: Document, name: str, infer: str) -> bool:
    """Whether a link welded below ``name`` gives MuJoCo's fused body a mass."""
    graph, b = doc.graph, bodies(doc)
    stack = [j.child for j in graph.child_joints.get(name, []) if j.type == "fixed"]
    seen = {name}
    while stack:
        child = stack.pop()
        if child is None or child in seen or child not in doc.link_map:
            continue
        seen.add(child)
        inertial = b.inertials.get(child)
        if _collides(doc, child) and (infer == "true" or (infer == "auto" and inertial is None)):
            return True
        if inertial is not None and inertial.mass is not None and inertial.mass > 0:
            return True
        stack.extend(j.child for j in graph.child_joints.get(child, []) if j.type == "fixed")
    return False


def _add(a: Vec, b: Vec) -> Vec:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])
