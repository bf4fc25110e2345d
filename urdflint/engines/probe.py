"""Load URDF files in one simulation engine and print what it built, one JSON line per file.

``python -m urdflint.engines.probe ENGINE MEMORY URDF [URDF...]`` is run by
:mod:`urdflint.engines.runner` in its own process (engines abort or crash on bad input),
with an address-space limit of ``MEMORY`` bytes (0: none). It loads the files in turn: a
new engine state for each (a PyBullet connection, a Drake plant), and writes one JSON line
per file to stdout, flushed, ``{"path", "engine", "ok", "error", "bodies", "joints",
"limits", "inertias"}``. The engine's own output, C level included, is moved to stderr,
where the parent reads it: before each file the probe writes a marker line, ``MARK INDEX``
(:data:`MARK`), so what the engine printed is attributable to its file, and after each file
it echoes (and deletes) the ``MUJOCO_LOG.TXT`` MuJoCo writes in the working folder.
``python -m urdflint.engines.probe --serve ENGINE MEMORY`` reads the paths from stdin
instead, one JSON string per line, and writes an end marker (:data:`END`) to stderr after
each file, before its report: a warm probe (:mod:`urdflint.engines.warm`).

``bodies`` are the link names the engine kept (MuJoCo bodies, PyBullet links, Drake bodies,
Pinocchio ``BODY`` frames). ``limits`` maps each revolute or prismatic joint to ``[type,
lower, upper]`` as built (``null`` when unlimited), in URDF units; ``inertias`` maps each
body to ``[mass, principal moments about its centre of mass]`` as built.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path
from typing import Any

Built = dict[str, Any]
Limit = list[Any]


def principal(matrix: Any) -> list[float]:
    """The eigenvalues of a symmetric 3x3 tensor, ascending."""
    import numpy as np

    return [float(v) for v in np.linalg.eigvalsh(np.asarray(matrix, dtype=float).reshape(3, 3))]


def bound(value: float, infinite: bool) -> float | None:
    return None if infinite else float(value)


def mujoco(path: str) -> Built:
    import mujoco as mj

    model = mj.MjModel.from_xml_path(path)
    bodies = [mj.mj_id2name(model, mj.mjtObj.mjOBJ_BODY, i) or "" for i in range(model.nbody)]
    joints = [mj.mj_id2name(model, mj.mjtObj.mjOBJ_JOINT, i) or "" for i in range(model.njnt)]
    kinds = {int(mj.mjtJoint.mjJNT_HINGE): "revolute", int(mj.mjtJoint.mjJNT_SLIDE): "prismatic"}
    limits: dict[str, Limit] = {}
    for i, name in enumerate(joints):
        kind = kinds.get(int(model.jnt_type[i]))
        if kind is not None:
            low, high = (float(v) for v in model.jnt_range[i])
            limited = bool(model.jnt_limited[i])
            limits[name] = [kind, low if limited else None, high if limited else None]
    inertias = {
        name: [float(model.body_mass[i]), sorted(float(v) for v in model.body_inertia[i])]
        for i, name in enumerate(bodies)
    }
    return {"bodies": bodies, "joints": joints, "limits": limits, "inertias": inertias}


def pybullet(path: str) -> Built:
    import pybullet as pb

    client = pb.connect(pb.DIRECT)
    kinds = {pb.JOINT_REVOLUTE: "revolute", pb.JOINT_PRISMATIC: "prismatic"}
    try:
        robot = pb.loadURDF(path, useFixedBase=True, flags=pb.URDF_USE_INERTIA_FROM_FILE,
                           physicsClientId=client)  # fmt: skip
        bodies = [pb.getBodyInfo(robot, physicsClientId=client)[0].decode()]
        joints, limits = [], {}
        for index in range(pb.getNumJoints(robot, physicsClientId=client)):
            info = pb.getJointInfo(robot, index, physicsClientId=client)
            joints.append(info[1].decode())
            bodies.append(info[12].decode())
            if info[2] in kinds:  # Bullet: lower > upper means no limit
                low, high = float(info[8]), float(info[9])
                limited = low <= high
                limits[joints[-1]] = [kinds[info[2]], low if limited else None,
                                      high if limited else None]  # fmt: skip
        inertias = {}
        for index, name in enumerate(bodies, start=-1):
            found = pb.getDynamicsInfo(robot, index, physicsClientId=client)
            inertias[name] = [float(found[0]), sorted(float(v) for v in found[2])]
        return {"bodies": bodies, "joints": joints, "limits": limits, "inertias": inertias}
    finally:
        pb.disconnect(client)


def drake(path: str) -> Built:
    import math

    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
    from pydrake.multibody.tree import BodyIndex, JointIndex
    from pydrake.systems.framework import DiagramBuilder

    # with a SceneGraph, as simulations use it: geometry (meshes, shapes) is registered too
    plant, _ = AddMultibodyPlantSceneGraph(DiagramBuilder(), 0.0)
    Parser(plant).AddModels(file_name=Path(path))
    found = [plant.get_body(BodyIndex(i)) for i in range(1, plant.num_bodies())]
    bodies = [body.name() for body in found]
    joints, limits = [], {}
    for i in range(plant.num_joints()):
        joint = plant.get_joint(JointIndex(i))
        joints.append(joint.name())
        kind = {"revolute": "revolute", "prismatic": "prismatic"}.get(joint.type_name())
        if kind is not None:
            low = float(joint.position_lower_limits()[0])
            high = float(joint.position_upper_limits()[0])
            limits[joint.name()] = [
                kind,
                bound(low, math.isinf(low)),
                bound(high, math.isinf(high)),
            ]
    inertias = {}
    for body in found:
        spatial = body.default_spatial_inertia()  # about the body origin: shift to the COM
        about_com = spatial.Shift(spatial.get_com()).CalcRotationalInertia()
        moments = about_com.CalcPrincipalMomentsOfInertia()
        inertias[body.name()] = [float(body.default_mass()), sorted(float(v) for v in moments)]
    return {"bodies": bodies, "joints": joints, "limits": limits, "inertias": inertias}


def pinocchio(path: str) -> Built:
    import math

    import pinocchio as pin

    model = pin.buildModelFromUrdf(path)
    for kind in (pin.GeometryType.COLLISION, pin.GeometryType.VISUAL):  # as RobotWrapper does
        pin.buildGeomFromUrdf(model, path, kind, package_dirs=[str(Path(path).parent)])
    frames = [f for f in model.frames if f.type == pin.FrameType.BODY]
    joints = [str(name) for name in list(model.names)[1:]]
    limits, inertias = {}, {}
    for index, joint in enumerate(model.joints):
        kind = {"R": "revolute", "P": "prismatic"}.get(joint.shortname()[len("JointModel")])
        if index == 0 or joint.nq != 1 or kind is None:
            continue
        low = float(model.lowerPositionLimit[joint.idx_q])
        high = float(model.upperPositionLimit[joint.idx_q])
        unbounded = [math.isinf(v) or abs(v) >= 1e300 for v in (low, high)]
        limits[str(model.names[index])] = [
            kind,
            bound(low, unbounded[0]),
            bound(high, unbounded[1]),
        ]
        inertia = model.inertias[index]
        inertias[str(model.names[index])] = [float(inertia.mass), principal(inertia.inertia)]
    bodies = [f.name for f in frames]
    child: dict[int, str] = {}
    for frame in frames:  # a joint's first body frame is its child link (the others: lumped)
        child.setdefault(int(frame.parentJoint), frame.name)
    named = {child.get(model.getJointId(j), j): v for j, v in inertias.items()}
    return {"bodies": bodies, "joints": joints, "limits": limits, "inertias": named}


LOADERS = {"mujoco": mujoco, "pybullet": pybullet, "drake": drake, "pinocchio": pinocchio}


def limit_memory(limit: int) -> None:
    """Cap the address space (POSIX): a runaway engine fails to allocate instead of
    taking the machine down. Set here, before the engine is imported: a ``preexec_fn``
    is not safe in a parent that runs several probes from threads."""
    try:
        import resource
    except ImportError:  # Windows: only the timeout applies
        return
    if limit > 0:
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))


MARK = "@@urdflint-probe-file"  # stderr: what follows, up to the next mark, is about file N
END = "@@urdflint-probe-done"  # --serve, stderr: model N is done (its report follows)
MUJOCO_LOG = "MUJOCO_LOG.TXT"


def load(engine: str, path: str) -> dict[str, Any]:
    """The report on one file: what ``engine`` built, or why it refused it."""
    report: dict[str, Any] = {"path": path, "engine": engine, "ok": False, "error": None,
                              "bodies": [], "joints": [], "limits": {}, "inertias": {}}  # fmt: skip
    try:
        report.update(LOADERS[engine](path))
        report["ok"] = True
    except Exception as exc:  # the engine refused the model: its message is the finding
        report["error"] = f"{type(exc).__name__}: {exc}"
    return report


def flush() -> None:
    """Flush what was printed so far, Python's buffers and C's (``stdout`` is stderr here)."""
    sys.stdout.flush()
    sys.stderr.flush()
    try:
        import ctypes

        ctypes.CDLL(None).fflush(None)
    except (OSError, AttributeError, TypeError):  # no C library to ask (Windows)
        pass


def echo_log() -> None:
    """Move MuJoCo's log of the file just loaded (in the working folder) to stderr."""
    log = Path(MUJOCO_LOG)
    if log.is_file():
        sys.stderr.write("\n" + log.read_text(encoding="utf-8", errors="replace") + "\n")
        log.unlink()


def main(argv: list[str]) -> int:
    if argv[:1] == ["--serve"]:
        return serve(*argv[1:3])
    engine, memory, *paths = argv
    limit_memory(int(memory))
    out = os.fdopen(os.dup(1), "w")
    os.dup2(2, 1)  # everything the engine prints, C level included, goes to stderr
    for index, path in enumerate(paths):
        answer(engine, path, index, out)
    return 0


def answer(engine: str, path: str, index: int, out: Any, end: bool = False) -> None:
    """Load one file: its marker and the engine's output on stderr, its report on ``out``
    (``end``: an end marker on stderr before the report)."""
    flush()
    sys.stderr.write(f"\n{MARK} {index}\n")
    flush()
    report = load(engine, path)
    if engine == "mujoco":
        echo_log()
    flush()
    if end:
        sys.stderr.write(f"\n{END} {index}\n")
        flush()
    out.write(json.dumps(report) + "\n")
    out.flush()


def serve(engine: str, memory: str) -> int:
    """``--serve ENGINE MEMORY``: one JSON-quoted path per line on stdin, answered in turn
    (:mod:`urdflint.engines.warm`), until stdin closes; then the working folder, the
    probe's own, is removed."""
    limit_memory(int(memory))
    out = os.fdopen(os.dup(1), "w")
    os.dup2(2, 1)
    stdin = os.fdopen(os.dup(0), "r", encoding="utf-8")
    os.dup2(os.open(os.devnull, os.O_RDONLY), 0)  # the engine reads nothing of ours
    for index, line in enumerate(stdin):
        answer(engine, json.loads(line), index, out, end=True)
    folder = Path.cwd()
    if folder.name.startswith("urdflint-probe-"):
        import shutil

        os.chdir(folder.parent)
        shutil.rmtree(folder, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
