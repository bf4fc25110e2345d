"""``urdflint fix --unsafe-fixes`` on copies of the 36 corpus robots: it converges (a second
run changes nothing), no new error appears, and Pinocchio and MuJoCo (where installed) still
load what they loaded before."""

from __future__ import annotations

import json
import shutil
from collections import Counter
from pathlib import Path

import pytest

from tests.conftest import CORPUS, needs_corpus
from urdflint.cli import main
from urdflint.engine import config, linter

pytestmark = pytest.mark.slow  # every corpus robot fixed end to end

ROBOTS = sorted(p.parent for p in CORPUS.glob("*/model.urdf")) if CORPUS.is_dir() else []


def package_args(robot: Path) -> list[str]:
    mapping = robot / "package_map.json"
    if not mapping.is_file():
        return []
    found = json.loads(mapping.read_text())
    return [f"--package-path={name}={robot / folder}" for name, folder in found.items()]


def errors(path: Path, args: list[str]) -> Counter[str]:
    settings = config.Settings(
        package_paths={a.split("=")[1]: Path(a.split("=", 2)[2]) for a in args}
    )
    found = linter.lint_path(path, str(path), settings).findings
    return Counter(f.code for f in found if str(f.severity) == "error")


def mujoco_loads(path: Path, args: list[str]) -> bool | None:
    """Whether MuJoCo builds the model (its own process; None when not installed)."""
    from urdflint.engines import runner

    if not runner.installed("mujoco"):
        return None
    settings = config.Settings(
        confirm=("mujoco",),
        select=("E001", "E005"),
        package_paths={a.split("=")[1]: Path(a.split("=", 2)[2]) for a in args},
    )
    found = linter.lint_path(path, str(path), settings).findings
    return not any(f.code in ("E001", "E005") for f in found)


def builds(path: Path) -> bool:
    pinocchio = pytest.importorskip("pinocchio")
    try:
        pinocchio.buildModelFromUrdf(str(path))
    except Exception:
        return False
    return True


@needs_corpus
@pytest.mark.parametrize("robot", ROBOTS, ids=lambda p: p.name)
def test_fix_converges_and_adds_no_error(robot: Path, tmp_path: Path, capsys) -> None:
    path = tmp_path / "model.urdf"
    shutil.copyfile(robot / "model.urdf", path)
    args = package_args(robot)
    before = errors(path, args)
    built = builds(path)
    loaded = mujoco_loads(path, args)
    main(["fix", "--isolated", "--unsafe-fixes", "--exit-zero", *args, str(path)])
    once = path.read_bytes()
    main(["fix", "--isolated", "--unsafe-fixes", "--exit-zero", *args, str(path)])
    capsys.readouterr()
    assert path.read_bytes() == once, "a second run changed the file"
    after = errors(path, args)
    new = {code for code in after if after[code] > before.get(code, 0)}
    assert not new, f"new errors after fixing: {sorted(new)}"
    if built:
        assert builds(path), "Pinocchio built the original but not the fixed model"
    if loaded:
        assert mujoco_loads(path, args), "MuJoCo loaded the original but not the fixed model"


@needs_corpus
def test_write_meshes_gives_every_mesh_only_link_its_hull(tmp_path: Path, capsys) -> None:
    """eve_r3 draws 19 links with OBJ meshes and gives them no collision: a copy of the whole
    robot (its meshes too) is fixed with --write-meshes; the corpus itself is never written."""
    robot = tmp_path / "eve_r3"
    shutil.copytree(CORPUS / "eve_r3", robot)
    path = robot / "model.urdf"
    args = package_args(robot)
    before = errors(path, args)
    fix = ["fix", "--isolated", "--unsafe-fixes", "--write-meshes", "--exit-zero", *args]
    main([*fix, str(path)])
    once = path.read_bytes(), sorted(p.name for p in robot.rglob("*_hull.obj"))
    main([*fix, str(path)])
    capsys.readouterr()
    assert (path.read_bytes(), sorted(p.name for p in robot.rglob("*_hull.obj"))) == once
    assert len(once[1]) == 13  # left and right links share a mesh, and its hull
    assert path.read_text().count("_hull.obj") == 19
    after = errors(path, args)
    assert not {code for code in after if after[code] > before.get(code, 0)}
    settings = config.Settings(
        select=("C001", "C004", "C005", "C006"),
        package_paths={a.split("=")[1]: Path(a.split("=", 2)[2]) for a in args},
    )
    left = linter.lint_path(path, str(path), settings).findings
    assert not [f for f in left if f.code == "C001" and str(f.severity) == "warning"]
    assert not [f for f in left if "_hull.obj" in f.message]  # every hull resolves and reads
