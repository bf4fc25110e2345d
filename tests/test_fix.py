"""``urdflint fix``: each fixable rule's bad fixtures become their ``fixed/`` twins byte for
byte, fixes converge, and everything else in the file is kept."""

from __future__ import annotations

import json
import shutil
import tomllib
from pathlib import Path

import pytest

from tests.conftest import FIXTURES
from tests.helpers import fixture_settings
from urdflint.cli import main
from urdflint.engine import config, fixes, linter, registry
from urdflint.model import edits as E

RULES = sorted(registry.load_rules().values(), key=lambda r: r.code)
FIXABLE = [r for r in RULES if r.fixable]


def pairs() -> list:
    found = []
    for rule in FIXABLE:
        folder = FIXTURES / "rules" / rule.code
        for expected in sorted((folder / "fixed").glob("*.urdf")):
            found.append(
                pytest.param(
                    rule, folder / expected.name, expected, id=f"{rule.code}/{expected.name}"
                )
            )
    return found


def copy_fixture(bad: Path, tmp_path: Path) -> Path:
    """The fixture (and its settings file and folders) in a folder of its own."""
    target = tmp_path / bad.name
    shutil.copyfile(bad, target)
    folders = [p for p in bad.parent.iterdir() if p.is_dir() and p.name != "fixed"]
    for extra in (bad.with_suffix(".toml"), bad.parent / "config.toml", *folders):  # meshes/...
        if extra.is_file():
            shutil.copyfile(extra, tmp_path / extra.name)
        elif extra.is_dir():
            shutil.copytree(extra, tmp_path / extra.name)
    return target


def fix_file(path: Path, code: str, unsafe: bool) -> int:
    argv = ["fix", "--isolated", "--select", code, "--exit-zero", str(path)]
    toml = path.with_suffix(".toml")
    if not toml.is_file():
        toml = path.parent / "config.toml"  # the folder's (fixture_settings reads it too)
    if toml.is_file():
        data = config.from_mapping(tomllib.loads(toml.read_text()))
        argv += [f"--target={t}" for t in data.targets]
        if data.rule_options.get("C001", {}).get("write_meshes"):
            argv.append("--write-meshes")
    return main(argv + (["--unsafe-fixes"] if unsafe else []))


# Fixes that need an absolute path on this machine: their pair is built in a temporary folder
# (test_c014_absolute_path_becomes_the_package_uri below).
MACHINE_PAIRS = {"C014"}


@pytest.mark.parametrize(
    "rule", [r for r in FIXABLE if r.code not in MACHINE_PAIRS], ids=lambda r: r.code
)
def test_every_fixable_rule_has_a_fixture_pair(rule: registry.Rule) -> None:
    assert list((FIXTURES / "rules" / rule.code / "fixed").glob("*.urdf")), rule.code


def test_c014_absolute_path_becomes_the_package_uri(tmp_path: Path, capsys) -> None:
    package = tmp_path / "arm_description"
    (package / "meshes").mkdir(parents=True)
    (package / "package.xml").write_text(
        '<package format="3"><name>arm_description</name><version>1.0.0</version>'
        "<description>d</description><maintainer email='a@b.c'>a</maintainer>"
        "<license>BSD</license></package>"
    )
    (package / "meshes" / "base.stl").write_bytes(
        (FIXTURES / "rules" / "C008" / "meshes" / "box.stl").read_bytes()
    )
    (package / "urdf").mkdir()
    path = package / "urdf" / "arm.urdf"
    template = (
        '<?xml version="1.0"?>\n<robot name="arm">\n  <link name="base_link">\n'
        '    <visual>\n      <geometry>\n        <mesh filename="{}"/>\n'
        "      </geometry>\n    </visual>\n  </link>\n</robot>\n"
    )
    path.write_text(template.format(f"file://{package}/meshes/base.stl"))
    fix_file(path, "C014", unsafe=True)
    assert path.read_text() == template.format("package://arm_description/meshes/base.stl")
    again = path.read_bytes()
    fix_file(path, "C014", unsafe=True)
    assert path.read_bytes() == again
    capsys.readouterr()


@pytest.mark.parametrize(("rule", "bad", "expected"), pairs())
def test_fix_gives_the_expected_text_and_converges(
    rule, bad: Path, expected: Path, tmp_path, capsys
) -> None:
    path = copy_fixture(bad, tmp_path)
    fix_file(path, rule.code, unsafe=rule.fixable == "unsafe")
    assert path.read_bytes() == expected.read_bytes()
    again = path.read_bytes()
    fix_file(path, rule.code, unsafe=True)
    assert path.read_bytes() == again  # a second run changes nothing
    settings = fixture_settings(bad)
    settings = config.Settings(**{**settings.__dict__, "select": (rule.code,)})
    left = [f for f in linter.lint_path(path, str(path), settings).findings if f.code == rule.code]
    assert all(f.autofix is None or f.autofix.unavailable for f in left), left
    capsys.readouterr()


def test_unsafe_fixes_wait_for_the_flag(tmp_path: Path, capsys) -> None:
    path = copy_fixture(FIXTURES / "rules" / "J009" / "bad.urdf", tmp_path)
    before = path.read_bytes()
    main(["fix", "--isolated", "--select", "J009", str(path)])
    assert path.read_bytes() == before
    assert "more with --unsafe-fixes" in capsys.readouterr().err


def test_diff_changes_nothing_and_exits_one(tmp_path: Path, capsys) -> None:
    path = copy_fixture(FIXTURES / "rules" / "J008" / "bad.urdf", tmp_path)
    before = path.read_bytes()
    assert main(["check", "--diff", "--isolated", "--select", "J008", str(path)]) == 1
    out = capsys.readouterr().out
    assert path.read_bytes() == before
    assert out.startswith(f"--- {path}\n+++ {path}\n@@ ")
    assert main(["check", "--diff", "--isolated", "--select", "J011", str(path)]) == 0


def test_json_carries_the_fix(tmp_path: Path, capsys) -> None:
    path = copy_fixture(FIXTURES / "rules" / "J008" / "bad.urdf", tmp_path)
    main(["check", "--format", "json", "--isolated", "--select", "J008", str(path)])
    finding = json.loads(capsys.readouterr().out)["findings"][0]
    fix = finding["autofix"]
    assert fix["applicability"] == "safe" and fix["description"].startswith("normalise")
    (edit,) = fix["edits"]
    assert set(edit) == {"path", "start", "end", "content", "offsets"}
    assert edit["start"]["line"] == finding["line"]
    start, end = edit["offsets"]  # the bytes of the file that "content" replaces
    data = path.read_bytes()
    assert len(data[:start].decode().splitlines()) == edit["start"]["line"]
    assert 0 <= start <= end <= len(data)


def test_fix_refuses_standard_input(capsys) -> None:
    assert main(["fix", "-"]) == 2
    assert "need files" in capsys.readouterr().err


def test_edits_keep_everything_else() -> None:
    data = (
        b"<robot>\r\n  <!-- keep -->\r\n  <a x=\"1\"  y='2'/>\r\n"
        b"  <b>\r\n    <c/>\r\n  </b>\r\n</robot>\r\n"
    )
    a = data.index(b"<a")
    b = data.index(b"<b")
    span = E.attribute_span(data, a, "y")
    assert span is not None and data[span[1] : span[2]] == b"2"
    start, end = E.line_span(data, b, E.element_end(data, b))
    assert data[start:end] == b"  <b>\r\n    <c/>\r\n  </b>\r\n"
    new, left = E.apply(data, [E.Edit("f", span[1], span[2], "3"), E.Edit("f", start, end, "")])
    assert (
        left == [] and new == b"<robot>\r\n  <!-- keep -->\r\n  <a x=\"1\"  y='3'/>\r\n</robot>\r\n"
    )
    assert E.newline(data) == "\r\n"


def test_overlapping_edits_wait_for_the_next_round() -> None:
    data = b"abcdef"
    new, left = E.apply(data, [E.Edit("f", 0, 3, "X"), E.Edit("f", 2, 4, "Y")])
    assert new == b"Xdef" and [e.text for e in left] == ["Y"]


def test_fixes_cache_is_cleared() -> None:
    fixes.forget_files()
    assert fixes._FILES == {}


MACRO = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm" params="name parent ax">
    <joint name="${name}_j" type="revolute">
      <parent link="${parent}"/>
      <child link="${name}"/>
      <axis xyz="${ax}"/>
      <limit lower="1" upper="-1" effort="1" velocity="1"/>
    </joint>
    <joint name="${name}_f" type="fixed">
      <parent link="${name}"/>
      <child link="${name}_tip"/>
      <axis xyz="0 0 2"/>
    </joint>
    <link name="${name}"><inertial><mass value="1"/>
      <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
    <link name="${name}_tip"/>
  </xacro:macro>
</robot>
"""
ENTRY = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="parts.xacro"/>
  <link name="base"><inertial><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <xacro:arm name="a" parent="base" ax="0 0 3"/>
</robot>
"""


def test_xacro_fixes_go_to_the_macro_and_skip_computed_values(tmp_path: Path, capsys) -> None:
    (tmp_path / "parts.xacro").write_text(MACRO)
    entry = tmp_path / "robot.urdf.xacro"
    entry.write_text(ENTRY)
    main(["fix", "--isolated", "--unsafe-fixes", "--exit-zero", str(entry)])
    out = capsys.readouterr().out
    assert entry.read_text() == ENTRY  # nothing to fix is written in the entry file
    fixed = (tmp_path / "parts.xacro").read_text()
    assert '<limit lower="-1" upper="1" effort="1" velocity="1"/>' in fixed  # J009, unsafe
    assert 'xyz="0 0 2"' not in fixed  # J006: the fixed joint's axis is gone
    assert '<axis xyz="${ax}"/>' in fixed  # J008: computed by xacro, left alone
    assert "J008" in out and "[fix]" not in out.split("J008", 1)[1].splitlines()[0]
    main(["check", "--isolated", "--format", "json", "--select", "J008", str(entry)])
    (finding,) = json.loads(capsys.readouterr().out)["findings"]
    assert finding["autofix"]["unavailable"].startswith("the value is computed by xacro (${ax})")
