"""The verdict does not depend on where the repository sits (issue 24, items 6 and 7).

A file checked alone (as pre-commit and the editor do) inside a git repository that holds
another package of the same name gets the findings it gets outside any repository: the
package that holds the file always wins, then the package of that name nearest to it.
Two packages as near are C017. ``--show-packages`` says which folder each name resolved
to, and why, without changing the findings or the exit code.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import CORPUS, FIXTURES, ROOT, needs_corpus

pytest.importorskip("xacro")
pytestmark = pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")

UR_ARGS = ("--xacro-arg", "name:=ur", "--xacro-arg", "ur_type:=ur5e")
NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
PARTS = f"""<robot {NS}>
  <xacro:macro name="part" params="name">
    <link name="${{name}}"><inertial><mass value="1"/>
      <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  </xacro:macro>
</robot>
"""


def manifest(folder: Path, name: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "package.xml").write_text(f"<package format='3'><name>{name}</name></package>\n")
    return folder


def run(top: Path, *args: str) -> subprocess.CompletedProcess[str]:
    env = {"PATH": os.environ.get("PATH", "/usr/bin:/bin"), "PYTHONPATH": str(ROOT),
           "URDFLINT_CACHE_DIR": os.environ["URDFLINT_CACHE_DIR"]}  # fmt: skip
    return subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--isolated", *args],
        capture_output=True, text=True, cwd=top, env=env, check=False,
    )  # fmt: skip


def findings(top: Path, *args: str) -> list[tuple[str, int, str, str]]:
    proc = run(top, "--format", "json", *args)
    found = json.loads(proc.stdout)["findings"]
    return [(f["path"], f["line"], f["code"], f["message"].replace(str(top), "TOP")) for f in found]


def placed(tmp_path: Path, build) -> tuple[Path, Path]:
    """The same tree twice: ``in/`` a git work tree, ``out/`` outside any repository."""
    inside, outside = tmp_path / "in", tmp_path / "out"
    build(inside)
    build(outside)
    subprocess.run(["git", "init", "-q", str(inside)], check=True)
    return inside, outside


# -- the reproduction ----------------------------------------------------------------


def desc_repository(top: Path) -> None:
    """``a/desc`` and ``0/desc`` both named ``desc``; a robot in ``a/desc`` uses $(find desc)."""
    for side in ("a", "0"):
        manifest(top / side / "desc", "desc")
    (top / "a/desc/urdf").mkdir()
    (top / "a/desc/urdf/parts.xacro").write_text(PARTS)
    (top / "a/desc/urdf/robot.urdf.xacro").write_text(
        f'<robot name="r" {NS}>\n'
        '  <xacro:include filename="$(find desc)/urdf/parts.xacro"/>\n'
        '  <xacro:part name="base"/>\n</robot>\n'
    )


def test_the_package_holding_the_file_wins_inside_a_repository(tmp_path: Path) -> None:
    inside, outside = placed(tmp_path, desc_repository)
    robot = "a/desc/urdf/robot.urdf.xacro"
    here = findings(inside, "--show-info", robot)
    assert here == findings(outside, "--show-info", robot)
    assert [code for _, _, code, _ in here] == ["I011"]  # no X010 "cannot read 0/desc/..."
    assert findings(inside, "--show-info", "a") == here  # the folder run agrees


def test_show_packages_says_why_and_changes_nothing(tmp_path: Path) -> None:
    inside, _ = placed(tmp_path, desc_repository)
    robot = "a/desc/urdf/robot.urdf.xacro"
    plain, shown = run(inside, robot), run(inside, "--show-packages", robot)
    assert (shown.returncode, shown.stdout) == (plain.returncode, plain.stdout)
    listing = shown.stderr.splitlines()
    assert listing[0].startswith("urdflint: packages for 1 file(s), in this order: --package-path")
    assert listing[1:] == [
        "  desc: a/desc (the package holding the file)",
        "    also named desc, not used: 0/desc",
    ]


# -- the UR ROS 2 description beside its ROS 1 sibling ---------------------------------------


def ur_workspace(top: Path) -> None:
    """src/ros1/universal_robot/ur_description (ROS 1, only its manifest) is met first."""
    shutil.copytree(FIXTURES / "placement/universal_robot", top / "src/ros1/universal_robot")
    shutil.copytree(
        FIXTURES / "packages/ur_description", top / "src/ros2/Universal_Robots_ROS2_Description"
    )


def test_ur_ros2_description_is_not_resolved_to_its_ros1_sibling(tmp_path: Path) -> None:
    inside, outside = placed(tmp_path, ur_workspace)
    entry = "src/ros2/Universal_Robots_ROS2_Description/urdf/ur.urdf.xacro"
    here = findings(inside, *UR_ARGS, "--select", "X,C017", entry)
    assert here == findings(outside, *UR_ARGS, "--select", "X,C017", entry) == []
    listing = run(inside, *UR_ARGS, "--show-packages", entry).stderr
    assert (
        "  ur_description: src/ros2/Universal_Robots_ROS2_Description "
        "(the package holding the file)\n"
        "    also named ur_description, not used: src/ros1/universal_robot/ur_description\n"
    ) in listing


# -- a corpus robot in its package, beside a same-named package without its meshes ------------


@needs_corpus
def test_a_corpus_robot_gets_the_same_findings_inside_and_outside(tmp_path: Path) -> None:
    """jackal's meshes in ``robots/jackal/jackal_description`` and an empty
    ``0_sibling/jackal_description``: before, all 7 meshes were C004 errors inside a
    repository (the sibling was met first) and none outside."""

    def build(top: Path) -> None:
        package = top / "robots/jackal/jackal_description"
        shutil.copytree(CORPUS / "jackal/meshes/jackal_description", package)
        manifest(package, "jackal_description")
        (package / "urdf").mkdir()
        shutil.copy(CORPUS / "jackal/model.urdf", package / "urdf/model.urdf")
        manifest(top / "0_sibling/jackal_description", "jackal_description")

    inside, outside = placed(tmp_path, build)
    model = "robots/jackal/jackal_description/urdf/model.urdf"
    here = findings(inside, "--show-info", "--select", "C", model)
    assert here == findings(outside, "--show-info", "--select", "C", model)
    assert "C004" not in {code for _, _, code, _ in here}


# -- the nearest package; two as near are C017 ------------------------------------------------


def test_each_robot_gets_the_nearest_of_same_named_packages(tmp_path: Path) -> None:
    """As hyq, solo12 and tiago of the corpus each carry an ``example-robot-data``."""
    for robot in ("hyq", "solo12"):
        data = manifest(tmp_path / "robots" / robot / "meshes/example-robot-data", "erd")
        (data / "urdf").mkdir()
        (data / "urdf/parts.xacro").write_text(PARTS.replace('"part"', f'"{robot}_part"'))
        (tmp_path / "robots" / robot / "robot.urdf.xacro").write_text(
            f'<robot name="{robot}" {NS}>\n'
            '  <xacro:include filename="$(find erd)/urdf/parts.xacro"/>\n'
            f'  <xacro:{robot}_part name="base"/>\n</robot>\n'
        )
    subprocess.run(["git", "init", "-q", str(tmp_path)], check=True)
    assert findings(tmp_path, "--select", "X,C017", "robots") == []


def test_two_packages_as_near_are_one_warning_naming_both(tmp_path: Path) -> None:
    for side in ("a", "b"):
        (manifest(tmp_path / "src" / side / "desc", "desc") / "urdf").mkdir()
        (tmp_path / "src" / side / "desc/urdf/parts.xacro").write_text(PARTS)
    bot = manifest(tmp_path / "src/bot", "bot") / "bot.urdf.xacro"
    bot.write_text(
        f'<robot name="bot" {NS}>\n'
        '  <xacro:include filename="$(find desc)/urdf/parts.xacro"/>\n'
        '  <xacro:part name="base"/>\n</robot>\n'
    )
    subprocess.run(["git", "init", "-q", str(tmp_path)], check=True)
    [(path, line, code, message)] = findings(tmp_path, "--select", "C017", "src/bot")
    assert (path, line, code) == ("src/bot/bot.urdf.xacro", 2, "C017")
    assert message == (
        "package 'desc' is at 2 places as near to this file: src/a/desc (used) and src/b/desc;"
        " colcon and catkin refuse a workspace with two packages of one name"
    )
    listing = run(tmp_path, "--show-packages", "src/bot").stderr
    assert "  desc: src/a/desc (workspace, nearest of 2; as near: src/b/desc (C017))\n" in listing
