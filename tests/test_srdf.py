"""The MoveIt SRDF: how it is found, parsed once, and where the M rules' findings point."""

from __future__ import annotations

import json
from pathlib import Path
from unittest.mock import ANY

import pytest

from tests.conftest import FIXTURES
from tests.helpers import lint_file
from urdflint.cli import main
from urdflint.engine import config, linter
from urdflint.model import optional
from urdflint.sources import srdf as srdf_source

ARM = FIXTURES / "rules" / "M003"
URDF = (ARM / "good.urdf").read_text()
GOOD = (ARM / "good.srdf").read_text()
STALE = GOOD.replace('link2="forearm"', 'link2="lower_arm"')  # line 25: one M009 finding
PACKAGE_XML = "<package format='3'><name>{}</name></package>\n"


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def load(path: Path, **settings: object) -> linter.Document:
    chosen = config.Settings(**settings)  # type: ignore[arg-type]
    return linter.load(path, str(path), chosen)


def found(path: Path, **settings: object) -> tuple[Path, str, str] | None:
    return srdf_source.find(load(path, **settings))


def m_findings(path: Path, **settings: object) -> list[tuple[str, int, str, str]]:
    chosen = config.Settings(select=("M",), **settings)  # type: ignore[arg-type]
    return [(f.path, f.line, f.code, f.element) for f in lint_file(path, settings=chosen)]


# -- discovery ---------------------------------------------------------------------------------


def test_explicit_srdf_wins_over_the_one_beside(tmp_path: Path) -> None:
    urdf = write(tmp_path / "arm.urdf", URDF)
    write(tmp_path / "arm.srdf", GOOD)
    other = write(tmp_path / "elsewhere" / "robot.srdf", STALE)
    assert found(urdf, srdf=other) == (other, str(other), "--srdf")
    assert m_findings(urdf, srdf=other) == [
        (str(other), 25, "M009", "/robot/disable_collisions[2]")
    ]


def test_srdf_beside_the_file_by_stem(tmp_path: Path) -> None:
    urdf = write(tmp_path / "arm.urdf.xacro", URDF)
    beside = write(tmp_path / "arm.srdf", STALE)
    assert found(urdf) == (beside, str(beside), "beside")
    assert m_findings(urdf) == [(str(beside), 25, "M009", "/robot/disable_collisions[2]")]


def test_package_config_srdf_with_the_same_robot_name(tmp_path: Path) -> None:
    package = tmp_path / "arm_description"
    write(package / "package.xml", PACKAGE_XML.format("arm_description"))
    urdf = write(package / "urdf" / "robot.urdf", URDF)
    write(package / "config" / "another.srdf", GOOD.replace('name="arm"', 'name="other"', 1))
    config_srdf = write(package / "config" / "zzz.srdf", STALE)
    path, shown, how = found(urdf) or (None, "", "")
    assert (path, how) == (config_srdf, "package")
    assert Path(shown) == config_srdf


def test_package_srdf_of_another_robot_is_ignored(tmp_path: Path) -> None:
    package = tmp_path / "arm_description"
    write(package / "package.xml", PACKAGE_XML.format("arm_description"))
    urdf = write(package / "urdf" / "robot.urdf", URDF)
    write(package / "config" / "other.srdf", STALE.replace('name="arm"', 'name="other"', 1))
    assert found(urdf) is None
    assert m_findings(urdf) == []


def test_moveit_config_setup_assistant_pairs_urdf_and_srdf(tmp_path: Path) -> None:
    description = tmp_path / "arm_description"
    write(description / "package.xml", PACKAGE_XML.format("arm_description"))
    urdf = write(description / "urdf" / "robot.urdf", URDF)
    moveit = tmp_path / "arm_moveit_config"
    write(moveit / "package.xml", PACKAGE_XML.format("arm_moveit_config"))
    srdf = write(moveit / "config" / "arm_robot.srdf", STALE.replace('"arm"', '"arm_x"', 1))
    write(
        moveit / ".setup_assistant",
        "moveit_setup_assistant_config:\n  URDF:\n    package: arm_description\n"
        "    relative_path: urdf/robot.urdf\n  SRDF:\n    relative_path: config/arm_robot.srdf\n",
    )
    path, _, how = found(urdf) or (None, "", "")
    assert (path, how) == (srdf, "setup-assistant")
    codes = sorted(code for _, _, code, _ in m_findings(urdf))
    assert codes == ["M002", "M009"]  # paired although the robot names differ


def test_a_setup_assistant_pairs_only_the_xacro_variant_it_was_made_for(tmp_path: Path) -> None:
    """Kinova's kortex: one gen3.xacro, a MoveIt config per variant (xacro_args dof:=6 and
    dof:=7, both with gripper:=robotiq_2f_85); the SRDF of another variant is not paired."""
    description = tmp_path / "arm_description"
    write(description / "package.xml", PACKAGE_XML.format("arm_description"))
    entry = write(
        description / "robots" / "arm.urdf.xacro",
        '<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:arg name="dof" default=""/>\n  <xacro:arg name="gripper" default=""/>\n'
        + URDF.split("\n", 2)[2],
    )
    srdfs = {}
    for dof in ("6", "7"):
        moveit = tmp_path / f"arm_{dof}dof_moveit_config"
        write(moveit / "package.xml", PACKAGE_XML.format(moveit.name))
        srdfs[dof] = write(moveit / "config" / "arm.srdf", GOOD)
        write(
            moveit / ".setup_assistant",
            "moveit_setup_assistant_config:\n  urdf:\n    package: arm_description\n"
            "    relative_path: robots/arm.urdf.xacro\n"
            f"    xacro_args: gripper:=robotiq_2f_85 dof:={dof}\n"
            "  srdf:\n    relative_path: config/arm.srdf\n",
        )
    for dof in ("6", "7"):
        args = {"dof": dof, "gripper": "robotiq_2f_85"}
        assert found(entry, xacro_args=args) == (srdfs[dof], ANY, "setup-assistant")
    assert found(entry, xacro_args={"dof": "7"}) is None  # no gripper: neither variant
    assert found(entry) is None  # the defaults: neither


def test_no_srdf_no_findings(tmp_path: Path) -> None:
    urdf = write(tmp_path / "arm.urdf", URDF)
    assert found(urdf) is None
    assert srdf_source.disabled_pairs(load(urdf)) == set()
    assert m_findings(urdf) == []


def test_disabled_pairs(tmp_path: Path) -> None:
    urdf = write(tmp_path / "arm.urdf", URDF)
    write(tmp_path / "arm.srdf", GOOD)
    pairs = srdf_source.disabled_pairs(load(urdf))
    assert pairs == {
        frozenset({"base_link", "upper_arm"}),
        frozenset({"upper_arm", "forearm"}),
        frozenset({"hand", "finger"}),
    }


def test_the_srdf_is_parsed_once_per_document(tmp_path: Path) -> None:
    urdf = write(tmp_path / "arm.urdf", URDF)
    write(tmp_path / "arm.srdf", GOOD)
    doc = load(urdf)
    assert srdf_source.load(doc) is srdf_source.load(doc)


# -- unreadable SRDF ---------------------------------------------------------------------------


def test_malformed_srdf_is_one_finding(tmp_path: Path) -> None:
    urdf = write(tmp_path / "arm.urdf", URDF)
    srdf = write(tmp_path / "arm.srdf", GOOD.replace("  </group>\n", "  </grup>\n", 1))
    assert m_findings(urdf) == [(str(srdf), 6, "M001", "/robot")]


def test_srdf_with_a_doctype_is_refused(tmp_path: Path) -> None:
    urdf = write(tmp_path / "arm.urdf", URDF)
    bomb = GOOD.replace(
        '<?xml version="1.0"?>\n',
        '<?xml version="1.0"?>\n<!DOCTYPE r [<!ENTITY a "aaaa">]>\n',
    ).replace('name="arm"', 'name="&a;"', 1)
    srdf = write(tmp_path / "arm.srdf", bomb)
    found_ = m_findings(urdf)
    assert [(p, c) for p, _, c, _ in found_] == [(str(srdf), "M001")]


def test_missing_explicit_srdf(tmp_path: Path) -> None:
    urdf = write(tmp_path / "arm.urdf", URDF)
    missing = tmp_path / "nope.srdf"
    findings = lint_file(urdf, settings=config.Settings(select=("M",), srdf=missing))
    assert [(f.code, f.path, f.line) for f in findings] == [("M001", str(missing), 1)]
    assert "does not exist" in findings[0].message


@pytest.mark.skipif(not optional.available("xacro"), reason="xacro is not installed")
def test_srdf_xacro_is_expanded_and_points_at_its_source(tmp_path: Path) -> None:
    urdf = write(tmp_path / "arm.urdf", URDF)
    include = STALE.replace('<?xml version="1.0"?>\n<robot name="arm">', "<robot>")
    include = include.replace(
        "<robot>", '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n<xacro:macro name="m">'
    ).replace("</robot>", "</xacro:macro>\n</robot>")
    write(tmp_path / "macro.srdf.xacro", include)
    srdf = write(
        tmp_path / "arm.srdf.xacro",
        '<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="arm">\n'
        '  <xacro:include filename="macro.srdf.xacro"/>\n  <xacro:m/>\n</robot>\n',
    )
    assert found(urdf) == (srdf, str(srdf), "beside")
    findings = lint_file(urdf, settings=config.Settings(select=("M",)))
    assert [(Path(f.path).name, f.line, f.code) for f in findings] == [
        ("macro.srdf.xacro", 25, "M009")
    ]


# -- the command line --------------------------------------------------------------------------


def test_cli_srdf_option(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    urdf = write(tmp_path / "arm.urdf", URDF)
    srdf = write(tmp_path / "semantic" / "robot.srdf", STALE)
    code = main(["check", "--format", "json", "--select", "M", "--srdf", str(srdf), str(urdf)])
    out = json.loads(capsys.readouterr().out)
    assert code == 0  # M009 is a warning
    (finding,) = out["findings"]
    assert finding["code"] == "M009"
    assert finding["path"] == str(srdf)
    assert finding["line"] == 25
    assert finding["element"] == "/robot/disable_collisions[2]"
