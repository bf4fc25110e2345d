"""``urdflint fix --unsafe-fixes --write-meshes``: C001's collision for a mesh visual is the
mesh's convex hull, written as ``<stem>_hull.obj`` beside it (never over another file), and
every engine installed here loads the result."""

from __future__ import annotations

import importlib.util
import shutil
from pathlib import Path

import pytest

from tests.conftest import FIXTURES
from urdflint.cli import main
from urdflint.engine import config, linter

pytest.importorskip("trimesh")
import numpy as np
import trimesh

FOLDER = FIXTURES / "rules" / "C001"
FIX = ["fix", "--isolated", "--select", "C001", "--exit-zero", "--unsafe-fixes"]


@pytest.fixture
def robot(tmp_path: Path) -> Path:
    shutil.copyfile(FOLDER / "bad_mesh.urdf", tmp_path / "gripper.urdf")
    shutil.copytree(FOLDER / "meshes", tmp_path / "meshes")
    return tmp_path / "gripper.urdf"


def c001(path: Path, write_meshes: bool = False) -> list:
    options = {"C001": {"write_meshes": True}} if write_meshes else {}
    settings = config.Settings(select=("C001",), rule_options=options)
    return [f for f in linter.lint_path(path, str(path), settings).findings if f.code == "C001"]


def test_the_hull_is_written_beside_the_mesh_and_the_collision_uses_it(robot: Path, capsys) -> None:
    assert main([*FIX, "--write-meshes", str(robot)]) == 0
    assert robot.read_bytes() == (FOLDER / "fixed" / "bad_mesh.urdf").read_bytes()
    written = robot.parent / "meshes" / "bracket_hull.obj"
    text = written.read_text()
    assert text.startswith("# convex hull of bracket.stl, written by urdflint fix --write-meshes")
    hull = trimesh.load(written, force="mesh")
    source = trimesh.load(robot.parent / "meshes" / "bracket.stl", force="mesh")
    assert hull.is_watertight and hull.is_winding_consistent and hull.volume > 0
    expected = source.convex_hull
    assert hull.volume == pytest.approx(expected.volume, rel=1e-6)
    assert sorted(map(tuple, np.round(hull.vertices, 9))) == sorted(
        map(tuple, np.round(expected.vertices, 9))
    )
    assert c001(robot) == []  # fixed, and the second run changes nothing
    before = robot.read_bytes(), text
    main([*FIX, "--write-meshes", str(robot)])
    assert (robot.read_bytes(), written.read_text()) == before


def test_the_run_says_which_file_it_wrote(robot: Path, capsys) -> None:
    capsys.readouterr()
    main([*FIX, "--write-meshes", str(robot)])
    err = capsys.readouterr().err
    assert "fixed 1 finding in 1 file; wrote " in err
    assert err.rstrip().endswith(str(robot.parent / "meshes" / "bracket_hull.obj"))


def test_without_the_option_nothing_is_written_and_the_finding_says_why(
    robot: Path, capsys
) -> None:
    before = robot.read_bytes()
    main([*FIX, str(robot)])
    assert robot.read_bytes() == before
    assert sorted(p.name for p in (robot.parent / "meshes").iterdir()) == ["bracket.stl"]
    (finding,) = c001(robot)
    assert finding.line == 22 and finding.autofix is not None
    assert finding.autofix.applicability == "unsafe" and not finding.autofix.edits
    assert finding.autofix.unavailable == "the visual is a mesh: --write-meshes writes its hull"


def test_the_diff_shows_the_new_file_and_writes_nothing(robot: Path, capsys) -> None:
    capsys.readouterr()
    assert main(["fix", "--isolated", "--select", "C001", "--unsafe-fixes", "--write-meshes",
                 "--diff", str(robot)]) == 1  # fmt: skip
    out = capsys.readouterr().out
    hull = robot.parent / "meshes" / "bracket_hull.obj"
    assert f"--- /dev/null\n+++ {hull}\n@@ -0,0 +1," in out
    assert '+        <mesh filename="meshes/bracket_hull.obj" scale="1 1 1"/>' in out
    assert not hull.exists()


def test_another_file_with_the_hull_name_is_never_overwritten(robot: Path) -> None:
    hull = robot.parent / "meshes" / "bracket_hull.obj"
    hull.write_text("# the user's own file\n")
    (finding,) = c001(robot, write_meshes=True)
    assert finding.autofix is not None and not finding.autofix.edits
    assert finding.autofix.unavailable == f"{hull} exists with other content; it is not overwritten"
    before = robot.read_bytes()
    main([*FIX, "--write-meshes", str(robot)])
    assert robot.read_bytes() == before and hull.read_text() == "# the user's own file\n"


def test_one_hull_serves_every_link_that_draws_the_mesh(robot: Path) -> None:
    text = robot.read_text()
    second = text[text.index('  <joint name="finger_joint"') : text.index("</robot>")]
    second = second.replace('"finger', '"finger2').replace('link="finger"', 'link="finger2"')
    second = second.replace('scale="1 1 1"', 'scale="-1 1 1"')  # the mirrored finger
    robot.write_text(text.replace("</robot>", second + "</robot>"))
    main([*FIX, "--write-meshes", str(robot)])
    fixed = robot.read_text()
    assert fixed.count('<mesh filename="meshes/bracket_hull.obj" scale="1 1 1"/>') == 1
    assert fixed.count('<mesh filename="meshes/bracket_hull.obj" scale="-1 1 1"/>') == 1
    assert sorted(p.name for p in (robot.parent / "meshes").iterdir()) == [
        "bracket.stl",
        "bracket_hull.obj",
    ]
    assert c001(robot) == []


def test_a_missing_or_flat_mesh_gets_no_fix(robot: Path) -> None:
    flat = trimesh.Trimesh(vertices=[[0, 0, 0], [1, 0, 0], [0, 1, 0]], faces=[[0, 1, 2]])
    (robot.parent / "meshes" / "flat.stl").write_bytes(trimesh.exchange.stl.export_stl(flat))
    robot.write_text(robot.read_text().replace("bracket.stl", "flat.stl"))
    (finding,) = c001(robot, write_meshes=True)
    assert finding.autofix is not None and finding.autofix.unavailable == (
        "the mesh 'meshes/flat.stl' is flat or degenerate: it has no convex hull with a volume"
    )
    robot.write_text(robot.read_text().replace("flat.stl", "gone.stl"))
    (finding,) = c001(robot, write_meshes=True)
    assert finding.autofix is not None
    assert finding.autofix.unavailable == "the mesh 'meshes/gone.stl' was not found"


@pytest.mark.skipif(importlib.util.find_spec("mujoco") is None, reason="MuJoCo not installed")
def test_mujoco_loads_the_written_hull(robot: Path) -> None:
    import mujoco

    main([*FIX, "--write-meshes", str(robot)])
    text = robot.read_text().replace(
        '<robot name="gripper">',
        '<robot name="gripper"><mujoco><compiler discardvisual="true" '
        f'meshdir="{robot.parent}"/></mujoco>',
    )
    model = mujoco.MjModel.from_xml_string(text)
    assert model.ngeom == 2  # the palm's box and the finger's hull; the visual is discarded
    assert model.nmesh == 1


def test_the_service_refuses_the_option() -> None:
    pytest.importorskip("fastapi")
    from urdflint.server.options import OptionError, parse

    config_text = '{"rules": {"C001": {"write_meshes": true}}}'
    with pytest.raises(OptionError, match=r"rules\.C001\.write_meshes' is not accepted"):
        parse({"config": [config_text]}, fix=True)


def test_a_collada_unit_is_baked_into_the_hull(robot: Path) -> None:
    pytest.importorskip("collada")
    box = trimesh.creation.box((4.0, 6.0, 2.0))  # centimetres
    text = trimesh.exchange.dae.export_collada(box).decode()
    text = text.replace("<asset>", '<asset>\n    <unit meter="0.01" name="centimeter"/>', 1)
    (robot.parent / "meshes" / "cover.dae").write_text(text)
    robot.write_text(robot.read_text().replace("bracket.stl", "cover.dae"))
    main([*FIX, "--write-meshes", str(robot)])
    assert '<mesh filename="meshes/cover_hull.obj" scale="1 1 1"/>' in robot.read_text()
    hull = trimesh.load(robot.parent / "meshes" / "cover_hull.obj", force="mesh")
    assert hull.extents == pytest.approx([0.04, 0.06, 0.02])  # metres, as Gazebo reads the dae
