"""Load one URDF in one simulation engine and print what it built, as one JSON line.

``python -m urdflint.engines.probe ENGINE URDF`` is run by :mod:`urdflint.engines.runner`
in its own process (engines abort or crash on bad input). The engine's own output, C level
included, is moved to stderr, where the parent reads it; stdout carries only the JSON line
``{"engine", "ok", "error", "bodies", "joints"}``. ``bodies`` are the link names the engine
kept (MuJoCo bodies, PyBullet links, Drake bodies, Pinocchio ``BODY`` frames).
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path
from typing import Any


def mujoco(path: str) -> tuple[list[str], list[str]]:
    import mujoco as mj

    model = mj.MjModel.from_xml_path(path)
    bodies = [mj.mj_id2name(model, mj.mjtObj.mjOBJ_BODY, i) or "" for i in range(model.nbody)]
    joints = [mj.mj_id2name(model, mj.mjtObj.mjOBJ_JOINT, i) or "" for i in range(model.njnt)]
    return bodies, joints


def pybullet(path: str) -> tuple[list[str], list[str]]:
    import pybullet as pb

    client = pb.connect(pb.DIRECT)
    try:
        robot = pb.loadURDF(path, useFixedBase=True, physicsClientId=client)
        bodies = [pb.getBodyInfo(robot, physicsClientId=client)[0].decode()]
        joints = []
        for index in range(pb.getNumJoints(robot, physicsClientId=client)):
            info = pb.getJointInfo(robot, index, physicsClientId=client)
            joints.append(info[1].decode())
            bodies.append(info[12].decode())
        return bodies, joints
    finally:
        pb.disconnect(client)


def drake(path: str) -> tuple[list[str], list[str]]:
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant
    from pydrake.multibody.tree import BodyIndex, JointIndex

    plant = MultibodyPlant(0.0)
    Parser(plant).AddModels(file_name=Path(path))
    bodies = [plant.get_body(BodyIndex(i)).name() for i in range(1, plant.num_bodies())]
    joints = [plant.get_joint(JointIndex(i)).name() for i in range(plant.num_joints())]
    return bodies, joints


def pinocchio(path: str) -> tuple[list[str], list[str]]:
    import pinocchio as pin

    model = pin.buildModelFromUrdf(path)
    bodies = [f.name for f in model.frames if f.type == pin.FrameType.BODY]
    return bodies, [str(name) for name in list(model.names)[1:]]


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


def main(argv: list[str]) -> int:
    engine, path, *rest = argv
    limit_memory(int(rest[0]) if rest else 0)
    out = os.fdopen(os.dup(1), "w")
    os.dup2(2, 1)  # everything the engine prints, C level included, goes to stderr
    report: dict[str, Any] = {"engine": engine, "ok": False, "error": None,
                              "bodies": [], "joints": []}  # fmt: skip
    try:
        report["bodies"], report["joints"] = LOADERS[engine](path)
        report["ok"] = True
    except Exception as exc:  # the engine refused the model: its message is the finding
        report["error"] = f"{type(exc).__name__}: {exc}"
    sys.stdout.flush()
    out.write(json.dumps(report) + "\n")
    out.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
