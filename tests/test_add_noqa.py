"""``check --add-noqa``: a suppression comment for every finding reported, written where the
finding is reported, extended rather than repeated, byte-preserving, idempotent, and only
when it works."""

from __future__ import annotations

import json
import os
import re
import shutil
from pathlib import Path

import pytest
from lxml import etree

from tests.conftest import CORPUS, FIXTURES, needs_corpus
from urdflint.cli import main
from urdflint.model import optional

BROKEN = FIXTURES / "models" / "broken_arm.urdf"
RRBOT = FIXTURES / "xacro" / "rrbot"
COMMENT = re.compile(rb"<!-- urdflint: ignore(?:-file)?\[[^\]]*\][^>]*-->")


def run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    code = main(["check", "--isolated", *args])
    out, err = capsys.readouterr()
    return code, out, err


def added(old: bytes, new: bytes) -> bool:
    """Whether ``new`` is ``old`` plus suppression comments and blanks around them."""
    return b"".join(COMMENT.sub(b"", new).split()) == b"".join(old.split())


def comments_before(path: Path) -> list[tuple[str, str]]:
    """Each comment line with the first word of the line after it."""
    lines = path.read_text(encoding="utf-8").splitlines()
    return [
        (line.strip(), lines[i + 1].split()[0])
        for i, line in enumerate(lines)
        if "urdflint: ignore" in line
    ]


@pytest.fixture
def arm(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    shutil.copy(BROKEN, tmp_path / "arm.urdf")
    monkeypatch.chdir(tmp_path)
    return tmp_path / "arm.urdf"


def test_a_comment_before_each_element_then_the_check_is_clean(capsys, arm: Path) -> None:
    code, out, err = run(capsys, "--add-noqa", "arm.urdf")
    assert (code, err) == (0, "")
    assert out == (
        "arm.urdf: 14 comments added (C003, G001, G003, G006, I001, I002, I005, J001, J007,"
        " J009, J010, S003, S005, S006, X007)\n"
        "urdflint: added 14 suppression comments in 1 file for 15 findings\n"
    )
    assert comments_before(arm) == [
        ("<!-- urdflint: ignore[X007] unknown-element -->", "<colision>"),
        ("<!-- urdflint: ignore[J001] missing-limit -->", "<joint"),
        ("<!-- urdflint: ignore[J007] zero-axis -->", "<axis"),
        ("<!-- urdflint: ignore[I002] non-positive-mass -->", "<mass"),
        ("<!-- urdflint: ignore[I005] triangle-inequality -->", "<inertia"),
        (
            "<!-- urdflint: ignore[J009,J010] inverted-limits, non-positive-effort-or-velocity -->",
            "<limit",
        ),
        ("<!-- urdflint: ignore[I001] missing-inertial -->", "<link"),
        ("<!-- urdflint: ignore[C003] invalid-geometry -->", "<cylinder"),
        ("<!-- urdflint: ignore[S005] kinematic-loop -->", "<joint"),
        ("<!-- urdflint: ignore[S006] invalid-joint-type -->", "<joint"),
        ("<!-- urdflint: ignore[S003] undefined-link -->", "<child"),
        ("<!-- urdflint: ignore[G001] undefined-gazebo-reference -->", "<gazebo"),
        ("<!-- urdflint: ignore[G003] unknown-gazebo-material -->",
         "<material>Gazebo/Organge</material>"),
        ("<!-- urdflint: ignore[G006] unrecognized-gazebo-element -->", "<mu>0.5</mu>"),
    ]  # fmt: skip
    lines = arm.read_text().splitlines()
    for i, line in enumerate(lines):  # on its own line, indented as its element
        if "urdflint: ignore" in line:
            assert re.match(r"\s*", line)[0] == re.match(r"\s*", lines[i + 1])[0]  # type: ignore[index]
    assert added(BROKEN.read_bytes(), arm.read_bytes())
    code, out, _ = run(capsys, "arm.urdf")
    assert code == 0
    assert out.splitlines()[-1] == "urdflint: 2 infos in 1 file"  # no error, no warning left


def test_a_second_run_changes_nothing(capsys, arm: Path) -> None:
    assert run(capsys, "--add-noqa", "arm.urdf")[0] == 0
    before = arm.read_bytes(), os.stat(arm).st_mtime_ns
    assert run(capsys, "--add-noqa", "arm.urdf") == (0, "urdflint: no comment to add\n", "")
    assert (arm.read_bytes(), os.stat(arm).st_mtime_ns) == before


def test_infos_too_when_they_are_listed(capsys, arm: Path) -> None:
    code, out, _ = run(capsys, "--add-noqa", "--show-info", "--select", "C001,J002", "arm.urdf")
    assert code == 0
    assert out.splitlines()[-1] == "urdflint: added 2 suppression comments in 1 file for 2 findings"
    assert [c for c, _ in comments_before(arm)] == [
        "<!-- urdflint: ignore[C001] missing-collision -->",
        "<!-- urdflint: ignore[J002] calibration-ignored -->",
    ]


LEGACY = (
    '<?xml version="1.0" encoding="ISO-8859-1"?>\r\n'
    "<!-- \xc4rm written on Windows -->\r\n"
    '<robot name="r">\r\n'
    '  <link name="a"/>\r\n'
    '  <joint name="j" type="revolute">\r\n'
    '    <origin xyz="0 0 0.1"/>\r\n'
    '    <parent link="a"/>\r\n'
    '    <child link="b"/>\r\n'
    '    <axis xyz="0 0 1"/>\r\n'
    "    <!-- urdflint: ignore[J009] the stops are swapped on purpose -->\r\n"
    '    <limit lower="1" upper="-1" effort="-1" velocity="1"/>\r\n'
    "  </joint>\r\n"
    '  <link name="b"><inertial><mass value="0"/><inertia ixx="0.001" ixy="0" ixz="0"'
    ' iyy="0.001" iyz="0" izz="0.001"/></inertial></link>\r\n'
    "</robot>\r\n"
)


def test_encoding_line_endings_and_existing_comments_are_kept(capsys, tmp_path: Path) -> None:
    path = tmp_path / "legacy.urdf"
    path.write_bytes(LEGACY.encode("latin-1"))
    code, out, _ = run(capsys, "--add-noqa", str(path))
    assert code == 0
    assert out.splitlines()[0] == f"{path}: 2 comments added, 1 comment extended (I002, I013, J010)"
    assert path.read_bytes() == (
        '<?xml version="1.0" encoding="ISO-8859-1"?>\r\n'
        "<!-- \xc4rm written on Windows -->\r\n"
        '<robot name="r">\r\n'
        "  <!-- urdflint: ignore[I013] massless-model -->\r\n"
        '  <link name="a"/>\r\n'
        '  <joint name="j" type="revolute">\r\n'
        '    <origin xyz="0 0 0.1"/>\r\n'
        '    <parent link="a"/>\r\n'
        '    <child link="b"/>\r\n'
        '    <axis xyz="0 0 1"/>\r\n'
        "    <!-- urdflint: ignore[J009,J010] the stops are swapped on purpose -->\r\n"
        '    <limit lower="1" upper="-1" effort="-1" velocity="1"/>\r\n'
        "  </joint>\r\n"
        '  <link name="b"><inertial>\r\n'  # the element did not start its line: now it does
        "    <!-- urdflint: ignore[I002] non-positive-mass -->\r\n"
        '    <mass value="0"/><inertia ixx="0.001" ixy="0" ixz="0"'
        ' iyy="0.001" iyz="0" izz="0.001"/></inertial></link>\r\n'
        "</robot>\r\n"
    ).encode("latin-1")
    assert run(capsys, str(path))[0] == 0


def test_a_syntax_error_takes_no_comment(capsys, tmp_path: Path) -> None:
    path = tmp_path / "bad.urdf"
    shutil.copy(FIXTURES / "rules" / "X001" / "bad.urdf", path)
    before = path.read_bytes()
    code, out, _ = run(capsys, "--add-noqa", "--select", "X001", str(path))
    assert code == 1  # the error is left, at or above --fail-on
    lines = out.splitlines()
    assert lines[0] == "1 finding cannot be suppressed by a comment:"
    assert lines[1].startswith(f"{path}:") and " error X001 invalid-xml: " in lines[1]
    assert lines[2] == (
        "    a file that is not well-formed XML takes no comment: fix the syntax error first"
    )
    assert lines[3] == "urdflint: no comment to add; 1 finding left to fix"
    assert path.read_bytes() == before


def test_a_comment_that_does_not_work_is_not_written(capsys, arm: Path, monkeypatch) -> None:
    from urdflint.engine import suppress

    monkeypatch.setattr(suppress, "parse", lambda root: ([], []))  # every comment ignored
    code, out, _ = run(capsys, "--add-noqa", "--no-cache", "--select", "J007", "arm.urdf")
    assert code == 1
    assert out.splitlines()[1:] == [
        "arm.urdf:37:11: error J007 zero-axis: revolute joint 'shoulder' has the zero axis 0 0 0",
        "    a comment before its element does not suppress it (xacro drops or moves it)",
        "urdflint: no comment to add; 1 finding left to fix",
    ]
    assert arm.read_bytes() == BROKEN.read_bytes()


def test_srdf_findings_go_in_the_urdf_as_a_file_comment(capsys, tmp_path: Path) -> None:
    shutil.copy(FIXTURES / "rules" / "M003" / "bad.urdf", tmp_path / "robot.urdf")
    shutil.copy(FIXTURES / "rules" / "M003" / "bad.srdf", tmp_path / "robot.srdf")
    srdf = (tmp_path / "robot.srdf").read_bytes()
    code, out, _ = run(capsys, "--add-noqa", "--select", "M", str(tmp_path / "robot.urdf"))
    assert code == 0
    assert out.splitlines()[-1] == "urdflint: added 1 suppression comment in 1 file for 3 findings"
    assert (tmp_path / "robot.srdf").read_bytes() == srdf
    lines = (tmp_path / "robot.urdf").read_text().splitlines()
    assert lines[1].startswith("<robot ")
    assert lines[2] == "  <!-- urdflint: ignore-file[M003] group-unknown-member -->"
    assert run(capsys, "--select", "M", str(tmp_path / "robot.urdf"))[0] == 0


@pytest.mark.skipif(not optional.available("pinocchio"), reason="needs Pinocchio")
def test_a_robot_level_finding_gets_the_file_comment(capsys, tmp_path: Path) -> None:
    path = tmp_path / "arm.urdf"
    shutil.copy(FIXTURES / "models" / "example_arm.urdf", path)
    assert run(capsys, "--add-noqa", "--expect-mass", "10", str(path))[0] == 0
    lines = path.read_text().splitlines()
    assert lines[2:4] == [
        '<robot name="example_arm">',
        "  <!-- urdflint: ignore-file[P003] expected-mass -->",
    ]
    assert run(capsys, "--expect-mass", "10", str(path))[0] == 0


# -- xacro: the comment goes where the finding is reported --------------------------------


def edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new, 1))


@pytest.fixture
def rrbot(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """RRBot with a defect in a macro (three links), one in the main file, one in an included
    file, besides its camera's implausible inertia (a warning)."""
    pytest.importorskip("xacro")
    folder = tmp_path / "rrbot_description"
    shutil.copytree(RRBOT, folder)
    edit(folder / "urdf" / "rrbot.xacro", 'ixx="${m*(y*y + z*z)/12}"', 'ixx="-1"')
    edit(folder / "urdf" / "rrbot.xacro", '<axis xyz="0 1 0"/>', '<axis xyz="0 0 0"/>')
    edit(
        folder / "urdf" / "rrbot.gazebo", '<gazebo reference="link3">', '<gazebo reference="link9">'
    )
    monkeypatch.chdir(folder)
    return folder


def test_xacro_findings_are_suppressed_in_the_macro_and_included_files(capsys, rrbot: Path) -> None:
    before = {p: p.read_bytes() for p in (rrbot / "urdf").iterdir()}
    code, out, _ = run(capsys, "--add-noqa", ".")
    assert code == 0
    assert out == (
        "urdf/rrbot.gazebo: 1 comment added (G001)\n"
        "urdf/rrbot.xacro: 4 comments added (G002, I003, I007, J007)\n"
        "urdflint: added 5 suppression comments in 2 files for 5 findings\n"
    )
    main_file, gazebo = rrbot / "urdf" / "rrbot.xacro", rrbot / "urdf" / "rrbot.gazebo"
    assert comments_before(main_file) == [
        ("<!-- urdflint: ignore[I003] non-positive-moment -->", "<inertia"),  # in the macro
        ("<!-- urdflint: ignore[J007] zero-axis -->", "<axis"),
        ("<!-- urdflint: ignore[G002] urdf-color-ignored -->", "<material"),  # link3 lost its
        ("<!-- urdflint: ignore[I007] inertia-geometry-mismatch -->", "<inertia"),  # Gazebo one
    ]
    assert comments_before(gazebo) == [
        ("<!-- urdflint: ignore[G001] undefined-gazebo-reference -->", "<gazebo")
    ]
    assert (rrbot / "urdf" / "materials.xacro").read_bytes() == before[
        rrbot / "urdf" / "materials.xacro"
    ]
    for path in (main_file, gazebo):
        assert added(before[path], path.read_bytes())
        etree.fromstring(path.read_bytes())
    code, out, _ = run(capsys, "--format", "json", ".")
    assert code == 0
    left = json.loads(out)["findings"]
    assert [f for f in left if f["severity"] != "info"] == []
    edited = {p: p.read_bytes() for p in (rrbot / "urdf").iterdir()}
    assert run(capsys, "--add-noqa", ".") == (0, "urdflint: no comment to add\n", "")
    assert {p: p.read_bytes() for p in (rrbot / "urdf").iterdir()} == edited


def test_files_of_other_packages_are_left_alone(capsys, tmp_path: Path, monkeypatch) -> None:
    """A macro of another package (outside the working folder and the paths checked) is not
    edited: its finding is listed instead."""
    pytest.importorskip("xacro")
    macros = tmp_path / "ws" / "their_description"
    macros.mkdir(parents=True)
    (macros / "axis.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:macro name="axis"><axis xyz="0 0 0"/></xacro:macro>\n'
        "</robot>\n"
    )
    mine = tmp_path / "ws" / "my_description"
    mine.mkdir()
    robot = (
        BROKEN.read_text()
        .replace(
            '<axis xyz="0 0 0"/>',
            '<xacro:include filename="$(find their_description)/axis.xacro"/><xacro:axis/>',
        )
        .replace(
            '<robot name="broken_arm">',
            '<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">',
        )
    )
    (mine / "arm.urdf.xacro").write_text(robot)
    monkeypatch.chdir(mine)
    before = (macros / "axis.xacro").read_bytes()
    code, out, _ = run(capsys, "--add-noqa", "--package-path", f"their_description={macros}",
                       "--select", "J007,J009", "arm.urdf.xacro")  # fmt: skip
    assert code == 1
    assert out.splitlines() == [
        "arm.urdf.xacro: 1 comment added (J009)",
        "1 finding cannot be suppressed by a comment:",
        "../their_description/axis.xacro:2:34: error J007 zero-axis: revolute joint 'shoulder'"
        " has the zero axis 0 0 0",
        "    in a file outside the working folder and the paths checked (another package)",
        "urdflint: added 1 suppression comment in 1 file for 1 finding; 1 finding left to fix",
    ]
    assert (macros / "axis.xacro").read_bytes() == before


# -- a real robot ---------------------------------------------------------------------------


@needs_corpus
def test_add_noqa_on_real_robots(capsys, tmp_path: Path, monkeypatch) -> None:
    """PR2 and TIAGo, as published: every error and warning gets its comment, the files keep
    every other byte and still parse, a check is then clean and a second run adds nothing."""
    for name in ("pr2", "tiago"):
        shutil.copytree(CORPUS / name, tmp_path / name)
    monkeypatch.chdir(tmp_path)
    paths = ["--package-path", "pr2_description=pr2/meshes/pr2_description"]
    originals = {p: p.read_bytes() for p in tmp_path.glob("*/model.urdf")}
    code, out, _ = run(capsys, "--add-noqa", *paths, ".")
    assert code == 0, out
    assert re.fullmatch(
        r"urdflint: added \d+ suppression comments in 2 files for \d+ findings",
        out.splitlines()[-1],
    )
    for path, old in originals.items():
        new = path.read_bytes()
        assert new != old and added(old, new)
        etree.fromstring(new)
    code, out, _ = run(capsys, "--format", "json", *paths, ".")
    assert code == 0
    assert [f for f in json.loads(out)["findings"] if f["severity"] != "info"] == []
    edited = {p: p.read_bytes() for p in originals}
    assert run(capsys, "--add-noqa", *paths, ".") == (0, "urdflint: no comment to add\n", "")
    assert {p: p.read_bytes() for p in originals} == edited
