"""Parsing what tinyxml2-based consumers load: default namespaces, undeclared prefixes,
files that are not well-formed (checked on libxml2's recovered tree), and the X rules
whose severity or scope follows from what the consumers were observed to do."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from tests.helpers import lint_text
from urdflint.engine.linter import RECOVERED
from urdflint.model.document import Document
from urdflint.model.finding import Severity

ARM = """<?xml version="1.0"?>
<robot name="arm"{robot}>
  <link name="base_link">
    <inertial><mass value="1"/><inertia {inertia}/></inertial>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base_link"/>
    <child link="upper_arm"/>
    <axis xyz="0 0 1"/>
  </joint>{extra}
  <link name="upper_arm">
    <inertial><mass value="1"/><inertia {inertia}/></inertial>
  </link>
</robot>
"""


INERTIA = 'ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"'


def arm(robot: str = "", extra: str = "") -> str:
    return ARM.format(robot=robot, extra=extra, inertia=INERTIA)


def codes(text: str, **kwargs: object) -> dict[str, list]:
    found: dict[str, list] = {}
    for finding in lint_text(text, **kwargs):
        found.setdefault(finding.code, []).append(finding)
    return found


# -- a default namespace on <robot> -------------------------------------------------------


def test_default_namespace_is_checked_like_any_robot() -> None:
    found = codes(arm(robot=' xmlns="http://www.ros.org"'))
    (x002,) = found["X002"]
    assert x002.severity is Severity.WARNING and "yourdfpy" in x002.message
    assert (x002.line, x002.column) == (2, 19)  # the xmlns= attribute
    assert "J001" in found  # the missing <limit> is found: every other rule ran


def test_default_namespace_elements_are_plain() -> None:
    doc = Document("a.urdf", arm(robot=' xmlns="http://www.ros.org"').encode())
    assert doc.ok and doc.default_namespace == "http://www.ros.org"
    assert [link.name for link in doc.links] == ["base_link", "upper_arm"]
    assert doc.element_path(doc.joints[0].element) == "/robot/joint[@name='shoulder']"


def test_prefixed_robot_is_still_not_a_robot() -> None:
    text = '<u:robot xmlns:u="http://example.com" name="a"><u:link name="b"/></u:robot>'
    found = lint_text(text)
    assert [(f.code, f.severity) for f in found] == [("X002", Severity.ERROR)]


# -- undeclared namespace prefixes ---------------------------------------------------------


def test_undeclared_prefix_is_a_warning_and_the_file_is_checked() -> None:
    extra = '\n  <drake:joint name="z" type="planar"><parent link="a"/></drake:joint>'
    found = codes(arm(extra=extra))
    assert "X001" not in found
    (x012,) = found["X012"]
    assert x012.severity is Severity.WARNING and x012.line == 11
    assert x012.element == "/robot/drake:joint[@name='z']"
    assert "J001" in found
    assert "X007" not in found  # a namespaced extension element, not an unknown URDF one


def test_undeclared_prefix_columns_come_from_the_original_text() -> None:
    # the declaration urdflint adds goes on the <robot> line: lines and columns stay right
    text = '<robot name="r"><link name="a" drake:x="1"/>\n  <link name="b" drake:y="2"/>\n</robot>'
    (x012,) = [f for f in lint_text(text) if f.code == "X012"]
    assert (x012.line, x012.column) == (1, 32) and "(and 1 more use)" in x012.message


def test_undeclared_xacro_prefix_is_still_unexpanded_xacro() -> None:
    extra = '\n  <xacro:property name="l" value="1"/>'
    found = codes(arm(extra=extra))
    assert "X012" in found and "X008" in found


# -- files that are not well-formed --------------------------------------------------------


def test_rules_run_on_the_recovered_tree_and_say_so() -> None:
    text = arm().replace('<link name="upper_arm">', '<link name="upper_arm" note="a&b">')
    found = codes(text)
    (x001,) = found["X001"]
    assert x001.severity is Severity.ERROR and not x001.message.endswith(RECOVERED)
    (j001,) = found["J001"]
    assert j001.message.endswith(RECOVERED)
    assert not [code for code in found if code.startswith("P")]  # Pinocchio reads the file


def test_recovered_document_is_not_ok_for_physics() -> None:
    doc = Document("a.urdf", arm().replace("</joint>", "</joint_>").encode())
    assert doc.recovered and not doc.ok and doc.problem is not None
    assert doc.problem.code == "X001" and doc.links[0].name == "base_link"


def test_undeclared_prefix_after_the_syntax_error_is_declared_too() -> None:
    text = arm(extra='\n  <drake:joint name="z"/>').replace('name="base_link">', 'name="a&b">')
    doc = Document("a.urdf", text.encode())
    assert doc.recovered and doc.undeclared_prefixes == ("drake",)


@pytest.mark.parametrize(
    "text",
    [
        '<?xml version="1.0"?>\n<!DOCTYPE robot [<!ENTITY m "1">]>\n<robot name="r"><link></robot>',
        '<robot name="r"><link name="a">&nbsp;<bad></link></robot>',
        "<sdf><model name='m'><link></sdf>",
    ],
    ids=["doctype", "entity-reference", "not-a-robot"],
)
def test_what_is_never_recovered(text: str) -> None:
    doc = Document("a.urdf", text.encode())
    assert doc.root is None and not doc.recovered
    assert len(lint_text(text)) == 1


def test_recovered_file_still_fails_the_run(tmp_path: Path) -> None:
    path = tmp_path / "broken.urdf"
    path.write_text(arm().replace("</joint>", "</joint_>"))
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--isolated", "--format", "text", str(path)],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 1 and "X001" in proc.stdout and RECOVERED.strip() in proc.stdout


# -- an empty robot name depends on the target ---------------------------------------------


@pytest.mark.parametrize(
    ("targets", "severity"),
    [
        (["gazebo-classic"], Severity.ERROR),
        (["gz-sim"], Severity.ERROR),
        (["mujoco"], Severity.WARNING),
        (["mujoco", "gz-sim"], Severity.ERROR),
    ],
)
def test_empty_robot_name_severity_follows_the_target(targets: list[str], severity) -> None:
    text = arm().replace('name="arm"', 'name=""')
    (x003,) = [f for f in lint_text(text, select=("X003",), targets=targets)]
    assert x003.severity is severity and x003.element == "/robot"


def test_empty_link_name_is_an_error_for_every_target() -> None:
    text = arm(extra='\n  <link name=""/>')
    (x003,) = lint_text(text, select=("X003",), targets=["mujoco"])
    assert x003.severity is Severity.ERROR


# -- a <material> inside <geometry> ---------------------------------------------------------


def geometry(inner: str) -> str:
    visual = f"\n    <visual><geometry>{inner}</geometry></visual>"
    return arm().replace('<link name="upper_arm">', '<link name="upper_arm">' + visual)


def test_material_after_the_shape_is_not_a_second_shape() -> None:
    found = codes(geometry('<box size="1 1 1"/><material name="red"/>'))
    assert "C003" not in found
    (x007,) = found["X007"]
    assert "<material>" in x007.message and "inside <visual>" in x007.message


def test_material_before_the_shape_makes_urdfdom_drop_the_visual() -> None:
    found = codes(geometry('<material name="red"/><box size="1 1 1"/>'))
    (c003,) = found["C003"]
    assert "starts with <material>" in c003.message and "X007" in found


def test_unknown_shape_stays_c003s() -> None:
    found = codes(geometry('<cube size="1 1 1"/>'))
    assert "C003" in found and "X007" not in found


# -- unknown attributes ---------------------------------------------------------------------


def test_unknown_attribute_suggests_the_known_one() -> None:
    text = arm().replace('type="revolute"', 'typ="revolute"')
    (x013,) = lint_text(text, select=("X013",))
    assert "did you mean type?" in x013.message and x013.severity is Severity.WARNING
    assert (x013.line, x013.column) == (6, 26)


def test_extension_and_namespaced_attributes_are_accepted() -> None:
    text = arm(robot=' xmlns:drake="http://drake.mit.edu" version="1.0"').replace(
        '<link name="base_link">', '<link name="base_link" drake_ignore="false" drake:x="1">'
    )
    assert lint_text(text, select=("X013",)) == []
