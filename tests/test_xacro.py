"""Xacro input: expansion without ROS, $(find), args, errors as findings, line mapping, guards."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from lxml import etree

from tests.conftest import FIXTURES, corpus_models, needs_corpus
from tests.helpers import expectations
from urdflint.engine import config, linter
from urdflint.engine.context import Context
from urdflint.model.finding import Finding, Severity
from urdflint.sources import xacro as xacro_input

pytest.importorskip("xacro")

RRBOT = FIXTURES / "xacro" / "rrbot"
MAIN = RRBOT / "urdf" / "rrbot.xacro"
NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def lint(
    path: Path,
    shown: str | None = None,
    *,
    context: Context | None = None,
    **settings: object,
) -> linter.Result:
    """Lint like the CLI does; no environment package paths unless the context gives them."""
    return linter.lint_path(
        path,
        shown or str(path),
        config.Settings(**settings),  # type: ignore[arg-type]
        context or Context(environ={}),
    )


def codes(findings: list[Finding]) -> list[str]:
    return [f.code for f in findings]


def line_of(path: Path, needle: str, start: str | None = None) -> int:
    """1-based line of the first ``needle`` (after the first ``start``, if given)."""
    text = path.read_text(encoding="utf-8")
    offset = text.index(start) if start else 0
    return text[: text.index(needle, offset)].count("\n") + 1


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(textwrap.dedent(text).lstrip(), encoding="utf-8")
    return path


@pytest.fixture
def rrbot(tmp_path: Path) -> Path:
    """A copy of the RRBot layout (package.xml included) to edit."""
    folder = tmp_path / "rrbot_description"
    shutil.copytree(RRBOT, folder)
    return folder


def edit(path: Path, old: str, new: str, after: str | None = None) -> None:
    text = path.read_text(encoding="utf-8")
    start = text.index(after) if after else 0
    index = text.index(old, start)
    path.write_text(text[:index] + new + text[index + len(old) :], encoding="utf-8")


def run_cli(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    env = {"PATH": "/usr/bin:/bin", "PYTHONPATH": str(Path(__file__).resolve().parent.parent)}
    return subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--isolated", *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        env=env,
        timeout=120,
    )


# -- the RRBot layout -------------------------------------------------------------------


def test_rrbot_expands_and_is_clean() -> None:
    result = lint(MAIN)
    doc = result.document
    assert doc is not None and doc.ok and not doc.library
    assert {link.name for link in doc.links} == {"world", "link1", "link2", "link3", "camera_link"}
    assert {t.get("name") for t in doc.transmissions} == {"tran1", "tran2"}
    assert len(doc.material_map) == 3  # from materials.xacro
    assert [g.get("reference") for g in doc.gazebo][1:] == [
        "link1",
        "link2",
        "link3",
        "camera_link",
    ]
    # P002 is the one note: the robot is welded to 'world', so Pinocchio's fixed-base
    # computeTotalMass leaves link1 out, which is exactly what P002 explains.
    assert all(f.severity is Severity.INFO for f in result.findings), result.findings
    assert set(codes(result.findings)) <= {"P002", "U004"}


def test_defects_point_into_the_file_and_line_that_wrote_them(rrbot: Path) -> None:
    main, gazebo = rrbot / "urdf" / "rrbot.xacro", rrbot / "urdf" / "rrbot.gazebo"
    edit(main, '<mass value="${mass}"/>', '<mass value="-1"/>', after='<link name="link2">')
    edit(gazebo, '<gazebo reference="link3">', '<gazebo reference="link4">')
    result = lint(main, "robot/urdf/rrbot.xacro")
    found = {f.code: f for f in result.findings}

    mass = found["I002"]
    assert mass.path == "robot/urdf/rrbot.xacro"
    assert mass.line == line_of(main, '<mass value="-1"/>')
    assert mass.column == 13 and "expanded document" not in mass.message  # at value="-1"
    assert mass.element == "/robot/link[@name='link2']/inertial/mass"

    reference = found["G001"]
    assert reference.path == "robot/urdf/rrbot.gazebo"
    assert reference.line == line_of(gazebo, '<gazebo reference="link4">')
    assert reference.column == 3


def test_json_paths_name_the_xacro_and_gazebo_files(rrbot: Path) -> None:
    main, gazebo = rrbot / "urdf" / "rrbot.xacro", rrbot / "urdf" / "rrbot.gazebo"
    edit(main, '<axis xyz="0 1 0"/>', '<axis xyz="0 0 0"/>', after='<joint name="joint2"')
    edit(gazebo, '<gazebo reference="link3">', '<gazebo reference="link4">')
    proc = run_cli("--format", "json", "--select", "J,G", "urdf/rrbot.xacro", cwd=rrbot)
    assert proc.returncode == 1 and proc.stderr == ""
    report = json.loads(proc.stdout)
    where = {(f["code"], f["path"], f["line"]) for f in report["findings"]}
    assert ("J007", "urdf/rrbot.xacro", line_of(main, '<axis xyz="0 0 0"/>')) in where
    assert ("G001", "urdf/rrbot.gazebo", line_of(gazebo, "link4")) in where


def test_macro_output_is_located_in_the_macro_with_its_call(rrbot: Path) -> None:
    main = rrbot / "urdf" / "rrbot.xacro"
    edit(main, 'm="${mass}"', 'm="${-mass}"', after='<link name="link3">')
    proc = run_cli("--select", "I003", "urdf/rrbot.xacro", cwd=rrbot)
    assert proc.returncode == 1 and proc.stderr == ""
    first, called = proc.stdout.splitlines()[:2]
    # the <inertia> comes out of the box_inertia macro: the finding is on the macro's line,
    # and the call with the bad argument follows
    inertia = line_of(main, "<inertia ", start='name="box_inertia"')
    call = line_of(main, 'm="${-mass}"')
    assert first.startswith(f"urdf/rrbot.xacro:{inertia}:5: error I003 ")
    assert "expanded document" not in first
    assert called == f"    in macro `box_inertia`, called from urdf/rrbot.xacro:{call}:7"


def test_emit_expanded_writes_the_urdf_that_was_checked(tmp_path: Path) -> None:
    out = tmp_path / "rrbot.urdf"
    proc = run_cli("--select", "X", "--emit-expanded", str(out), str(MAIN))
    assert proc.returncode == 0, proc.stdout + proc.stderr
    root = etree.parse(str(out)).getroot()
    assert root.tag == "robot" and len(root.findall("link")) == 5
    text = out.read_text()
    assert "<xacro:" not in text and "${" not in text and "xmlns:xacro" not in text
    again = linter.lint_path(out, str(out), config.Settings(select=("X", "S", "J")), Context())
    assert [f for f in again.findings if f.severity > Severity.INFO] == []


def test_emit_expanded_writes_no_file_when_xacro_fails(tmp_path: Path) -> None:
    """No 0-byte file, and no stale one from an earlier run passing for this one's (issue 25)."""
    broken = tmp_path / "broken.urdf.xacro"
    broken.write_text(f'<robot name="r" {NS}><link name="${{nowhere}}"/></robot>\n')
    out = tmp_path / "out.urdf"
    out.write_text("an earlier expansion\n")
    proc = run_cli("--emit-expanded", str(out), str(broken))
    assert proc.returncode == 1 and "X010" in proc.stdout
    assert not out.exists()


def test_emit_expanded_needs_one_xacro_file(tmp_path: Path) -> None:
    other = RRBOT / "urdf" / "materials.xacro"
    proc = run_cli("--emit-expanded", str(tmp_path / "x.urdf"), str(MAIN), str(other))
    assert proc.returncode == 2 and "exactly one xacro file" in proc.stderr


def test_xacro_args_change_the_model() -> None:
    with_camera = lint(MAIN, select=("X",)).document
    without = lint(MAIN, select=("X",), xacro_args={"camera": "false"}).document
    assert with_camera is not None and without is not None
    assert "camera_link" in with_camera.link_map and "camera_link" not in without.link_map
    refs = [g.get("reference") for g in without.gazebo]
    assert "camera_link" not in refs  # the include saw the same argument


def test_xacro_arg_on_the_command_line() -> None:
    proc = run_cli("--select", "S,G", "--xacro-arg", "camera:=false", "--format", "json", str(MAIN))
    assert proc.returncode == 0, proc.stdout
    proc = run_cli("--select", "X010", "--xacro-arg", "camera:=maybe", str(MAIN))
    assert proc.returncode == 1 and "X010" in proc.stdout and "not a boolean" in proc.stdout


# -- $(find pkg) ------------------------------------------------------------------------


def test_find_uses_package_xml_upward() -> None:
    doc = lint(MAIN, context=Context(environ={})).document
    assert doc is not None and doc.ok


def test_find_uses_package_path(rrbot: Path, tmp_path: Path) -> None:
    (rrbot / "package.xml").unlink()
    main = rrbot / "urdf" / "rrbot.xacro"
    result = lint(main, select=("X",))
    assert codes(result.findings) == ["X010"]
    message = result.findings[0].message
    assert "package 'rrbot_description' was not found" in message
    assert result.findings[0].line == line_of(main, "$(find rrbot_description)", "<xacro:include")

    context = Context(package_paths={"rrbot_description": rrbot}, environ={})
    assert codes(lint(main, select=("X",), context=context).findings) == []
    proc = run_cli("--select", "X", "--package-path", f"rrbot_description={rrbot}", str(main))
    assert proc.returncode == 0, proc.stdout
    moved = tmp_path / "elsewhere"
    shutil.move(rrbot, moved)  # relative package paths work from the current folder
    proc = run_cli(
        *("--select", "X", "--package-path", "rrbot_description=elsewhere"),
        "elsewhere/urdf/rrbot.xacro",
        cwd=tmp_path,
    )
    assert proc.returncode == 0, proc.stdout


def test_find_uses_ros_package_path(rrbot: Path) -> None:
    (rrbot / "package.xml").rename(rrbot / "package.bak")
    (rrbot.parent / "ws" / "src" / "rrbot_description").mkdir(parents=True)
    (rrbot.parent / "ws" / "src" / "rrbot_description" / "package.xml").write_text(
        "<package><name>rrbot_description</name></package>"
    )
    shutil.copytree(rrbot / "urdf", rrbot.parent / "ws" / "src" / "rrbot_description" / "urdf")
    context = Context(environ={"ROS_PACKAGE_PATH": str(rrbot.parent / "ws" / "src")})
    assert (
        codes(lint(rrbot / "urdf" / "rrbot.xacro", select=("X",), context=context).findings) == []
    )


# -- expansion errors -------------------------------------------------------------------

TRANSMISSION = '<xacro:simple_transmission number="2"/>'
ERRORS = {
    "undefined-property": (
        "rrbot.xacro",
        'value="${mass}"',
        'value="${mas}"',
        "name 'mas' is not defined",
    ),
    "missing-include": ("rrbot.xacro", "urdf/materials.xacro", "urdf/colours.xacro", "cannot read"),
    "bad-xml-in-include": ("rrbot.gazebo", "</plugin>", "</plugn>", "mismatched tag"),
    "unknown-macro": (
        "rrbot.xacro",
        TRANSMISSION,
        TRANSMISSION.replace("transmission", "transmision"),
        "unknown macro name: xacro:simple_transmision",
    ),
    "undeclared-arg": (
        "rrbot.xacro",
        '<xacro:arg name="camera" default="true"/>',
        "",
        "xacro argument 'camera' has no value",
    ),
    "macro-parameter": (
        "rrbot.xacro",
        TRANSMISSION,
        TRANSMISSION.replace("/>", ' ratio="3"/>'),
        'invalid parameter "ratio"',
    ),
    "recursion": (
        "rrbot.xacro",
        TRANSMISSION,
        '<xacro:macro name="loop"><xacro:loop/></xacro:macro><xacro:loop/>',
        "recursed too deeply",
    ),
}


@pytest.mark.parametrize("case", sorted(ERRORS))
def test_expansion_error_is_one_x010_finding(rrbot: Path, case: str) -> None:
    name, old, new, expected = ERRORS[case]
    edit(rrbot / "urdf" / name, old, new)
    main = rrbot / "urdf" / "rrbot.xacro"
    found = lint(main).findings
    assert codes(found) == ["X010"], found
    assert expected in found[0].message
    assert found[0].element == "/robot"
    if case in ("bad-xml-in-include", "undeclared-arg"):  # the cause is in rrbot.gazebo
        gazebo = rrbot / "urdf" / "rrbot.gazebo"
        needle = "</plugn>" if case == "bad-xml-in-include" else "$(arg camera)"
        assert (found[0].path, found[0].line) == (str(gazebo), line_of(gazebo, needle))
    else:
        assert found[0].path == str(main)


def test_expansion_error_lines_point_at_the_cause(rrbot: Path) -> None:
    main = rrbot / "urdf" / "rrbot.xacro"
    edit(main, 'value="${mass}"', 'value="${mas}"', after='<link name="link2">')
    [finding] = lint(main).findings
    assert finding.line == line_of(main, "${mas}") and finding.column > 1
    edit(main, "${mas}", "${mass}")
    edit(main, "urdf/materials.xacro", "urdf/colours.xacro")
    [finding] = lint(main).findings
    assert (finding.line, finding.column) == (line_of(main, "colours.xacro"), 3)


def test_expansion_error_from_the_cli_has_no_traceback(rrbot: Path) -> None:
    edit(rrbot / "urdf" / "rrbot.gazebo", "</plugin>", "</plugn>")
    proc = run_cli("urdf/rrbot.xacro", cwd=rrbot)
    assert proc.returncode == 1
    assert proc.stderr == ""
    assert "Traceback" not in proc.stdout and "X010" in proc.stdout
    assert proc.stdout.count("\n") == 2  # the finding and the summary


def test_yaml_error_names_the_yaml_file(rrbot: Path) -> None:
    main = rrbot / "urdf" / "rrbot.xacro"
    edit(
        main,
        '<xacro:property name="mass" value="1"/>',
        '<xacro:property name="cfg" value="${xacro.load_yaml(\'cfg.yaml\')}"/>'
        '<xacro:property name="mass" value="${cfg.mass}"/>',
    )
    (rrbot / "urdf" / "cfg.yaml").write_text("mass: [1\n")
    [finding] = lint(main).findings
    assert finding.code == "X010" and "cfg.yaml line 2" in finding.message
    assert '"<file>"' not in finding.message
    (rrbot / "urdf" / "cfg.yaml").write_text("mass: 2\n")
    doc = lint(main).document
    assert (
        doc is not None and doc.robot.find("link[@name='link1']/inertial/mass").get("value") == "2"
    )


def test_xacro_console_output_is_captured(tmp_path: Path) -> None:
    path = write(
        tmp_path / "talk.xacro",
        f"""
        <robot name="talk" {NS}>
          <xacro:property name="pi" value="3"/>
          <link name="a${{xacro.warning('boo')}}${{xacro.message('hello')}}"/>
        </robot>
        """,
    )
    proc = run_cli("--select", "X", str(path))
    assert proc.returncode == 0 and proc.stderr == ""
    assert "boo" not in proc.stdout and "hello" not in proc.stdout


def test_missing_xacro_package_is_a_finding(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "xacro", None)
    [finding] = lint(MAIN).findings
    assert finding.code == "X010"
    assert "the xacro package, a dependency of urdflint, is not installed" in finding.message


# -- libraries and fragments ------------------------------------------------------------


def test_library_file_is_x011_only() -> None:
    found = lint(RRBOT / "urdf" / "materials.xacro").findings
    assert codes(found) == ["X011"]
    [note] = [f for f in found if f.code == "X011"]
    assert note.severity is Severity.INFO and "3 <material>" in note.message
    assert note.line == line_of(RRBOT / "urdf" / "materials.xacro", "<robot")


def test_library_robot_needs_no_name() -> None:
    assert codes(lint(RRBOT / "urdf" / "materials.xacro").findings) == ["X011"]


def test_macro_only_file_is_a_library(tmp_path: Path) -> None:
    path = write(
        tmp_path / "macros.xacro",
        f"""
        <robot name="macros" {NS}>
          <xacro:macro name="wheel" params="side">
            <link name="${{side}}_wheel"/>
          </xacro:macro>
        </robot>
        """,
    )
    result = lint(path)
    assert (
        codes(result.findings) == ["X011"] and "only defines macros" in result.findings[0].message
    )
    assert result.document is not None and result.document.library


def test_fragment_is_a_library_when_its_includer_defines_what_it_uses() -> None:
    gazebo = RRBOT / "urdf" / "rrbot.gazebo"  # uses $(arg camera), declared by rrbot.xacro
    settings = config.Settings()
    doc = xacro_input.document(gazebo, "urdf/rrbot.gazebo", settings, Context(environ={}))
    assert doc.library and not doc.ok
    found = linter.lint_document(doc, settings).findings
    assert codes(found) == ["X011"]
    assert "fragment of" in found[0].message and "rrbot.xacro" in found[0].message


def test_undefined_name_without_an_includer_is_an_error(tmp_path: Path) -> None:
    path = write(
        tmp_path / "lonely.xacro",
        f"""
        <robot name="lonely" {NS}>
          <link name="${{prefix}}base"/>
        </robot>
        """,
    )
    assert codes(lint(path).findings) == ["X010"]


# -- line mapping ---------------------------------------------------------------------------


def mapped(tmp_path: Path, text: str, **files: str) -> linter.Result:
    for name, body in files.items():
        write(tmp_path / name, body)
    return lint(write(tmp_path / "robot.xacro", text), "robot.xacro", select=("X",))


def origin_of(result: linter.Result, xpath: str) -> tuple[str, int, bool]:
    doc = result.document
    assert doc is not None and doc.origin is not None
    [el] = doc.robot.xpath(xpath)
    origin = doc.origin(el)
    assert origin is not None
    return origin.path, origin.line, origin.exact


def test_mapping_follows_literal_children_through_conditions(tmp_path: Path) -> None:
    result = mapped(
        tmp_path,
        f"""
        <robot name="r" {NS}>
          <xacro:property name="m" value="2"/>
          <link name="a">
            <xacro:if value="true">
              <visual><geometry><sphere radius="0.1"/></geometry></visual>
            </xacro:if>
            <visual>
              <geometry><box size="1 1 1"/></geometry>
            </visual>
            <inertial>
              <mass value="${{m}}"/>
            </inertial>
          </link>
        </robot>
        """,
    )
    assert origin_of(result, "/robot") == ("robot.xacro", 1, True)
    assert origin_of(result, "/robot/link[@name='a']") == ("robot.xacro", 3, True)
    assert origin_of(result, "//visual[2]/geometry/box") == ("robot.xacro", 8, True)
    assert origin_of(result, "//visual[1]/geometry/sphere") == ("robot.xacro", 5, True)
    assert origin_of(result, "//inertial/mass") == ("robot.xacro", 11, True)


def test_mapping_traces_macros_names_and_repeats(tmp_path: Path) -> None:
    result = mapped(
        tmp_path,
        f"""
        <robot name="r" {NS}>
          <xacro:property name="p" value="left_"/>
          <xacro:macro name="vis">
            <visual><geometry><sphere radius="0.1"/></geometry></visual>
          </xacro:macro>
          <link name="${{p}}arm"/>
          <link name="a">
            <xacro:vis/>
            <visual><geometry><box size="1 1 1"/></geometry></visual>
          </link>
          <link name="twice"/>
          <link name="twice"/>
        </robot>
        """,
    )
    assert origin_of(result, "/robot/link[@name='left_arm']") == ("robot.xacro", 6, True)
    assert origin_of(result, "//link[@name='a']/visual[1]/geometry/sphere") == (
        "robot.xacro",
        4,
        True,
    )
    assert origin_of(result, "//link[@name='a']/visual[2]") == ("robot.xacro", 9, True)
    assert origin_of(result, "//link[@name='a']")[1:] == (7, True)
    assert origin_of(result, "/robot/link[@name='twice'][1]")[1:] == (11, True)
    assert origin_of(result, "/robot/link[@name='twice'][2]")[1:] == (12, True)
    doc = result.document
    assert doc is not None and doc.origin is not None
    [sphere] = doc.robot.xpath("//sphere")
    origin = doc.origin(sphere)
    assert origin is not None
    assert [(c.macro, c.path, c.line, c.column) for c in origin.trace] == [
        ("vis", "robot.xacro", 8, 5)
    ]


def test_mapping_tells_definitions_from_references(tmp_path: Path) -> None:
    result = mapped(
        tmp_path,
        f"""
        <robot name="r" {NS}>
          <xacro:include filename="parts/colours.xacro"/>
          <link name="a">
            <visual>
              <geometry><box size="1 1 1"/></geometry>
              <material name="red"/>
            </visual>
          </link>
          <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
          <link name="b"/>
          <transmission name="t">
            <joint name="j"/>
          </transmission>
        </robot>
        """,
        **{
            "parts/colours.xacro": f"""
            <robot {NS}>
              <!-- the one red -->
              <material name="red">
                <color rgba="1 0 0 1"/>
              </material>
            </robot>
            """
        },
    )
    assert origin_of(result, "/robot/material[@name='red']") == ("parts/colours.xacro", 3, True)
    assert origin_of(result, "/robot/material/color") == ("parts/colours.xacro", 4, True)
    assert origin_of(result, "//visual/material") == ("robot.xacro", 6, True)
    assert origin_of(result, "/robot/joint[@name='j']") == ("robot.xacro", 9, True)
    assert origin_of(result, "/robot/transmission/joint") == ("robot.xacro", 12, True)
    doc = result.document
    assert doc is not None and doc.origin is not None
    comment = next(c for c in doc.robot.iter(etree.Comment) if "the one red" in c.text)
    assert doc.origin(comment) == xacro_input.Origin("parts/colours.xacro", 2, 3, True)


# -- state, guards, confinement -------------------------------------------------------------


def test_xacro_state_does_not_leak_between_files(tmp_path: Path) -> None:
    first = write(
        tmp_path / "a.xacro",
        f"""
        <robot name="a" {NS}>
          <xacro:arg name="side" default="left"/>
          <xacro:property name="size" value="1"/>
          <xacro:macro name="thing"><link name="thing"/></xacro:macro>
          <xacro:thing/>
        </robot>
        """,
    )
    second = write(
        tmp_path / "b.xacro",
        f"""
        <robot name="b" {NS}>
          <link name="b_${{size}}"/>
        </robot>
        """,
    )
    third = write(
        tmp_path / "c.xacro",
        f"""
        <robot name="c" {NS}>
          <link name="c_$(arg side)"/>
        </robot>
        """,
    )
    context = Context(environ={})
    ros = ("ros",)  # frames only: for a simulator the lone link is I013's
    assert codes(lint(first, context=context, targets=ros).findings) == []
    assert codes(lint(second, context=context, targets=ros).findings) == ["X010"]
    assert codes(lint(third, context=context, targets=ros).findings) == ["X010"]
    assert codes(lint(first, context=context, targets=ros).findings) == []


def test_doctype_is_refused_in_the_main_file_and_in_includes(tmp_path: Path) -> None:
    laughs = (
        '<?xml version="1.0"?>\n<!DOCTYPE robot [\n <!ENTITY lol "lol">\n'
        ' <!ENTITY lol2 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">\n]>\n'
    )
    main = tmp_path / "main.xacro"
    main.write_text(laughs + f'<robot name="&lol2;" {NS}><link name="a"/></robot>\n')
    [finding] = lint(main).findings
    assert finding.code == "X002" and finding.line == 2 and "lol" not in finding.message

    part = tmp_path / "part.xacro"
    part.write_text(laughs + f'<robot {NS}><link name="&lol2;"/></robot>\n')
    main.write_text(f'<robot name="r" {NS}>\n  <xacro:include filename="part.xacro"/>\n</robot>\n')
    [finding] = lint(main).findings
    assert finding.code == "X002" and finding.line == 2
    assert "DOCTYPE" in finding.message
    assert (Path(finding.path).name, finding.line) == ("part.xacro", 2)
    # a DOCTYPE mentioned in a comment is not one
    part.write_text(f'<robot {NS}><!-- no <!DOCTYPE here --><link name="a"/></robot>\n')
    assert codes(lint(main, targets=("ros",)).findings) == []  # a lone link: I013 for Gazebo


def test_macro_bomb_stops(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from urdflint.sources.xacro import guards

    monkeypatch.setattr(guards, "MAX_MACRO_CALLS", 2_000)  # the same stop, a tenth of the way
    levels = ['<xacro:macro name="m0"><link name="l"/></xacro:macro>'] + [
        f'<xacro:macro name="m{i}"><xacro:m{i - 1}/><xacro:m{i - 1}/></xacro:macro>'
        for i in range(1, 30)
    ]
    path = tmp_path / "bomb.xacro"
    path.write_text(f'<robot name="b" {NS}>\n' + "\n".join(levels) + "\n<xacro:m29/>\n</robot>")
    [finding] = lint(path).findings
    assert finding.code == "X010" and "more than 2000 macro calls" in finding.message


@pytest.fixture
def jail(tmp_path: Path) -> Path:
    """``root/`` holds a package; ``secret.*`` lie outside it."""
    root = tmp_path / "root"
    shutil.copytree(RRBOT, root / "rrbot")
    (tmp_path / "secret.xacro").write_text(f'<robot {NS}><link name="secret"/></robot>')
    (tmp_path / "secret.yaml").write_text("name: secret\n")
    (root / "rrbot" / "urdf" / "inside.yaml").write_text("name: inside\n")
    return root


def confined(jail: Path, body: str, **environ: str) -> linter.Result:
    path = write(
        jail / "rrbot" / "urdf" / "probe.xacro", f'<robot name="p" {NS}>\n{body}\n</robot>\n'
    )
    context = Context(root=jail, environ=environ or None)
    return linter.lint_path(path, "rrbot/urdf/probe.xacro", config.Settings(select=("X",)), context)


@pytest.mark.parametrize(
    "body",
    [
        '<xacro:include filename="../../../secret.xacro"/>',
        '<xacro:include filename="{tmp}/secret.xacro"/>',
        "<link name=\"${{xacro.load_yaml('../../../secret.yaml').name}}\"/>",
        '<xacro:include filename="$(find outside)/secret.xacro"/>',
    ],
    ids=["relative", "absolute", "yaml", "find"],
)
def test_confined_expansion_reads_nothing_outside_root(jail: Path, body: str) -> None:
    result = confined(jail, body.format(tmp=jail.parent))
    assert codes(result.findings) == ["X010"]
    assert "secret" not in str(result.document.links if result.document.ok else "")
    message = result.findings[0].message
    assert "outside the allowed folder" in message or "not found" in message


def test_confined_find_and_yaml_work_inside_root(jail: Path) -> None:
    result = confined(
        jail,
        "<link name=\"${xacro.load_yaml('inside.yaml').name}\"/>\n"
        '<xacro:include filename="$(find rrbot_description)/urdf/materials.xacro"/>',
    )
    assert codes(result.findings) == ["X010"]  # no package paths given: nothing is searched
    path = jail / "rrbot" / "urdf" / "probe.xacro"
    context = Context(root=jail, package_paths={"rrbot_description": jail / "rrbot"})
    result = linter.lint_path(path, "probe.xacro", config.Settings(select=("X",)), context)
    assert result.document is not None and result.document.ok
    assert [link.name for link in result.document.links] == ["inside"]
    assert len(result.document.materials) == 3


def test_confined_glob_include_sees_nothing_outside(jail: Path) -> None:
    result = confined(jail, '<xacro:include filename="../../../*.xacro"/>\n<link name="a"/>')
    assert result.document is not None and [link.name for link in result.document.links] == ["a"]


@pytest.mark.parametrize(
    ("body", "expected"),
    [
        ('<link name="$(env HOME)"/>', "environment variable HOME is not set"),
        (
            "<link name=\"${python.vars(python.type(python.type(0)))['mro']"
            '(python.type(0))[1]}"/>',
            "'vars'",
        ),
        (
            "<link name=\"${('{0.__globals__[os].environ' + python.repr(python.dict())[1])"
            '.format(xacro.load_yaml)}"/>',
            "'format'",
        ),
        ('<link name="${(x for x in [1]).gi_frame}"/>', "'gi_frame'"),
    ],
    ids=["env", "vars", "format", "frame"],
)
def test_confined_expressions_cannot_reach_the_process(
    jail: Path, body: str, expected: str
) -> None:
    result = confined(jail, body)
    assert codes(result.findings) == ["X010"] and expected in result.findings[0].message
    assert result.findings[0].line == 2


def test_confined_environment_is_the_given_one(jail: Path) -> None:
    result = confined(jail, '<link name="$(env ROBOT)_$(optenv NONE dflt)"/>', ROBOT="bot")
    assert result.document is not None and result.document.links[0].name == "bot_dflt"


def test_main_file_outside_root_is_refused(jail: Path) -> None:
    context = Context(root=jail)
    outside = jail.parent / "secret.xacro"
    result = linter.lint_path(outside, "secret.xacro", config.Settings(), context)
    assert codes(result.findings) == ["X010"]


# -- fixtures of X010 and X011 (the generic runner reads *.urdf only) -----------------------


def _xacro_fixtures(prefix: str) -> list[object]:
    return [
        pytest.param(path, id=f"{path.parent.name}/{path.name}")
        for code in ("X010", "X011")
        for path in sorted((FIXTURES / "rules" / code).glob(f"{prefix}*.xacro"))
    ]


@pytest.mark.parametrize("path", _xacro_fixtures("bad"))
def test_bad_xacro_fixture_matches_expectations(path: Path) -> None:
    code = path.parent.name
    findings = [f for f in lint(path, select=(code,)).findings if f.code == code]
    files = {path} | {Path(f.path) for f in findings}  # an error in an include is reported there
    found = {(Path(f.path).name, f.line, f.code, f.element) for f in findings}
    assert found == {(p.name, *e) for p in files for e in expectations(p)}


@pytest.mark.parametrize("path", _xacro_fixtures("good"))
def test_good_xacro_fixture_is_clean(path: Path) -> None:
    found = lint(path).findings
    assert [f for f in found if f.code == path.parent.name] == []
    assert [f for f in found if f.severity is Severity.ERROR] == []


# -- real robots are unaffected ----------------------------------------------------------------


@needs_corpus
def test_corpus_urdf_files_do_not_go_through_xacro() -> None:
    for model in corpus_models():
        result = lint(model, select=("X",))
        assert result.document is not None and result.document.origin is None
        assert not {"X010", "X011"} & set(codes(result.findings)), model


def test_bad_xml_in_the_main_file_is_x001(tmp_path: Path) -> None:
    path = tmp_path / "bad.xacro"
    path.write_text(f'<robot name="r" {NS}>\n  <link name="a">\n</robot>\n')
    [finding] = lint(path).findings
    assert (finding.code, finding.line) == ("X001", 3) and "mismatched tag" in finding.message
