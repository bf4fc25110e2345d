"""Helpers shared by the S, T and C rules (urdflint/structure.py) and their edge cases."""

from __future__ import annotations

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
