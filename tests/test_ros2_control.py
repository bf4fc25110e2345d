"""The R rules (ros2_control blocks): exact code, element, file and line, and the edge cases."""

from __future__ import annotations

from pathlib import Path

import pytest
from urdflint.rules.ros2_control.r008_misspelt_ros2_control_interface import standard_for

from tests.conftest import FIXTURES
from tests.helpers import lint_file, lint_text
from urdflint.model.finding import Severity

NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
JOINTS = """
  <link name="base"/>
  <link name="a"/>
  <link name="b"/>
  <link name="c"/>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="a"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="j2" type="prismatic">
    <parent link="a"/><child link="b"/>
    <limit lower="0" upper="0.1" effort="1" velocity="1"/>
    <mimic joint="j1"/>
  </joint>
  <joint name="fixed" type="fixed">
    <parent link="b"/><child link="c"/>
  </joint>
"""
HW = "<hardware><plugin>mock_components/GenericSystem</plugin></hardware>"


def robot(body: str) -> str:
    return f'<robot name="r" {NS}>{JOINTS}{body}\n</robot>\n'


def block(inner: str, name: str = "arm", type_: str = "system", hw: str = HW) -> str:
    return f'\n  <ros2_control name="{name}" type="{type_}">\n    {hw}\n{inner}\n  </ros2_control>'


def run(code: str, body: str):
    return [f for f in lint_text(robot(body), select=(code,)) if f.code == code]


def line_of(text: str, needle: str, nth: int = 1) -> int:
    lines = [n for n, line in enumerate(text.splitlines(), start=1) if needle in line]
    return lines[nth - 1]


# -- R001 ------------------------------------------------------------------------------


def test_r001_block_inside_gazebo_is_reported_with_its_line() -> None:
    body = (
        '\n  <gazebo>\n    <ros2_control name="sim" type="system">'
        + HW
        + "</ros2_control>\n  </gazebo>"
    )
    text = robot(body)
    (found,) = [f for f in lint_text(text, select=("R001",))]
    assert found.severity is Severity.ERROR
    assert found.element == "/robot/gazebo/ros2_control[@name='sim']"
    assert found.line == line_of(text, '<ros2_control name="sim"')
    assert "no 'ros2_control' tag found" in found.message


def test_r001_says_the_joints_get_no_hardware_when_other_blocks_exist() -> None:
    inner = '    <ros2_control name="g" type="system">' + HW + "</ros2_control>"
    body = block('<joint name="j1"><state_interface name="position"/></joint>')
    body += f"\n  <gazebo>\n{inner}\n  </gazebo>"
    (found,) = run("R001", body)
    assert "get no hardware interfaces" in found.message


def test_r001_leaves_a_block_nested_in_a_block_to_r003() -> None:
    nested = '<ros2_control name="inner" type="system">' + HW + "</ros2_control>"
    body = block(nested)
    assert run("R001", body) == []
    (found,) = run("R003", body)
    assert found.element == "/robot/ros2_control[@name='arm']/ros2_control[@name='inner']"


# -- R002 ------------------------------------------------------------------------------


def test_r002_type_is_compared_exactly_and_points_at_the_attribute() -> None:
    (found,) = run("R002", block("", type_="System"))
    assert "'System'" in found.message
    assert found.fix == "Use type='system'."


def test_r002_duplicate_name_names_the_first_block() -> None:
    body = block("", name="hw") + block("", name="hw")
    text = robot(body)
    (found,) = run("R002", body)
    tag = '<ros2_control name="hw"'
    assert found.line == line_of(text, tag, 2)
    assert f"line {line_of(text, tag)}" in found.message


def test_r002_plugin_after_params_is_accepted() -> None:
    hw = "<hardware><param name='port'>x</param><plugin>pkg/Hw</plugin></hardware>"
    assert run("R002", block("", hw=hw)) == []


def test_r002_the_last_hardware_counts() -> None:
    hw = HW + "<hardware><param name='x'>1</param></hardware>"
    (found,) = run("R002", block("", hw=hw))
    assert found.element == "/robot/ros2_control[@name='arm']/hardware[2]"


# -- R003 ------------------------------------------------------------------------------


def test_r003_suggests_the_closest_child() -> None:
    (found,) = run("R003", block('<joints name="j1"/>'))
    assert found.fix == "Did you mean <joint>?"


def test_r003_accepts_properties_and_gpio_sizes() -> None:
    inner = (
        '<properties><async thread_priority="50"/></properties>'
        '<gpio name="io"><command_interface name="out" data_type="bool" size="4"/></gpio>'
    )
    assert run("R003", block(inner)) == []


# -- R004 ------------------------------------------------------------------------------


def test_r004_xacro_include_lands_in_the_included_file() -> None:
    entry = FIXTURES / "rules" / "R004" / "bad_include.xacro"
    part = entry.parent / "parts" / "arm.ros2_control.xacro"
    (found,) = [f for f in lint_file(entry, select=("R004",)) if f.code == "R004"]
    assert Path(found.path).resolve() == part.resolve()
    assert found.line == line_of(part.read_text(), "elbow_joint")
    assert found.element == "/robot/ros2_control[@name='arm']/joint[@name='elbow_joint']"
    assert found.trace and found.trace[0].macro == "arm_ros2_control"
    assert found.fix == "Did you mean joint 'elbow'?" or found.fix is None


def test_r004_fixed_joint_and_undefined_joint() -> None:
    inner = '<joint name="fixed"><state_interface name="position"/></joint>'
    inner += '\n<joint name="j3"><state_interface name="position"/></joint>'
    found = run("R004", block(inner))
    assert [f.element.rsplit("/", 1)[1] for f in found] == [
        "joint[@name='fixed']",
        "joint[@name='j3']",
    ]
    assert "fixed joint" in found[0].message and "not a joint of the URDF" in found[1].message


def test_r004_sensor_and_gpio_names_need_not_be_joints_or_links() -> None:
    inner = '<sensor name="imu"><state_interface name="orientation.x"/></sensor>'
    inner += '<gpio name="io"><state_interface name="in"/></gpio>'
    assert run("R004", block(inner)) == []


# -- R005 ------------------------------------------------------------------------------


def test_r005_mimic_with_state_only_and_its_leader_is_fine() -> None:
    inner = '<joint name="j1"><command_interface name="position"/></joint>'
    inner += '<joint name="j2"><state_interface name="position"/></joint>'
    assert run("R005", block(inner)) == []


@pytest.mark.parametrize("flag", ["false", "False", " FALSE "])
def test_r005_mimic_false_allows_commands_and_a_missing_leader(flag: str) -> None:
    inner = f'<joint name="j2" mimic="{flag}"><command_interface name="position"/></joint>'
    assert run("R005", block(inner)) == []


def test_r005_reports_commands_and_a_leader_in_another_block() -> None:
    inner = '<joint name="j2"><command_interface name="position"/></joint>'
    found = {f.element: f.message for f in run("R005", block(inner))}
    joint = "/robot/ros2_control[@name='arm']/joint[@name='j2']"
    assert set(found) == {joint, joint + "/command_interface[@name='position']"}
    assert "Activated mimic joints" in found[joint + "/command_interface[@name='position']"]
    assert "'j1'" in found[joint]


# -- R006 ------------------------------------------------------------------------------


def test_r006_same_key_in_two_blocks_is_an_error_and_in_one_block_a_warning() -> None:
    a = block('<joint name="j1"><state_interface name="position"/></joint>', name="a")
    b = block('<joint name="j1"><state_interface name="position"/></joint>', name="b")
    (across,) = run("R006", a + b)
    assert across.severity is Severity.ERROR and "'a'" in across.message
    twice = '<joint name="j1"><state_interface name="position"/><state_interface name="position"/>'
    (within,) = run("R006", block(twice + "</joint>"))
    assert within.severity is Severity.WARNING


def test_r006_sensor_named_like_a_joint_collides() -> None:
    inner = '<joint name="j1"><state_interface name="position"/></joint>'
    other = block('<sensor name="j1"><state_interface name="position"/></sensor>', name="s")
    (found,) = run("R006", block(inner) + other)
    assert (
        found.element
        == "/robot/ros2_control[@name='s']/sensor[@name='j1']/state_interface[@name='position']"
    )


def test_r006_command_and_state_of_the_same_name_do_not_collide() -> None:
    inner = '<joint name="j1"><command_interface name="position"/>'
    inner += '<state_interface name="position"/></joint>'
    assert run("R006", block(inner)) == []


# -- R007 ------------------------------------------------------------------------------


def _param(
    name: str, value: str, kind: str = "state", iface: str = "position", extra: str = ""
) -> str:
    return (
        f'<joint name="j1"><{kind}_interface name="{iface}"{extra}>'
        f'<param name="{name}">{value}</param></{kind}_interface></joint>'
    )


def test_r007_initial_value_out_of_limits_is_a_warning() -> None:
    (found,) = run("R007", block(_param("initial_value", "1.5")))
    assert found.severity is Severity.WARNING and "[-1, 1]" in found.message


@pytest.mark.parametrize("value", ["${pi}", "$(arg x)"])
def test_r007_unexpanded_xacro_is_not_judged(value: str) -> None:
    assert run("R007", block(_param("initial_value", value))) == []


def test_r007_non_numeric_data_types_are_not_judged() -> None:
    assert run("R007", block(_param("initial_value", "true", extra=' data_type="bool"'))) == []


def test_r007_min_max_only_on_joint_command_interfaces() -> None:
    assert run("R007", block(_param("min", "low", kind="state"))) == []
    (found,) = run("R007", block(_param("min", "low", kind="command")))
    assert found.severity is Severity.WARNING


# -- R008 ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("name", "meant"),
    [
        ("Position", "position"),
        ("VELOCITY", "velocity"),
        ("positon", "position"),
        ("effrot", "effort"),
        ("hardware_interface/PositionJointInterface", "position"),
        ("position_cmd", None),
        ("motor_current", None),
        ("pos", None),
        ("gripper_state", None),
    ],
)
def test_r008_standard_for(name: str, meant: str | None) -> None:
    assert standard_for(name) == meant


def test_r008_only_joint_interfaces() -> None:
    inner = '<gpio name="io"><state_interface name="Position"/></gpio>'
    assert run("R008", block(inner)) == []


# -- R009 ------------------------------------------------------------------------------


def test_r009_transmission_joint_declared_in_another_block() -> None:
    other = block('<joint name="j1"><command_interface name="position"/></joint>', name="a")
    inner = (
        '<transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>'
        '<actuator name="m" role="actuator1"/><joint name="j1" role="joint1"/></transmission>'
    )
    (found,) = run("R009", other + block(inner, name="b"))
    assert (
        found.element == "/robot/ros2_control[@name='b']/transmission[@name='t']/joint[@name='j1']"
    )
