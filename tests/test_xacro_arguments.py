"""X010 names the xacro argument behind a failed expansion: an empty or missing argument in
an include's filename (through macro parameters, properties and argument defaults), and the
argument whose <xacro:if>/<xacro:unless> lets a missing package be included."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from tests.conftest import FIXTURES
from urdflint.engine import config, linter
from urdflint.engine.context import Context
from urdflint.model.finding import Finding

pytest.importorskip("xacro")

ARM = FIXTURES / "xacro" / "arm_args"  # Kinova ros2_kortex's layout, cut down
MOBILE = FIXTURES / "xacro" / "mobile_components"  # Husarion panther_ros's layout, cut down
NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
PASS_HOW = (
    "pass it with --xacro-arg {}:=VALUE or set it under [tool.urdflint.xacro-args] (for this"
    " file only: [tool.urdflint.per-file-xacro-args])"
)


def lint(path: Path, shown: str, **args: str) -> list[Finding]:
    """The X rules' findings on ``path`` (named ``shown``), with these xacro arguments."""
    settings = config.Settings(select=("X",), xacro_args=dict(args))
    return linter.lint_path(path, shown, settings, Context(environ={})).findings


def one_x010(path: Path, shown: str, **args: str) -> tuple[str, int, int, str]:
    [finding] = lint(path, shown, **args)
    assert finding.code == "X010"
    return finding.path, finding.line, finding.column, finding.message


def write(path: Path, text: str) -> Path:
    path.write_text(textwrap.dedent(text).lstrip(), encoding="utf-8")
    return path


# -- an empty argument in an include's filename ---------------------------------------------


def test_empty_argument_through_a_macro_parameter_is_named_with_the_values_that_work() -> None:
    found = one_x010(ARM / "robots" / "arm.urdf.xacro", "arm_args/robots/arm.urdf.xacro")
    assert found == (
        "arm_args/robots/arm_macro.xacro",  # the include, where it is written
        4,
        5,
        "include of '$(find argarm_description)/arms/${arm}/${dof}dof/${arm}_macro.xacro'"
        " resolved to 'arm_args/arms/arm7/dof/arm7_macro.xacro' (no such file or directory):"
        " argument 'dof' is empty when expanding arm.urdf.xacro (default '' in"
        " arm.urdf.xacro:5; reached through macro 'load_robot' called with"
        ' dof="$(arg dof)" at arm.urdf.xacro:8); pass --xacro-arg dof:=6 or dof:=7',
    )


@pytest.mark.parametrize("dof", ["6", "7"])
def test_the_suggested_values_expand(dof: str) -> None:
    assert lint(ARM / "robots" / "arm.urdf.xacro", "arm.urdf.xacro", dof=dof) == []


def test_an_argument_given_empty_says_so() -> None:
    found = one_x010(ARM / "robots" / "arm.urdf.xacro", "arm_args/robots/arm.urdf.xacro", arm="")
    assert found[:3] == ("arm_args/robots/arm_macro.xacro", 4, 5)
    assert found[3] == (
        "include of '$(find argarm_description)/arms/${arm}/${dof}dof/${arm}_macro.xacro'"
        " resolved to 'arm_args/arms/dof/_macro.xacro' (no such file or directory):"
        " argument 'arm' is empty when expanding arm.urdf.xacro (given as ''; reached through"
        " macro 'load_robot' called with arm=\"$(arg arm)\" at arm.urdf.xacro:8); argument"
        " 'dof' is empty when expanding arm.urdf.xacro (default '' in arm.urdf.xacro:5;"
        " reached through macro 'load_robot' called with dof=\"$(arg dof)\" at"
        " arm.urdf.xacro:8); pass --xacro-arg arm:=arm7 and --xacro-arg dof:=6 or dof:=7"
    )


def test_a_wrong_but_not_empty_argument_keeps_the_message_and_finds_the_include() -> None:
    found = one_x010(ARM / "robots" / "arm.urdf.xacro", "arm_args/robots/arm.urdf.xacro", dof="8")
    assert found == (
        "arm_args/robots/arm_macro.xacro",
        4,
        5,
        "cannot read arm_args/arms/arm7/8dof/arm7_macro.xacro: no such file or directory",
    )


def test_an_empty_argument_that_does_not_make_the_path_wrong_is_not_blamed(tmp_path: Path) -> None:
    (tmp_path / "parts").mkdir()
    write(tmp_path / "parts" / "wheel.xacro", f"<robot {NS}/>\n")
    path = write(
        tmp_path / "robot.urdf.xacro",
        f"""
        <robot name="r" {NS}>
          <xacro:arg name="prefix" default=""/>
          <link name="base_link"/>
          <xacro:include filename="parts/$(arg prefix)arm.xacro"/>
        </robot>
        """,
    )
    assert one_x010(path, "robot.urdf.xacro") == (
        "robot.urdf.xacro",
        4,
        3,
        "cannot read parts/arm.xacro: no such file or directory",
    )


def test_an_argument_whose_default_is_another_argument_is_followed_to_it() -> None:
    path = ARM / "robots" / "chained.urdf.xacro"
    assert one_x010(path, "arm_args/robots/chained.urdf.xacro") == (
        "arm_args/robots/chained.urdf.xacro",
        6,
        3,
        "include of '$(find argarm_description)/arms/$(arg arm)/7dof/$(arg arm)_macro.xacro'"
        " resolved to 'arm_args/arms/7dof/_macro.xacro' (no such file or directory):"
        " argument 'model' is empty when expanding chained.urdf.xacro (default '' in"
        " chained.urdf.xacro:3; reached through argument 'arm' whose default is"
        " '$(arg model)' at chained.urdf.xacro:4); pass --xacro-arg model:=arm7",
    )
    assert lint(path, "chained.urdf.xacro", model="arm7") == []


def test_an_empty_argument_in_a_failed_expression_is_named(tmp_path: Path) -> None:
    path = write(
        tmp_path / "robot.urdf.xacro",
        f"""
        <robot name="r" {NS}>
          <xacro:arg name="payload" default=""/>
          <xacro:property name="mass" value="$(arg payload)"/>
          <xacro:macro name="body" params="m">
            <link name="base_link">
              <inertial>
                <mass value="${{float(m) + 1}}"/>
                <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
              </inertial>
            </link>
          </xacro:macro>
          <xacro:body m="${{mass}}"/>
        </robot>
        """,
    )
    assert one_x010(path, "robot.urdf.xacro") == (
        "robot.urdf.xacro",
        7,
        22,
        "could not convert string to float: '' when evaluating expression 'float(m) + 1' in"
        " macro 'body': argument 'payload' is empty when expanding robot.urdf.xacro (default ''"
        " in robot.urdf.xacro:2; reached through macro 'body' called with m=\"${mass}\" at"
        " robot.urdf.xacro:12, then property 'mass' = '$(arg payload)' at robot.urdf.xacro:3);"
        " pass --xacro-arg payload:=VALUE",
    )


# -- a missing argument -----------------------------------------------------------------------


def test_an_argument_used_before_its_declaration_names_the_declaration() -> None:
    found = one_x010(ARM / "robots" / "late.urdf.xacro", "arm_args/robots/late.urdf.xacro")
    assert found == (
        "arm_args/robots/late.urdf.xacro",
        2,
        14,
        "xacro argument 'name' has no value when expanding late.urdf.xacro: it was not given,"
        " and its <xacro:arg> (default 'late' in late.urdf.xacro:3) comes after this use;"
        " declare it first, or " + PASS_HOW.format("name"),
    )


def test_a_missing_argument_read_by_another_arguments_default_names_both(tmp_path: Path) -> None:
    path = write(
        tmp_path / "robot.urdf.xacro",
        f"""
        <robot name="r" {NS}>
          <link name="base_link"/>
          <xacro:arg name="arm" default="$(arg model)"/>
          <link name="$(arg arm)"/>
        </robot>
        """,
    )
    assert one_x010(path, "robot.urdf.xacro") == (
        "robot.urdf.xacro",
        3,
        34,
        "xacro argument 'model' has no value when expanding robot.urdf.xacro (the default of"
        " argument 'arm' at robot.urdf.xacro:3 reads it): it has no default and was not given; "
        + PASS_HOW.format("model"),
    )


# -- an argument that decides whether a missing package is included ------------------------------


def test_the_argument_deciding_a_condition_around_a_missing_package_is_named() -> None:
    path = MOBILE / "urdf" / "mobile.urdf.xacro"
    assert one_x010(path, "mobile_components/urdf/mobile.urdf.xacro") == (
        "mobile_components/urdf/mobile.urdf.xacro",
        15,
        5,
        "package 'absent_components_description' was not found (looked at: package.xml named"
        f" 'absent_components_description' above {MOBILE / 'urdf'}); this <xacro:include> is"
        " inside <xacro:unless value=\"${components_config_path_property == 'None'}\"> at"
        " mobile.urdf.xacro:14, which depends on argument 'components_config_path' (default"
        " '$(find mobile_description)/config/components.yaml' in mobile.urdf.xacro:11; reached"
        " through property 'components_config_path_property' = '$(arg components_config_path)'"
        " at mobile.urdf.xacro:12) when expanding mobile.urdf.xacro; pass --xacro-arg"
        " components_config_path:=None to skip it",
    )
    assert lint(path, "mobile.urdf.xacro", components_config_path="None") == []


@pytest.mark.parametrize(
    ("default", "condition", "advice"),
    [
        ("true", '<xacro:if value="$(arg cameras)">', "cameras:=false to skip it"),
        ("false", '<xacro:unless value="$(arg cameras)">', "cameras:=true to skip it"),
        ("false", '<xacro:if value="${not cameras}">', "cameras:=true to skip it"),
        ("all", "<xacro:if value=\"${cameras != 'none'}\">", "cameras:=none to skip it"),
        (
            "all",
            "<xacro:if value=\"${cameras == 'all'}\">",
            "cameras:=VALUE that makes the condition false",
        ),
    ],
)
def test_the_value_that_skips_a_condition(
    tmp_path: Path, default: str, condition: str, advice: str
) -> None:
    tag = condition[1 : condition.index(" ")]
    path = write(
        tmp_path / "robot.urdf.xacro",
        f"""
        <robot name="r" {NS}>
          <xacro:arg name="cameras" default="{default}"/>
          <xacro:property name="cameras" value="$(arg cameras)"/>
          <link name="base_link"/>
          {condition}
            <xacro:include filename="$(find no_such_cameras)/urdf/cameras.xacro"/>
          </{tag}>
        </robot>
        """,
    )
    found = one_x010(path, "robot.urdf.xacro")
    assert found[:3] == ("robot.urdf.xacro", 6, 5)
    assert found[3].endswith(f"when expanding robot.urdf.xacro; pass --xacro-arg {advice}") or (
        found[3].endswith(f"; to skip it, pass --xacro-arg {advice}")
    ), found[3]
    assert f"this <xacro:include> is inside {condition[:-1]}> at robot.urdf.xacro:5" in found[3]
