"""The display options of ``check``: ``--output-format concise|full``, ``--statistics`` and
``--quiet``. They change how the findings are shown, never the findings or the exit code."""

from __future__ import annotations

import io
import json
from pathlib import Path

import pytest

from tests.conftest import FIXTURES
from urdflint.cli import main
from urdflint.model.edits import Autofix, Edit
from urdflint.model.finding import Call, Finding, Severity
from urdflint.outputs.formatters import RunInfo, github, text
from urdflint.outputs.formatters.excerpt import Sources

BROKEN = FIXTURES / "models" / "broken_arm.urdf"
GOOD = FIXTURES / "models" / "template_good.urdf"
# one macro called seven times: six calls invert the limits, each with its own values, so
# the six J009 findings at the macro's <limit> line are not merged into one by the engine
SEGMENTS = """\
<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="segment" params="name parent lower upper">
    <link name="${name}_link">
      <inertial>
        <mass value="1"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
      </inertial>
    </link>
    <joint name="${name}_joint" type="revolute">
      <parent link="${parent}"/>
      <child link="${name}_link"/>
      <axis xyz="0 0 1"/>
      <limit lower="${lower}" upper="${upper}" effort="10" velocity="1"/>
    </joint>
  </xacro:macro>
  <link name="base_link"/>
  <xacro:segment name="a" parent="base_link" lower="1" upper="-1"/>
  <xacro:segment name="b" parent="a_link" lower="2" upper="-2"/>
  <xacro:segment name="c" parent="b_link" lower="0.5" upper="-0.5"/>
  <xacro:segment name="d" parent="c_link" lower="1.5" upper="-1.5"/>
  <xacro:segment name="e" parent="d_link" lower="0.3" upper="-0.3"/>
  <xacro:segment name="f" parent="e_link" lower="0.7" upper="-0.7"/>
  <xacro:segment name="g" parent="f_link" lower="-1" upper="1"/>
</robot>
"""
DISPLAY = [
    [],
    ["--output-format", "concise"],
    ["--output-format", "full"],
    ["--statistics"],
    ["--quiet"],
    ["-q", "--output-format", "full"],
    ["-q", "--statistics"],
    ["--show-info", "--output-format", "full", "--statistics", "-q"],
]


@pytest.fixture
def segments(tmp_path: Path) -> Path:
    pytest.importorskip("xacro")
    path = tmp_path / "arm.urdf.xacro"
    path.write_text(SEGMENTS, encoding="utf-8")
    return path


def check(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str]:
    code = main(["check", "--isolated", "--no-cache", *args])
    return code, capsys.readouterr().out


def findings_of(report: Path) -> list[dict[str, object]]:
    return json.loads(report.read_text(encoding="utf-8"))["findings"]


@pytest.mark.parametrize("model", ["broken_arm", "xacro macro"])
def test_display_options_never_change_findings_or_exit_codes(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, model: str
) -> None:
    if model == "xacro macro":
        pytest.importorskip("xacro")
        path = tmp_path / "arm.urdf.xacro"
        path.write_text(SEGMENTS, encoding="utf-8")
    else:
        path = BROKEN
    code, out = check(capsys, "--format", "json", str(path))
    expected = (code, json.loads(out)["findings"])
    assert code == 1 and expected[1]
    report = tmp_path / "report.json"
    for options in DISPLAY:
        for fmt in ("text", "json", "github"):
            done, out = check(capsys, "--format", fmt, "--report", f"json:{report}", *options,
                              str(path))  # fmt: skip
            assert (done, findings_of(report)) == expected, (fmt, options)
            if fmt == "json" and "--statistics" not in options:
                assert json.loads(out)["findings"] == expected[1], options
            if fmt == "json" and "--statistics" in options:
                assert sum(row["count"] for row in json.loads(out)) == len(expected[1])


def test_concise_groups_one_rule_at_one_source_location(
    capsys: pytest.CaptureFixture[str], segments: Path
) -> None:
    code, out = check(capsys, "--format", "text", str(segments))
    lines = out.splitlines()
    assert code == 1
    assert lines[:3] == [
        f"{segments}:14:14: error J009 inverted-limits: revolute joint 'a_joint' has lower 1 rad "
        "above upper -1 rad ×6 (joints a_joint, b_joint, c_joint, d_joint, e_joint, …)",
        f"    in macro `segment`, called from {segments}:18:3",
        "    6 call sites in all (--output-format full lists each)",
    ]
    assert sum(" J009 " in line for line in lines) == 1
    assert lines[-1] == "urdflint: 6 errors, 1 warning, 1 info in 1 file"  # every finding


def test_full_lists_each_finding_with_its_calls_and_source_line(
    capsys: pytest.CaptureFixture[str], segments: Path
) -> None:
    code, out = check(capsys, "--format", "text", "--output-format", "full", str(segments))
    lines = out.splitlines()
    assert code == 1
    heads = [i for i, line in enumerate(lines) if " J009 " in line]
    assert len(heads) == 6 and "×6" not in out
    first = heads[0]
    assert lines[first + 1 : first + 6] == [
        f"    in macro `segment`, called from {segments}:18:3",
        "    limits changed: Gazebo Sim · as written: ROS (KDL, MoveIt)",
        "   |",
        '14 |       <limit lower="${lower}" upper="${upper}" effort="10" velocity="1"/>',
        "   |              ^",
    ]
    calls = [lines[i + 1] for i in heads]
    assert calls == [f"    in macro `segment`, called from {segments}:{n}:3" for n in range(18, 24)]
    assert lines[-1] == "urdflint: 6 errors, 1 warning, 1 info in 1 file"


def test_full_puts_the_caret_under_the_column(capsys: pytest.CaptureFixture[str]) -> None:
    _, out = check(capsys, "--format", "text", "--output-format", "full", str(BROKEN))
    lines = out.splitlines()
    head = next(i for i, line in enumerate(lines) if ":61:12: error J009 " in line)
    assert lines[head + 1 : head + 5] == [
        "    limits changed: Gazebo Sim · as written: ROS (KDL, MoveIt)",  # full: every effect
        "   |",
        '61 |     <limit lower="1.2" upper="-1.2" effort="-20" velocity="2.5"/>',
        "   |            ^",
    ]
    assert lines[head + 3][len("61 | ") + 11 :].startswith("lower=")  # column 12
    assert lines[-1] == "urdflint: 12 errors, 3 warnings, 2 infos in 1 file"


def test_full_omits_the_excerpt_of_standard_input(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    for name in ("<stdin>", str(BROKEN)):  # a name on disk is not what was checked
        monkeypatch.setattr("sys.stdin", io.TextIOWrapper(io.BytesIO(BROKEN.read_bytes())))
        _, out = check(capsys, "--output-format", "full", "--format", "text",
                       "--stdin-filename", name, "-")  # fmt: skip
        assert f"{name}:61:12: error J009 " in out
        assert " |" not in out


def test_excerpt_keeps_tabs_under_the_caret_and_cuts_long_lines(tmp_path: Path) -> None:
    path = tmp_path / "r.urdf"
    path.write_text("<robot>\r\n\t<link  name='x'/>\n" + "a" * 150 + "<b/>" + "c" * 150 + "\n")
    sources = Sources()
    assert sources.excerpt(str(path), 2, 9) == ["  |", "2 | \t<link  name='x'/>", "  | \t       ^"]
    _, line, caret = sources.excerpt(str(path), 3, 151)
    assert line == "3 | …" + "a" * 40 + "<b/>" + "c" * 56 + "…"
    assert caret.index("^") == line.index("<b/>")
    assert sources.excerpt(str(path), 9, 1) == [] and sources.excerpt("<stdin>", 1, 1) == []
    assert Sources([str(path)]).excerpt(str(path), 2, 1) == []


def finding(element: str, message: str = "message", **more: object) -> Finding:
    return Finding("r.xacro", 4, 5, "J009", "inverted-limits", Severity.ERROR, message,
                   element, **more)  # type: ignore[arg-type]  # fmt: skip


def test_group_note_names_the_kind_and_at_most_five_names() -> None:
    links = [finding(f"/robot/link[@name='l{i}']/inertial") for i in range(3)]
    assert text.group_note(links[:1]) == ""
    assert text.group_note(links) == " ×3 (links l0, l1, l2)"
    mixed = [*links, finding("/robot/joint[@name='j']"), finding("/robot")]
    assert text.group_note(mixed) == " ×5 (elements l0, l1, l2, j)"
    many = [finding(f"/robot/gazebo[@reference='g{i}']") for i in range(7)]
    assert text.group_note(many) == " ×7 (gazebos g0, g1, g2, g3, g4, …)"
    assert text.group_note([finding("/robot")] * 2) == " ×2"
    named = [finding("/robot/link[@name='a']", "'a' (for links a, b)"),
             finding("/robot/link[@name='b']", "'b'")]  # fmt: skip
    assert text.group_note(named) == " ×2"  # the first message already names them


def test_a_group_keeps_the_fix_mark_and_the_first_call_chain() -> None:
    fix = Autofix("safe", "swap", (Edit("r.xacro", 0, 1, "x"),))
    calls = [(Call("m", "r.xacro", n, 3),) for n in (10, 11)]
    group = [finding("/robot/joint[@name='a']", trace=calls[0]),
             finding("/robot/joint[@name='b']", trace=calls[1], autofix=fix)]  # fmt: skip
    out = text.render(group, RunInfo("0", ("r.xacro",))).splitlines()
    assert out[:3] == [
        "r.xacro:4:5: error J009 inverted-limits: message ×2 (joints a, b) [fix]",
        "    in macro `m`, called from r.xacro:10:3",
        "    2 call sites in all (--output-format full lists each)",
    ]


def test_statistics_is_one_row_per_rule_most_frequent_first(
    capsys: pytest.CaptureFixture[str], segments: Path
) -> None:
    code, out = check(capsys, "--format", "text", "--statistics", str(segments))
    assert code == 1
    assert out.splitlines() == [
        "count  code  name                  severity  fixable",
        "    6  J009  inverted-limits       error",
        "    1  I013  massless-model        warning",
        "    1  J011  missing-joint-origin  info",
        "urdflint: 6 errors, 1 warning, 1 info in 1 file",
    ]
    code, out = check(capsys, "--format", "json", "--statistics", str(segments))
    assert code == 1
    assert json.loads(out) == [
        {"code": "J009", "name": "inverted-limits", "severity": "error", "count": 6,
         "fixable": 0},
        {"code": "I013", "name": "massless-model", "severity": "warning", "count": 1,
         "fixable": 0},
        {"code": "J011", "name": "missing-joint-origin", "severity": "info", "count": 1,
         "fixable": 0},
    ]  # fmt: skip


def test_statistics_counts_the_fixable_findings(capsys: pytest.CaptureFixture[str]) -> None:
    _, listed = check(capsys, "--format", "json", str(BROKEN))
    found = json.loads(listed)["findings"]
    _, out = check(capsys, "--format", "json", "--statistics", str(BROKEN))
    rows = json.loads(out)
    assert [r["count"] for r in rows] == sorted((r["count"] for r in rows), reverse=True)
    ready = [f for f in found if f["autofix"] and not f["autofix"].get("unavailable")]
    assert sum(r["fixable"] for r in rows) == len(ready) > 0
    _, table = check(capsys, "--format", "text", "--statistics", str(BROKEN))
    unsafe = next(line for line in table.splitlines() if " I005 " in line)
    assert unsafe.split()[-3:] == ["1", "(1", "unsafe)"]


def test_quiet_writes_only_the_findings(capsys: pytest.CaptureFixture[str]) -> None:
    code, full = check(capsys, "--format", "text", str(BROKEN))
    quiet_code, quiet = check(capsys, "--format", "text", "-q", str(BROKEN))
    assert quiet_code == code == 1
    kept = [line for line in full.splitlines() if line.startswith(str(BROKEN))]
    assert quiet.splitlines() == kept and len(kept) == 15
    assert check(capsys, "--format", "text", "--quiet", str(GOOD)) == (0, "")
    _, actions = check(capsys, "--format", "github", "-q", str(BROKEN))
    assert "urdflint:" not in actions and actions.startswith("::group::")


def test_quiet_is_not_the_joint_position_option(capsys: pytest.CaptureFixture[str]) -> None:
    code, out = check(capsys, "--format", "text", "-q", "--q", "elbow=0.1", str(BROKEN))
    assert code == 1 and "urdflint:" not in out


def test_github_quiet_has_no_summary_line() -> None:
    one = [finding("/robot")]
    assert github.render(one, RunInfo("0", ("r.xacro",), quiet=True)).splitlines()[-1] == (
        "::endgroup::"
    )
    assert github.render([], RunInfo("0", (), quiet=True)) == ""
