"""Description packages as users have them: a workspace of packages, entry files and macro
libraries, found without flags; findings inside macros with their call chain in every format."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from tests.conftest import FIXTURES, ROOT
from urdflint.sources import discovery, workspace

pytest.importorskip("xacro")

NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
PACKAGES = FIXTURES / "packages"


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(textwrap.dedent(text).lstrip(), encoding="utf-8")
    return path


def package(folder: Path, name: str) -> Path:
    write(folder / "package.xml", f"<package format='3'><name>{name}</name></package>\n")
    return folder


FINGER = f"""
<robot {NS}>
  <xacro:macro name="finger" params="prefix parent mass">
    <link name="${{prefix}}finger">
      <inertial>
        <mass value="${{mass}}"/>
        <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
      </inertial>
    </link>
    <joint name="${{prefix}}joint" type="revolute">
      <origin xyz="0 0 0.1"/>
      <parent link="${{parent}}"/>
      <child link="${{prefix}}finger"/>
      <axis xyz="0 0 0"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/>
    </joint>
  </xacro:macro>
</robot>
"""

GRIPPER = f"""
<robot {NS}>
  <xacro:include filename="$(find finger_description)/urdf/finger.xacro"/>
  <xacro:macro name="gripper" params="parent">
    <xacro:finger prefix="left_" parent="${{parent}}" mass="0.1"/>
    <xacro:finger prefix="right_" parent="${{parent}}" mass="0.1"/>
  </xacro:macro>
</robot>
"""

ROBOT = f"""
<robot name="bot" {NS}>
  <xacro:include filename="$(find gripper_description)/urdf/gripper.xacro"/>
  <link name="base">
    <inertial>
      <mass value="1"/>
      <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/>
    </inertial>
  </link>
  <xacro:gripper parent="base"/>
</robot>
"""


@pytest.fixture
def ws(tmp_path: Path) -> Path:
    """src/ with three packages: a finger macro, a gripper macro using it twice, a robot."""
    src = tmp_path / "src"
    write(package(src / "finger_description", "finger_description") / "urdf/finger.xacro", FINGER)
    write(
        package(src / "gripper_description", "gripper_description") / "urdf/gripper.xacro", GRIPPER
    )
    bot = package(src / "bot_description", "bot_description")
    write(bot / "urdf/bot.urdf.xacro", ROBOT)
    write(bot / "urdf/bot_alias.urdf.xacro", ROBOT.replace('name="bot"', 'name="bot2"'))
    write(bot / "urdf/materials.urdf.xacro", f'<robot {NS}><material name="red"/></robot>\n')
    return src


def run_cli(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    env = {"PATH": os.environ.get("PATH", "/usr/bin:/bin"), "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--isolated", *args],
        capture_output=True, text=True, cwd=cwd, env=env, check=False,
    )  # fmt: skip


def line_of(path: Path, needle: str) -> int:
    text = path.read_text(encoding="utf-8")
    return text[: text.index(needle)].count("\n") + 1


# -- discovery ------------------------------------------------------------------------------


def test_packages_are_found_below_the_paths_without_flags(ws: Path) -> None:
    (ws / "ignored").mkdir()
    package(ws / "ignored" / "old_copy", "finger_description")
    (ws / "ignored" / "COLCON_IGNORE").write_text("")
    found = workspace.discover([ws / "bot_description" / "urdf" / "bot.urdf.xacro"])
    assert found == {
        "bot_description": ws / "bot_description",
        "finger_description": ws / "finger_description",
        "gripper_description": ws / "gripper_description",
    }


def test_a_folder_yields_entry_files_not_libraries(ws: Path) -> None:
    files, errors = discovery.collect([str(ws)], workspace.discover([ws]))
    assert errors == []
    assert [Path(f).relative_to(ws).as_posix() for f in files] == [
        "bot_description/urdf/bot.urdf.xacro",
        "bot_description/urdf/bot_alias.urdf.xacro",
    ]


def test_a_moveit_srdf_in_xacro_is_not_an_entry(tmp_path: Path) -> None:
    """An SRDF is read with its URDF by the M rules, never linted as a URDF of its own."""
    srdf = (
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="arm">\n'
        '  <xacro:arg name="prefix" default=""/>\n'
        '  <group name="arm"><chain base_link="base" tip_link="tool"/></group>\n'
        '  <disable_collisions link1="base" link2="tool" reason="Never"/>\n</robot>\n'
    )
    (tmp_path / "arm.srdf.xacro").write_text(srdf)
    (tmp_path / "arm_moveit.xacro").write_text(srdf)  # SRDF content without the suffix
    robot = (
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="arm"><link name="base"/></robot>'
    )
    (tmp_path / "arm.urdf.xacro").write_text(robot)
    files, errors = discovery.collect([str(tmp_path)], {})
    assert errors == [] and [Path(f).name for f in files] == ["arm.urdf.xacro"]


def test_entries_match_a_hand_made_list_on_real_packages() -> None:
    wanted = {e["entry"] for e in json.loads((PACKAGES / "entries.json").read_text())}
    files, _ = discovery.collect([str(PACKAGES)], workspace.discover([PACKAGES]))
    found = {Path(f).relative_to(PACKAGES).as_posix() for f in files if f.endswith(".xacro")}
    assert wanted == found  # 18 entries written down by hand, no library among the found


def test_a_library_given_alone_is_checked_through_its_entries(ws: Path) -> None:
    packages = workspace.discover([ws])
    finger = ws / "finger_description" / "urdf" / "finger.xacro"
    found = discovery.as_entries([str(finger)], packages)
    assert sorted(Path(f).resolve() for f in found) == [
        (ws / "bot_description/urdf/bot.urdf.xacro").resolve(),
        (ws / "bot_description/urdf/bot_alias.urdf.xacro").resolve(),
    ]
    lonely = write(ws / "lonely.xacro", f'<robot {NS}><xacro:macro name="m"/></robot>\n')
    assert discovery.as_entries([str(lonely)], packages) == [str(lonely)]


JACKAL = FIXTURES / "discovery" / "jackal_description"  # cut down from jackal/jackal


def test_a_placeholder_urdf_included_through_an_argument_is_not_a_robot() -> None:
    """husky.urdf.xacro includes ``$(arg urdf_extras)``, whose default is
    ``$(optenv HUSKY_URDF_EXTRAS empty.urdf)``: empty.urdf is checked through it (it got
    S011 and X003 as a robot of its own)."""
    husky = PACKAGES / "husky_description"
    files, errors = discovery.collect([str(husky)], workspace.discover([PACKAGES]))
    assert errors == [] and files == [str(husky / "urdf" / "husky.urdf.xacro")]
    empty = husky / "urdf" / "empty.urdf"
    assert discovery.fragment(empty) == "its <robot> has no name and no <link>"
    found = discovery.as_entries([str(empty)], workspace.discover([PACKAGES]))
    assert [Path(f).resolve() for f in found] == [(husky / "urdf/husky.urdf.xacro").resolve()]


def test_a_xacro_snippet_named_urdf_is_one_fragment_note() -> None:
    """jackal's custom_example.urdf (macro calls and joints for JACKAL_URDF_EXTRAS) got 16
    S003, 9 X008 and 2 X003 (with empty.urdf's) as robots; now one X011 note."""
    files, errors = discovery.collect([str(JACKAL)], workspace.discover([JACKAL]))
    assert errors == [] and [Path(f).name for f in files] == [
        "custom_example.urdf",  # nobody includes it: its note
        "jackal.urdf.xacro",  # empty.urdf: $(optenv JACKAL_URDF_EXTRAS empty.urdf)
    ]
    assert discovery.fragment(JACKAL / "urdf" / "custom_example.urdf") == (
        "its <robot> has no name and uses xacro (<xacro:camera_mount>)"
    )
    proc = run_cli("--format", "json", "--show-info", str(JACKAL), cwd=ROOT)
    assert proc.returncode == 0, proc.stderr
    report = json.loads(proc.stdout)
    assert [(Path(f["path"]).name, f["line"], f["code"], f["severity"]) for f in
            report["findings"]] == [("custom_example.urdf", 1, "X011", "info")]  # fmt: skip
    assert report["findings"][0]["message"].startswith(
        "a fragment of a robot, not checked on its own: its <robot> has no name and uses xacro"
    )
    assert report["summary"]["files"] == 2


def test_what_is_a_fragment_and_what_stays_a_robot(tmp_path: Path) -> None:
    cases = {
        "gazebo.urdf": ('<gazebo reference="a"><material>Gazebo/Red</material></gazebo>',
                        "its root element is <gazebo>, a part of a <robot>"),
        "library.urdf": (f'<robot name="l" {NS}><xacro:macro name="m"/></robot>',
                         "it only defines xacro macros and properties"),
        "sdf.urdf": ('<sdf version="1.6"><model name="m"/></sdf>', None),  # X002 says it
        "broken.urdf": ("<robot><link", None),  # X001 says it
        # an export that kept xacro: a robot (X008 says what needs expanding)
        "export.urdf": (f'<robot name="r" {NS}><xacro:property name="p" value="1"/>'
                        '<link name="a"/></robot>', None),
        "named.urdf": ('<robot name="r"/>', None),  # S011 says it
    }  # fmt: skip
    for name, (text, why) in cases.items():
        (tmp_path / name).write_text(text)
        assert discovery.fragment(tmp_path / name) == why, name


def test_an_include_through_argument_and_environment_defaults(tmp_path: Path) -> None:
    (tmp_path / "extras.urdf").write_text("<robot/>")
    (tmp_path / "more.urdf").write_text("<robot/>")
    (tmp_path / "robot.urdf.xacro").write_text(
        f'<robot name="r" {NS}>\n'
        '  <xacro:arg name="extras" default="$(optenv EXTRAS extras.urdf)"/>\n'
        '  <xacro:include filename="$(arg extras)"/>\n'
        '  <xacro:include filename="$(optenv MORE more.urdf)"/>\n'
        '  <xacro:include filename="$(optenv NOTHING)"/>\n'
        '  <link name="a"/>\n</robot>\n'
    )
    files, _ = discovery.collect([str(tmp_path)], {})
    assert [Path(f).name for f in files] == ["robot.urdf.xacro"]


def test_every_package_of_a_name_is_kept_and_the_nearest_wins(tmp_path: Path) -> None:
    from urdflint.sources.resolve import Resolver, nearest

    first = package(tmp_path / "robots" / "hyq" / "meshes" / "erd", "erd")
    second = package(tmp_path / "robots" / "solo12" / "meshes" / "erd", "erd")
    index = workspace.Packages([tmp_path])
    assert index.candidates("erd") == (first, second) and index["erd"] == first
    assert index.duplicates() == {"erd": (first, second)}
    assert nearest([first, second], tmp_path / "robots" / "solo12") == (second, ())
    assert nearest([first, second], tmp_path / "robots") == (first, (second,))
    found = Resolver(tmp_path / "robots" / "solo12", workspace=index, environ={}).lookup("erd")
    assert (found.folder, found.how, found.ties) == (second, "workspace, nearest of 2", ())


# -- one defect, one finding, with its call chain ----------------------------------------------


def test_workspace_run_reports_each_macro_defect_once_with_its_chain(ws: Path) -> None:
    proc = run_cli("--select", "J007", "--format", "json", "src", cwd=ws.parent)
    assert proc.returncode == 1, proc.stderr
    [finding] = json.loads(proc.stdout)["findings"]
    finger = ws / "finger_description" / "urdf" / "finger.xacro"
    gripper = ws / "gripper_description" / "urdf" / "gripper.xacro"
    bot = ws / "bot_description" / "urdf" / "bot.urdf.xacro"
    assert (finding["path"], finding["line"]) == (
        "src/finger_description/urdf/finger.xacro",
        line_of(finger, '<axis xyz="0 0 0"/>'),
    )
    assert finding["message"].endswith("(for joints left_joint, right_joint)")
    assert finding["trace"] == [
        {"macro": "finger", "path": "src/gripper_description/urdf/gripper.xacro",
         "line": line_of(gripper, 'prefix="left_"'), "column": 5},
        {"macro": "gripper", "path": "src/bot_description/urdf/bot.urdf.xacro",
         "line": line_of(bot, "<xacro:gripper"), "column": 3},
    ]  # fmt: skip


def test_instances_with_different_values_stay_apart(ws: Path) -> None:
    gripper = ws / "gripper_description" / "urdf" / "gripper.xacro"
    right = 'prefix="right_" parent="${parent}" mass='
    gripper.write_text(gripper.read_text().replace(right + '"0.1"', right + '"-2"'))
    bot = ws / "bot_description" / "urdf" / "bot.urdf.xacro"
    proc = run_cli("--select", "I002", "--format", "json", str(bot), cwd=ws.parent)
    [finding] = json.loads(proc.stdout)["findings"]
    assert "right_finger" in finding["message"] and "left_finger" not in finding["message"]
    assert finding["trace"][0]["line"] == line_of(gripper, 'prefix="right_"')


def test_text_github_and_sarif_carry_the_chain(ws: Path) -> None:
    bot = "src/bot_description/urdf/bot.urdf.xacro"
    text = run_cli("--select", "J007", bot, cwd=ws.parent).stdout.splitlines()
    assert text[0].startswith("src/finger_description/urdf/finger.xacro:")
    assert text[1].startswith("    in macro `finger`, called from src/gripper_description/")
    assert text[2].startswith("    in macro `gripper`, called from src/bot_description/")
    github = run_cli("--select", "J007", "--format", "github", bot, cwd=ws.parent).stdout
    assert "file=src/finger_description/urdf/finger.xacro" in github
    assert "%0Ain macro `finger`, called from src/gripper_description/urdf/gripper.xacro" in github
    sarif = json.loads(run_cli("--select", "J007", "--format", "sarif", bot, cwd=ws.parent).stdout)
    [result] = sarif["runs"][0]["results"]
    uris = [r["physicalLocation"]["artifactLocation"]["uri"] for r in result["relatedLocations"]]
    assert uris[0].endswith("bot_description/urdf/bot.urdf.xacro")  # outermost call first
    assert uris[1].endswith("gripper_description/urdf/gripper.xacro")
    steps = result["codeFlows"][0]["threadFlows"][0]["locations"]
    assert len(steps) == 3 and steps[-1]["location"]["message"]["text"] == result["message"]["text"]


# -- arguments ------------------------------------------------------------------------------


def test_a_missing_argument_is_one_finding_that_says_how_to_pass_it(ws: Path) -> None:
    bot = ws / "bot_description" / "urdf" / "bot.urdf.xacro"
    bot.write_text(bot.read_text().replace('name="bot"', 'name="$(arg robot_name)"'))
    proc = run_cli("--select", "X010", str(bot), cwd=ws.parent)
    assert proc.returncode == 1
    assert "xacro argument 'robot_name' has no value" in proc.stdout
    assert "--xacro-arg robot_name:=VALUE" in proc.stdout
    config = ws.parent / "urdflint.toml"
    config.write_text(
        '[per-file-xacro-args]\n"src/bot_description/urdf/bot*.xacro" = { robot_name = "b" }\n'
    )
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--select", "X010", str(bot)],
        capture_output=True, text=True, cwd=ws.parent, check=False,
        env={"PATH": os.environ.get("PATH", ""), "PYTHONPATH": str(ROOT)},
    )  # fmt: skip
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_per_file_arguments_apply_by_glob_and_the_command_line_wins(tmp_path: Path) -> None:
    from urdflint.engine import config

    settings = config.from_mapping(
        {"xacro-args": {"a": "1", "b": "1"}, "per-file-xacro-args": {"arms/*.xacro": {"b": 2}}},
        tmp_path / "urdflint.toml",
    )
    assert settings.xacro_args_for(str(tmp_path / "arms" / "x.xacro")) == {"a": "1", "b": "2"}
    assert settings.xacro_args_for(str(tmp_path / "legs" / "x.xacro")) == {"a": "1", "b": "1"}
    with pytest.raises(config.ConfigError, match="per-file-xacro-args"):
        config.from_mapping({"per-file-xacro-args": {"*.xacro": "a:=1"}})


# -- positions: the start of the tag, the attribute at fault ------------------------------------


def test_findings_point_at_the_tag_start_and_the_attribute(tmp_path: Path) -> None:
    from urdflint.engine import config, linter
    from urdflint.engine.context import Context

    robot = write(
        tmp_path / "r.urdf",
        """
        <robot name="r">
          <link name="a">
            <inertial>
              <mass
                  value="-1"/>
              <inertia ixx="1" iyy="1" izz="1"
                       ixy="0" ixz="0" iyz="0"/>
            </inertial>
          </link>
        </robot>
        """,
    )
    settings = config.Settings(select=("I002", "X005"))
    [mass] = linter.lint_path(robot, "r.urdf", settings, Context(environ={})).findings
    assert (mass.line, mass.column) == (5, 11)  # value="-1", not the <mass on line 4
    robot.write_text(robot.read_text().replace('value="-1"/>', 'value="1"/>\n<origin xyz="0 0"/>'))
    [arity] = linter.lint_path(robot, "r.urdf", settings, Context(environ={})).findings
    assert (arity.code, arity.line, arity.column) == ("X005", 6, 9)


def test_an_attribute_in_a_macro_is_located_in_the_macro(ws: Path) -> None:
    finger = ws / "finger_description" / "urdf" / "finger.xacro"
    finger.write_text(finger.read_text().replace('<limit lower="-1"', '<limit\n        lower="2"'))
    bot = ws / "bot_description" / "urdf" / "bot.urdf.xacro"
    proc = run_cli("--select", "J009", "--format", "json", str(bot), cwd=ws.parent)
    [finding] = json.loads(proc.stdout)["findings"]
    assert (finding["line"], finding["column"]) == (line_of(finger, 'lower="2"'), 9)
    assert len(finding["trace"]) == 2


def test_a_suppression_inside_a_macro_works_and_an_unused_one_is_shown_there(ws: Path) -> None:
    finger = ws / "finger_description" / "urdf" / "finger.xacro"
    text = finger.read_text()
    text = text.replace(
        '      <axis xyz="0 0 0"/>',
        '      <!-- urdflint: ignore[J007] a test axis -->\n      <axis xyz="0 0 0"/>',
    )
    text = text.replace(
        "      <inertial>", "      <!-- urdflint: ignore[I002] -->\n      <inertial>"
    )
    finger.write_text(text)  # fmt: skip
    bot = ws / "bot_description" / "urdf" / "bot.urdf.xacro"
    proc = run_cli("--select", "J007,I002,U002", "--format", "json", str(bot), cwd=ws.parent)
    [unused] = json.loads(proc.stdout)["findings"]
    assert unused["code"] == "U002"
    assert (unused["path"], unused["line"]) == (str(finger), line_of(finger, "ignore[I002]"))


def test_an_include_of_the_installed_layout_is_read_from_the_source_tree(tmp_path: Path) -> None:
    """ros2_control_demos: `$(find pkg)/ros2_control/x.xacro` is installed from
    `description/ros2_control/` by CMake; before a build the source file is read."""
    from urdflint.engine import config, linter

    package = tmp_path / "demo_pkg"
    (package / "description" / "ros2_control").mkdir(parents=True)
    (package / "description" / "urdf").mkdir()
    (package / "package.xml").write_text(
        '<package format="3"><name>demo_pkg</name><version>1.0.0</version>'
        "<description>d</description><maintainer email='a@b.c'>a</maintainer>"
        "<license>BSD</license></package>"
    )
    (package / "CMakeLists.txt").write_text(
        "cmake_minimum_required(VERSION 3.16)\nproject(demo_pkg)\n"
        "# install(DIRECTORY nowhere DESTINATION share/${PROJECT_NAME})\n"
        "install(\n  DIRECTORY description/ros2_control description/urdf\n"
        "  DESTINATION share/${PROJECT_NAME}\n)\n"
    )
    (package / "description" / "ros2_control" / "bot.ros2_control.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:macro name="bot_ros2_control">\n'
        '    <ros2_control name="bot" type="system">\n'
        "      <hardware><plugin>mock_components/GenericSystem</plugin></hardware>\n"
        '      <joint name="elbow"><command_interface name="position"/></joint>\n'
        "    </ros2_control>\n  </xacro:macro>\n</robot>\n"
    )
    entry = package / "description" / "urdf" / "bot.urdf.xacro"
    entry.write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="bot">\n'
        '  <xacro:include filename="$(find demo_pkg)/ros2_control/bot.ros2_control.xacro"/>\n'
        '  <link name="base"/>\n  <xacro:bot_ros2_control/>\n</robot>\n'
    )
    settings = config.Settings(package_paths={"demo_pkg": package})
    found = linter.lint_path(entry, str(entry), settings).findings
    assert "X010" not in {f.code for f in found}
    (r004,) = [f for f in found if f.code == "R004"]  # 'elbow' is no joint of the URDF
    assert r004.path.endswith("description/ros2_control/bot.ros2_control.xacro")
    assert r004.line == 5
