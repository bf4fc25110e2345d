"""The robot as a 3D scene for the web page: poses, shapes, centres of mass, inertia boxes.

:func:`build_scene` turns a document and its findings into a JSON-ready dict the page draws
with three.js. Everything is in the world frame at the zero configuration, or at
``expect.q`` (``--q`` / the service's ``q``), through the forward kinematics of
:mod:`urdflint.sources.self_collision` (each root at the origin; a mimic joint follows its
leader). A pose is ``at``: ``[x, y, z, qx, qy, qz, qw]`` (metres, a unit quaternion).

Per link (document order; a name defined twice counts once):

``visual`` / ``collision``  shapes: ``box`` (``size``), ``sphere`` (``radius``),
                            ``cylinder`` and ``capsule`` (``radius``, ``length``, along
                            their z axis), ``mesh`` (``mesh``: an index into ``meshes``,
                            or ``None`` with ``missing``: why it was not read); a visual's
                            ``rgba`` when its material gives one
``inertial``                ``mass``, ``com`` (the inertial origin in the world) and
                            ``box``: the uniform box of the same mass and inertia, as
                            Gazebo draws it (``size`` along the principal axes, ``at``),
                            ``valid`` false for a tensor no body can have (a negative
                            side is drawn as 0), or ``None`` with ``problem``
``findings``, ``severity``  indices into the findings list given (the link's own, those
                            of its ``<gazebo reference>`` blocks and of the joints whose
                            child it is) and the worst severity; ``inertia_severity``:
                            the worst of its I-family findings (the box and the COM)
``parent``                  the joint that makes the link's tree edge (the first joint
                            naming it as child, a loop cut where it closes), or ``None``

Joints carry their ``axis`` in the world (``origin``, unit ``direction``; ``None`` for
fixed joints and a zero axis) and their own findings. Meshes are read through the
document's resolver and mesh cache, so the service never reads outside its request folder;
they are sent once per file and scale (:mod:`urdflint.outputs.scene_meshes`). Heavy imports
(numpy, trimesh) happen inside the functions.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from urdflint.model.finding import Finding, Severity
from urdflint.model.geometry import Shape, read_shape
from urdflint.model.values import vector

if TYPE_CHECKING:
    import numpy as np
    from lxml import etree

    from urdflint.model.document import Document
    from urdflint.outputs.scene_meshes import MeshTable

SCENE_VERSION = 1
DIGITS = 6  # decimals kept for lengths and quaternion components
MAX_LINKS = 2000  # as the tree picture: past this, no scene


def build_scene(
    doc: Document, findings: Sequence[Finding] = (), max_triangles: int | None = None
) -> dict[str, Any] | None:
    """The scene of ``doc`` (``None`` when there is no usable robot or it is too big)."""
    if not doc.ok or not doc.links or len(doc.links) > MAX_LINKS:
        return None
    from urdflint.outputs.scene_meshes import TRIANGLES, MeshTable
    from urdflint.sources.self_collision import joint_values, link_poses

    values = joint_values(doc)
    poses = link_poses(doc, values)
    marks = Marks(doc, findings)
    meshes = MeshTable(doc)
    parents = tree_parents(doc)
    links: list[dict[str, Any]] = []
    seen: set[str] = set()
    for link in doc.links:
        name = link.name
        if name is None or name in seen or doc.link_map.get(name) is not link:
            continue
        seen.add(name)
        links.append(_link(doc, link.element, name, poses.get(name), meshes, marks))
        links[-1]["parent"] = parents.get(name)
    joints = [_joint(doc, joint, poses, marks) for joint in doc.joints if joint.name is not None]
    encoded, notes = meshes.encode(TRIANGLES if max_triangles is None else max_triangles)
    return {
        "version": SCENE_VERSION,
        "robot": doc.robot.get("name") or "",
        "q": {name: _r(value) for name, value in sorted(values.items())},
        "links": links,
        "joints": joints,
        "meshes": encoded,
        "notes": notes,
    }


# -- findings -----------------------------------------------------------------------------


class Marks:
    """Which findings belong to which link and joint, through ``Finding.element``."""

    def __init__(self, doc: Document, findings: Sequence[Finding]) -> None:
        owners: dict[str, tuple[str, str]] = {}
        for link in doc.links:
            if link.name is not None:
                owners.setdefault(doc.element_path(link.element), ("link", link.name))
        for joint in doc.joints:
            if joint.name is not None:
                owners.setdefault(doc.element_path(joint.element), ("joint", joint.name))
        for block in doc.gazebo:
            ref = block.get("reference")
            kind = "link" if ref in doc.link_map else "joint" if ref in doc.joint_map else None
            if ref is not None and kind is not None:
                owners.setdefault(doc.element_path(block), (kind, ref))
        self.findings = list(findings)
        self.of: dict[tuple[str, str], list[int]] = {}
        for index, finding in enumerate(self.findings):
            owner = _owner(finding.element, owners)
            if owner is not None:
                self.of.setdefault(owner, []).append(index)
        self.child_of = {j.name: j.child for j in doc.joints if j.name is not None}

    def link(self, name: str, parent_joints: Sequence[str]) -> list[int]:
        found = list(self.of.get(("link", name), []))
        for joint in parent_joints:
            found += self.of.get(("joint", joint), [])
        return sorted(set(found))

    def joint(self, name: str) -> list[int]:
        return list(self.of.get(("joint", name), []))

    def worst(self, indices: Sequence[int], family: str = "") -> str | None:
        found = [self.findings[i].severity for i in indices]
        if family:
            found = [
                self.findings[i].severity for i in indices if self.findings[i].code[:1] == family
            ]
        return str(Severity(max(found))) if found else None


def _owner(element: str, owners: dict[str, tuple[str, str]]) -> tuple[str, str] | None:
    """What the longest registered prefix of ``element`` (whole path steps) names."""
    best = None
    cuts = [i for i, ch in enumerate(element) if ch == "/" and i > 0] + [len(element)]
    for cut in cuts:
        best = owners.get(element[:cut], best)
    return best


def tree_parents(doc: Document) -> dict[str, str | None]:
    """Each defined link's tree joint: its first parent joint, with every loop cut at the
    link that comes first in the document (as the tree picture does)."""
    graph = doc.graph
    parent: dict[str, str | None] = {}
    up: dict[str, str | None] = {}
    for name in graph.links:
        joint = graph.parent_joint(name)
        named = joint is not None and joint.name is not None and joint.parent != name
        parent[name] = joint.name if joint is not None and named else None
        up[name] = joint.parent if joint is not None and named else None
    order = {name: i for i, name in enumerate(graph.links)}
    state: dict[str, int] = {}  # 1: on the current walk up, 2: done
    for name in graph.links:
        walk: list[str] = []
        current: str | None = name
        while current is not None and current not in state:
            state[current] = 1
            walk.append(current)
            current = up.get(current)
        if current is not None and state[current] == 1:  # the walk closed a loop
            cut = min(walk[walk.index(current) :], key=order.__getitem__)
            parent[cut] = up[cut] = None
        for seen in walk:
            state[seen] = 2
    return parent


# -- links --------------------------------------------------------------------------------


def _link(
    doc: Document,
    element: etree._Element,
    name: str,
    pose: np.ndarray | None,
    meshes: MeshTable,
    marks: Marks,
) -> dict[str, Any]:
    parents = [j.name for j in doc.graph.parent_joints.get(name, []) if j.name is not None]
    indices = marks.link(name, parents)
    entry: dict[str, Any] = {
        "name": name,
        "at": None if pose is None else at(pose),
        "severity": marks.worst(indices),
        "inertia_severity": marks.worst(indices, "I"),
        "findings": indices,
        "visual": [],
        "collision": [],
        "inertial": None,
    }
    if pose is None:
        return entry  # in a loop no root reaches: not placed
    for tag in ("visual", "collision"):
        for owner in element.findall(tag):
            shape = read_shape(owner)
            if shape is not None and shape.valid:
                entry[tag].append(_shape(doc, name, tag, shape, pose, meshes))
    entry["inertial"] = _inertial(element, pose)
    return entry


def _shape(
    doc: Document, link: str, tag: str, shape: Shape, pose: np.ndarray, meshes: MeshTable
) -> dict[str, Any]:
    from urdflint.sources.self_collision import transform

    found: dict[str, Any] = {"kind": shape.kind, "at": at(pose @ transform(shape.xyz, shape.rpy))}
    if shape.kind == "box" and shape.size is not None:
        found["size"] = [_r(v) for v in shape.size]
    elif shape.kind == "sphere":
        found["radius"] = _r(shape.radius or 0.0)
    elif shape.kind in ("cylinder", "capsule"):
        found["radius"], found["length"] = _r(shape.radius or 0.0), _r(shape.length or 0.0)
    else:
        found["file"] = (shape.filename or "").strip()
        found["mesh"], missing = meshes.add(link, tag, shape)
        if missing is not None:
            found["missing"] = missing
    if tag == "visual":
        rgba = colour(doc, shape.owner)
        if rgba is not None:
            found["rgba"] = rgba
    return found


def colour(doc: Document, visual: etree._Element) -> list[float] | None:
    """The visual's material colour: its own ``<color>``, or the named robot material's."""
    material = visual.find("material")
    if material is None:
        return None
    rgba = vector(material.find("color"), "rgba", 4)
    if rgba is None and material.get("name") in doc.material_map:
        rgba = vector(doc.material_map[material.get("name") or ""].find("color"), "rgba", 4)
    if rgba is None or not all(math.isfinite(v) for v in rgba):
        return None
    return [_r(min(1.0, max(0.0, v)), 3) for v in rgba]


def _joint(doc: Document, joint: Any, poses: dict[str, Any], marks: Marks) -> dict[str, Any]:
    indices = marks.joint(str(joint.name))
    return {
        "name": joint.name,
        "type": joint.type,
        "parent": joint.parent,
        "child": joint.child,
        "axis": _axis(joint, poses.get(joint.parent or "")),
        "severity": marks.worst(indices),
        "findings": indices,
    }


def _axis(joint: Any, pose: np.ndarray | None) -> dict[str, list[float]] | None:
    """The joint's axis in the world: its frame's origin and the unit direction."""
    import numpy as np

    from urdflint.sources.self_collision import MOVING, transform

    if pose is None or joint.type not in MOVING:
        return None
    origin = joint.find("origin")
    xyz = vector(origin, "xyz", 3, (0.0, 0.0, 0.0)) or (0.0, 0.0, 0.0)
    rpy = vector(origin, "rpy", 3, (0.0, 0.0, 0.0)) or (0.0, 0.0, 0.0)
    frame = pose @ transform(xyz, rpy)
    axis = np.array(vector(joint.find("axis"), "xyz", 3, (1.0, 0.0, 0.0)) or (0.0, 0.0, 0.0))
    norm = float(np.linalg.norm(axis))
    if not np.isfinite(frame).all() or not (norm > 0 and math.isfinite(norm)):
        return None
    direction = frame[:3, :3] @ (axis / norm)
    return {"origin": [_r(v) for v in frame[:3, 3]], "direction": [_r(v) for v in direction]}


# -- the inertia ----------------------------------------------------------------------------


def _inertial(link: etree._Element, pose: np.ndarray) -> dict[str, Any] | None:
    from urdflint.model.inertia import read_inertial
    from urdflint.sources.self_collision import transform

    inertial = read_inertial(link)
    if inertial is None:
        return None
    xyz, rpy = inertial.xyz or (0.0, 0.0, 0.0), inertial.rpy or (0.0, 0.0, 0.0)
    frame = pose @ transform(xyz, rpy)
    if not all(math.isfinite(v) for v in (*xyz, *rpy)) or inertial.xyz is None:
        return {"mass": inertial.mass, "com": None, "box": None, "problem": "no usable origin"}
    found: dict[str, Any] = {"mass": inertial.mass, "com": [_r(v) for v in frame[:3, 3]]}
    box, problem = equivalent_box(inertial.mass, inertial.tensor)
    if box is None:
        found.update(box=None, problem=problem)
        return found
    size, rotation, valid = box
    placed = frame.copy()
    placed[:3, :3] = frame[:3, :3] @ rotation
    found["box"] = {"size": [_r(v) for v in size], "at": at(placed), "valid": valid}
    if not valid:
        found["problem"] = problem
    return found


def equivalent_box(
    mass: float | None, tensor: tuple[float, ...] | None
) -> tuple[tuple[list[float], np.ndarray, bool] | None, str | None]:
    """The uniform box of ``mass`` with the inertia ``tensor`` (ixx iyy izz ixy ixz iyz), as
    Gazebo's "View > Inertia" draws it: ``(size, rotation, valid)``, the rotation's columns
    the principal axes in the inertial frame (identity for a diagonal tensor), and why not.

    Side ``i`` is ``sqrt(6 / m * (Ij + Ik - Ii))`` for the principal moments; a tensor that
    breaks the triangle inequality gives a negative square, drawn as 0 (``valid`` false).
    """
    import numpy as np

    if mass is None or not math.isfinite(mass) or mass <= 0:
        return None, "the mass is not positive"
    if tensor is None or not all(math.isfinite(v) for v in tensor):
        return None, "the inertia tensor cannot be read"
    ixx, iyy, izz, ixy, ixz, iyz = tensor
    if ixy == ixz == iyz == 0.0:
        moments, rotation = np.array([ixx, iyy, izz]), np.eye(3)
    else:
        matrix = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
        moments, rotation = principal_axes(matrix)
    if not moments.max() > 0:
        return None, "the inertia tensor is zero"
    squares = 6.0 / mass * (moments.sum() - 2.0 * moments)  # Ij + Ik - Ii
    tol = 1e-9 * float(moments.max()) * 6.0 / mass
    valid = bool((squares >= -tol).all() and moments.min() >= -1e-9 * moments.max())
    size = [math.sqrt(max(0.0, float(v))) for v in squares]
    problem = None if valid else "no rigid body has this inertia (a side would be imaginary)"
    return (size, rotation, valid), problem


def principal_axes(matrix: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues and a right-handed eigenvector basis of a symmetric 3x3 matrix, each
    column matched to the coordinate axis it lies closest to (so a nearly diagonal tensor
    keeps its sides along x, y, z)."""
    import numpy as np

    values, vectors = np.linalg.eigh(matrix)
    order = [-1, -1, -1]
    free = [0, 1, 2]
    weight = np.abs(vectors)
    for _ in range(3):  # greedy: the strongest (axis, column) pair first
        axis, col = max(
            ((a, c) for a in range(3) if order[a] < 0 for c in free),
            key=lambda pair: weight[pair[0], pair[1]],
        )
        order[axis] = col
        free.remove(col)
    vectors, values = vectors[:, order], values[order]
    for axis in range(3):
        if vectors[axis, axis] < 0:
            vectors[:, axis] = -vectors[:, axis]
    if np.linalg.det(vectors) < 0:
        vectors[:, 2] = -vectors[:, 2]
    return values, vectors


# -- numbers ------------------------------------------------------------------------------


def _r(value: float, digits: int = DIGITS) -> float:
    rounded = round(float(value), digits)
    return 0.0 if rounded == 0 else rounded  # never -0.0


def at(matrix: np.ndarray) -> list[float]:
    """``[x, y, z, qx, qy, qz, qw]`` of a 4x4 transform (rotation part orthonormal)."""
    x, y, z, w = quaternion(matrix[:3, :3])
    return [_r(v) for v in (*matrix[:3, 3], x, y, z, w)]


def quaternion(r: np.ndarray) -> tuple[float, float, float, float]:
    """``(x, y, z, w)`` of a rotation matrix (Shepperd's method, ``w >= 0``)."""
    trace = float(r[0, 0] + r[1, 1] + r[2, 2])
    if trace > 0:
        s = math.sqrt(trace + 1.0) * 2
        q = ((r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s, s / 4)
    elif r[0, 0] > r[1, 1] and r[0, 0] > r[2, 2]:
        s = math.sqrt(max(0.0, 1.0 + r[0, 0] - r[1, 1] - r[2, 2])) * 2
        q = (s / 4, (r[0, 1] + r[1, 0]) / s, (r[0, 2] + r[2, 0]) / s, (r[2, 1] - r[1, 2]) / s)
    elif r[1, 1] > r[2, 2]:
        s = math.sqrt(max(0.0, 1.0 + r[1, 1] - r[0, 0] - r[2, 2])) * 2
        q = ((r[0, 1] + r[1, 0]) / s, s / 4, (r[1, 2] + r[2, 1]) / s, (r[0, 2] - r[2, 0]) / s)
    else:
        s = math.sqrt(max(0.0, 1.0 + r[2, 2] - r[0, 0] - r[1, 1])) * 2
        q = ((r[0, 2] + r[2, 0]) / s, (r[1, 2] + r[2, 1]) / s, s / 4, (r[1, 0] - r[0, 1]) / s)
    norm = math.sqrt(sum(float(v) ** 2 for v in q)) or 1.0
    sign = -1.0 if q[3] < 0 else 1.0
    x, y, z, w = (sign * float(v) / norm for v in q)
    return x, y, z, w
