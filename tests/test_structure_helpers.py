"""Helpers shared by the S, T and C rules (urdflint/structure.py) and their edge cases."""

from __future__ import annotations

import pytest
from lxml import etree
from urdflint.rules.geometry.c002_collision_same_as_visual_mesh import normalise

from tests.helpers import lint_text
from urdflint.model.document import Document
from urdflint.model.structure import closest, did_you_mean, transmission_joint_refs, welded


def doc(body: str) -> Document:
    return Document("t.urdf", f'<robot name="r">{body}</robot>'.encode())


def joint(name: str, parent: str, child: str, kind: str = "fixed", extra: str = "") -> str:
    return (
        f'<joint name="{name}" type="{kind}"><parent link="{parent}"/>'
        f'<child link="{child}"/>{extra}</joint>'
    )


def test_closest_prefers_case_insensitive_match_then_similarity() -> None:
    assert closest("Revolute", ["revolute", "prismatic"]) == "revolute"
    assert closest("revolut", ["continuous", "revolute"]) == "revolute"
    assert closest("zzz", ["revolute"]) is None
    assert closest("a", [None, ""]) is None
    assert did_you_mean("base_lnk", ["base_link"], "link") == "Did you mean link 'base_link'?"


def test_welded_follows_fixed_joints_both_ways_but_not_movable_ones() -> None:
    d = doc(
        '<link name="base"/><link name="shell"/><link name="arm"/><link name="cam"/>'
        + joint("j1", "base", "shell")
        + joint("j2", "base", "arm", "revolute")
        + joint("j3", "arm", "cam")
    )
    assert welded(d.graph, "shell") == ["shell", "base"]
    assert welded(d.graph, "cam") == ["cam", "arm"]


def test_transmission_joint_refs_cover_ros_control_and_pr2_forms() -> None:
    el = etree.fromstring(
        '<transmission><actuator name="m"/><leftActuator name="l"/><joint name="a"/>'
        '<flexJoint name="b"/><gap_joint name="c"/><use_simulated_gripper_joint/>'
        '<simulated_actuated_joint name="d" passive_actuated_joint="e"/></transmission>'
    )
    refs = [(e.tag, attr, value) for e, attr, value in transmission_joint_refs(el)]
    assert refs == [
        ("joint", "name", "a"),
        ("flexJoint", "name", "b"),
        ("gap_joint", "name", "c"),
        ("simulated_actuated_joint", "name", "d"),
        ("simulated_actuated_joint", "passive_actuated_joint", "e"),
    ]


def test_normalise_mesh_uris() -> None:
    assert normalise(" package://p/meshes/./a.dae ") == "package://p/meshes/a.dae"
    assert normalise("package://p//meshes/a.dae") == "package://p/meshes/a.dae"
    assert normalise("file:///opt/m/../m/a.stl") == "/opt/m/a.stl"
    assert normalise("meshes\\a.stl") == "meshes/a.stl"


def codes(text: str, select: str) -> list[tuple[int, str]]:
    return [(f.line, f.message) for f in lint_text(text, select=(select,))]


def test_root_only_because_of_an_undefined_parent_is_left_to_s003() -> None:
    text = (
        '<robot name="r">\n<link name="base"/>\n<link name="arm"/>\n<link name="hand"/>\n'
        + joint("a", "base", "arm")
        + "\n"
        + joint("h", "typo", "hand")
        + "\n</robot>"
    )
    assert codes(text, "S004") == []
    # ... even when the orphaned subtree is the larger one
    text = text.replace("</robot>", '<link name="f1"/>' + joint("f", "hand", "f1") + "</robot>")
    assert codes(text, "S004") == []


def test_three_joint_mimic_cycle_is_reported_once() -> None:
    links = "".join(f'<link name="{n}"/>' for n in "rabc")
    text = (
        f'<robot name="r">{links}'
        + joint("a", "r", "a", "continuous", '<mimic joint="b"/>')
        + joint("b", "r", "b", "continuous", '<mimic joint="c"/>')
        + joint("c", "r", "c", "continuous", '<mimic joint="a"/>')
        + "</robot>"
    )
    found = codes(text, "S008")
    assert [m for _, m in found] == ["mimic references form a cycle: 'a' -> 'b' -> 'c' -> 'a'"]


def test_loop_through_a_second_parent_is_reported_once() -> None:
    text = (
        '<robot name="r"><link name="base"/><link name="a"/><link name="b"/>'
        + joint("in", "base", "a")
        + joint("ab", "a", "b")
        + joint("ba", "b", "a")
        + "</robot>"
    )
    found = codes(text, "S005")
    assert len(found) == 1 and "'in' and joint 'ba'" in found[0][1]


def test_a_duplicated_link_with_two_parents_gets_both_findings() -> None:
    """S001 and S005 in one run: renaming the copy must not reveal the second parent later."""
    text = (
        '<robot name="r"><link name="base"/><link name="arm"/>'
        + joint("j1", "base", "arm")
        + '<link name="arm"/>'
        + joint("j2", "base", "arm")
        + "</robot>"
    )
    found = lint_text(text, select=("S",))
    assert sorted(f.code for f in found) == ["S001", "S005"]
    assert "child of both joint 'j1' and joint 'j2'" in next(
        f.message for f in found if f.code == "S005"
    )


def test_a_second_parent_is_reported_even_when_its_parent_link_is_undefined() -> None:
    text = (
        '<robot name="r"><link name="base"/><link name="arm"/>'
        + joint("j1", "base", "arm")
        + joint("j2", "bsae", "arm")
        + "</robot>"
    )
    assert sorted(f.code for f in lint_text(text, select=("S",))) == ["S003", "S005"]


def test_duplicates_inside_xacro_macros_name_where_the_first_was_written(tmp_path) -> None:
    from pathlib import Path

    from urdflint.engine import config, linter

    path = Path(tmp_path) / "robot.urdf.xacro"
    path.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <link name="base"/>\n'
        '  <xacro:macro name="finger" params="side">\n'
        '    <joint name="${side}_joint" type="fixed">\n'
        '      <parent link="base"/><child link="tip"/>\n'
        "    </joint>\n"
        '    <link name="tip"/>\n'
        "  </xacro:macro>\n"
        '  <xacro:finger side="left"/>\n'
        '  <xacro:finger side="right"/>\n'
        "</robot>\n"
    )
    settings = config.Settings(select=("S001", "S005"))
    found = linter.lint_path(path, str(path), settings).findings
    s001 = next(f for f in found if f.code == "S001")
    assert (s001.line, s001.column) == (7, 5)
    assert s001.message.endswith(
        f"(first defined on line 7, in macro `finger` called from {path}:9)"
    )
    assert {f.code for f in found} == {"S001", "S005"}


@pytest.mark.parametrize(
    ("targets", "severity"),
    [(["mujoco"], "info"), (["gazebo-classic"], "error"), (["mujoco", "gz-sim"], "error")],
)
def test_spherical_is_accepted_only_when_mujoco_is_the_only_target(
    targets: list[str], severity: str
) -> None:
    """MuJoCo 4 builds a ball joint (mjJNT_BALL) from type="spherical"; urdfdom refuses it."""
    text = (
        '<robot name="r"><link name="base"/><link name="head"/>'
        + joint("neck", "base", "head", "spherical")
        + "</robot>"
    )
    found = lint_text(text, select=("S006",), targets=targets)
    assert [f.severity.name.lower() for f in found] == [severity]
    ball = lint_text(text.replace("spherical", "ball"), select=("S006",), targets=["mujoco"])
    assert [f.severity.name.lower() for f in ball] == ["error"]


def test_no_links_is_an_error_for_urdf_but_x011_for_a_xacro_library(tmp_path) -> None:
    from pathlib import Path

    from urdflint.engine import config, linter

    assert [f.code for f in lint_text('<robot name="r"/>', select=("S011",))] == ["S011"]
    leftover = (
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:macro name="m"/></robot>'
    )
    assert lint_text(leftover, select=("S011",)) == []  # an unexpanded library: X008
    library = Path(tmp_path) / "colours.xacro"
    library.write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<material name="red"><color rgba="1 0 0 1"/></material></robot>'
    )
    found = linter.lint_path(library, str(library), config.Settings()).findings
    assert [f.code for f in found] == ["X011"]
