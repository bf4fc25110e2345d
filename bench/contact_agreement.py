#!/usr/bin/env python3
"""C013's pairs per target against each engine's contacts at rest.

    .venv/bin/python bench/contact_agreement.py [URDF or xacro ...] [--engines mujoco,drake,pybullet]
                                                [--json FILE] [--jobs N]

Without files: the C013 fixtures and the corpus robots (``../shared/corpus``). Each file is
written as the engines read it (``urdflint.engines.runner.write_model``: meshes absolute;
packages from a ``package_map.json`` beside a file, else found as ``urdflint check`` finds
them) and loaded in each engine, in its own process, at the zero configuration:

- MuJoCo: ``mj_forward`` at ``qpos0``, ``data.contact`` (bodies of ``geom1``/``geom2``, ``dist``);
- Drake: a ``MultibodyPlant`` with a ``SceneGraph``, ``ComputePointPairPenetration()`` at the
  default context; collision meshes that are not OBJ are converted to OBJ first (Drake 1.51
  refuses STL and Collada collision meshes, C009);
- PyBullet: ``loadURDF(useFixedBase=True, flags=URDF_USE_SELF_COLLISION)``,
  ``performCollisionDetection``, ``getContactPoints`` (without the flag it has no contact).

C013's prediction for a target is the set of pairs whose finding (``--target all``) has an
effect on it; PyBullet's is its info effect (self-collision on). MuJoCo names the bodies it
built: a link fixed to its parent is fused into it, a root's body is ``world``; predictions
are mapped to those names. Scoring: recall counts the engine's pairs deeper than 1.5 mm that
C013 predicted; precision the predicted pairs the engine has deeper than 0.5 mm (a margin for
depths measured differently). PyBullet's recall counts its pairs 2 mm deeper still: it
inflates each mesh hull by a 1 mm collision margin (observed: its depths exceed Drake's by
1-2 mm on the same hulls). PyBullet pairs of links welded together are counted apart: C013
leaves them out by design (no motion follows).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from collections import defaultdict
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

HI, LO = -0.0015, -0.0005  # an engine's pair must be found / a prediction must be confirmed
MARGIN = {"pybullet": 0.002}  # PyBullet inflates each mesh hull by 1 mm (its URDF margin)
TIMEOUT = 180.0
PACKAGE_MAP = "package_map.json"
DRAKE_MESHES = (".obj", ".vtk", ".gltf")


# --- the engines, each in its own process (``--probe ENGINE FILE``) ------------------------


def _mujoco(path: str) -> dict[str, float]:
    import mujoco as mj

    model = mj.MjModel.from_xml_path(path)
    data = mj.MjData(model)
    mj.mj_forward(model, data)
    found: dict[str, float] = {}
    for contact in data.contact[: data.ncon]:
        ids = (int(model.geom_bodyid[g]) for g in (contact.geom1, contact.geom2))
        names = [mj.mj_id2name(model, mj.mjtObj.mjOBJ_BODY, i) or "world" for i in ids]
        _deepest(found, names, float(contact.dist))
    return found


def _drake(path: str) -> dict[str, float]:
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
    from pydrake.systems.framework import DiagramBuilder

    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder, 0.0)
    Parser(plant).AddModels(file_name=Path(path))
    plant.Finalize()
    diagram = builder.Build()
    context = scene_graph.GetMyContextFromRoot(diagram.CreateDefaultContext())
    query = scene_graph.get_query_output_port().Eval(context)
    inspector = query.inspector()
    found: dict[str, float] = {}
    for pair in query.ComputePointPairPenetration():
        ids = (pair.id_A, pair.id_B)
        names = [plant.GetBodyFromFrameId(inspector.GetFrameId(g)).name() for g in ids]
        _deepest(found, names, -float(pair.depth))
    return found


def _pybullet(path: str) -> dict[str, float]:
    import pybullet as pb

    client = pb.connect(pb.DIRECT)
    try:
        robot = pb.loadURDF(path, useFixedBase=True, flags=pb.URDF_USE_SELF_COLLISION,
                            physicsClientId=client)  # fmt: skip
        names = {-1: pb.getBodyInfo(robot, physicsClientId=client)[0].decode()}
        for index in range(pb.getNumJoints(robot, physicsClientId=client)):
            names[index] = pb.getJointInfo(robot, index, physicsClientId=client)[12].decode()
        pb.performCollisionDetection(physicsClientId=client)
        found: dict[str, float] = {}
        for point in pb.getContactPoints(robot, robot, physicsClientId=client):
            _deepest(found, [names[point[3]], names[point[4]]], float(point[8]))
        return found
    finally:
        pb.disconnect(client)


PROBES = {"mujoco": _mujoco, "drake": _drake, "pybullet": _pybullet}


def _deepest(found: dict[str, float], names: list[str], distance: float) -> None:
    key = "|".join(sorted(names))
    found[key] = min(found.get(key, 1.0), distance)


def probe_main(engine: str, path: str) -> int:
    """Print ``@@contacts {json}`` on its own line (engines print to stdout too)."""
    try:
        result: dict[str, Any] = {"ok": True, "pairs": PROBES[engine](path)}
    except Exception as exc:  # the engine refused the model
        result = {"ok": False, "error": f"{type(exc).__name__}: {exc}"[:300]}
    sys.stdout.flush()
    sys.stdout.write("\n@@contacts " + json.dumps(result) + "\n")
    return 0


def contacts(engine: str, path: Path) -> dict[str, Any]:
    command = [sys.executable, __file__, "--probe", engine, str(path)]
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=TIMEOUT,
                              cwd=path.parent)  # fmt: skip
    except subprocess.TimeoutExpired:
        return {"ok": False, "error": "timed out"}
    for line in done.stdout.splitlines():
        if line.startswith("@@contacts "):
            return dict(json.loads(line.split(" ", 1)[1]))
    return {"ok": False, "error": f"died ({done.returncode}): {done.stderr[-200:]}"}


# --- the model and C013's prediction ------------------------------------------------------


def settings_for(path: Path) -> Any:
    from urdflint.engine import config
    from urdflint.model import targets

    mapping = path.parent / PACKAGE_MAP
    table = json.loads(mapping.read_text()) if mapping.is_file() else {}
    packages = {name: (path.parent / folder).resolve() for name, folder in table.items()}
    return config.Settings(package_paths=packages, targets=tuple(targets.TARGETS))


def predicted(doc: Any, min_depth: float = 0.001) -> dict[str, set[str]]:
    """Engine -> the pairs C013 reports with an effect on its target (engine's names)."""
    from urdflint.rules.geometry.c013_self_collision import Pairs

    from urdflint.sources.self_collision import overlaps

    pairs = Pairs(doc)
    found: dict[str, set[str]] = defaultdict(set)
    for overlap in overlaps(doc, min_depth, pairs.wanted)[0]:
        a, b = overlap.first, overlap.second
        effects = pairs.effects(a, b, overlap.mesh)
        if "mujoco" in effects:
            bodies = sorted(pairs.filters.mujoco_body(link) for link in (a, b))
            found["mujoco"].add("|".join(bodies))
        for engine in ("drake", "pybullet"):
            if engine in effects:
                found[engine].add("|".join(sorted((a, b))))
    return found


def welded(doc: Any) -> set[str]:
    """Link pairs of one rigid body (PyBullet collides those that are not parent and child)."""
    from urdflint.sources.contact_filters import bodies

    body = bodies(doc)
    names = sorted(body)
    return {f"{a}|{b}" for i, a in enumerate(names) for b in names[i + 1 :] if body[a] == body[b]}


def drake_copy(model: Path) -> Path:
    """The model with every collision mesh Drake cannot read converted to OBJ beside it."""
    import trimesh
    from lxml import etree

    tree = etree.parse(str(model))
    for index, mesh in enumerate(tree.iterfind(".//collision/geometry/mesh")):
        name = mesh.get("filename") or ""
        if name.lower().endswith(DRAKE_MESHES) or not Path(name).is_file():
            continue
        out = model.parent / f"drake_mesh_{index}.obj"
        trimesh.load(name, force="mesh").export(str(out))
        mesh.set("filename", str(out))
    out = model.with_name("drake_" + model.name)
    tree.write(str(out))
    return out


def check_file(path: Path, engines: list[str]) -> dict[str, Any]:
    from urdflint.engine import linter
    from urdflint.engines import runner

    doc = linter.load(path, str(path), settings_for(path))
    doc.targets = frozenset(settings_for(path).targets)
    result: dict[str, Any] = {"predicted": {k: sorted(v) for k, v in predicted(doc).items()},
                              "welded": sorted(welded(doc)), "engines": {}}  # fmt: skip
    with tempfile.TemporaryDirectory(prefix="urdflint-contacts-") as folder:
        model = runner.write_model(doc, Path(folder))
        for engine in engines:
            loaded = drake_copy(model) if engine == "drake" else model
            result["engines"][engine] = contacts(engine, loaded)
    return result


# --- scoring ------------------------------------------------------------------------------


def score(results: dict[str, dict[str, Any]], engines: list[str]) -> list[str]:
    lines = []
    for engine in engines:
        found = missed = confirmed = guessed = apart = refused = 0
        notes = []
        for path, result in results.items():
            seen = result["engines"].get(engine) or {}
            if not seen.get("ok"):
                refused += 1
                continue
            pairs = seen["pairs"]
            guess = set(result["predicted"].get(engine, ()))
            truth = {k for k, v in pairs.items() if v < HI - MARGIN.get(engine, 0.0)}
            if engine == "pybullet":
                apart += len(truth & set(result["welded"]))
                truth -= set(result["welded"])
            loose = {k for k, v in pairs.items() if v < LO}
            found, missed = found + len(truth & guess), missed + len(truth - guess)
            guessed, confirmed = guessed + len(guess), confirmed + len(guess & loose)
            for pair in sorted(truth - guess):
                notes.append(f"    missed {Path(path).parent.name}/{Path(path).name}: {pair}")
            for pair in sorted(guess - loose):
                notes.append(f"    extra  {Path(path).parent.name}/{Path(path).name}: {pair}")
        tail = f", welded pairs left out {apart}" if engine == "pybullet" else ""
        lines.append(f"{engine}: recall {_share(found, found + missed)}, precision "
                     f"{_share(confirmed, guessed)} ({refused} files refused{tail})")  # fmt: skip
        lines += notes
    return lines


def _share(hits: int, total: int) -> str:
    return f"{hits}/{total} = {hits / total:.0%}" if total else "0/0"


def default_files() -> list[Path]:
    from tests.conftest import FIXTURES, corpus_models

    return [*sorted((FIXTURES / "rules" / "C013").glob("*.urdf")), *corpus_models()]


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if args[:1] == ["--probe"]:
        return probe_main(args[1], args[2])
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("files", type=Path, nargs="*")
    parser.add_argument("--engines", default="mujoco,drake,pybullet")
    parser.add_argument("--json", type=Path, help="write the contacts and predictions here")
    parser.add_argument("--jobs", type=int, default=4)
    options = parser.parse_args(args)
    engines = options.engines.split(",")
    files = [p.resolve() for p in options.files] or default_files()
    with ProcessPoolExecutor(max_workers=options.jobs) as pool:
        done = list(pool.map(check_file, files, [engines] * len(files)))
    results = {str(p): r for p, r in zip(files, done, strict=True)}
    if options.json:
        options.json.write_text(json.dumps(results, indent=1) + "\n")
    print(f"{len(files)} files")
    print("\n".join(score(results, engines)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
