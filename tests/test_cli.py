"""The command line: formats, exit codes, path handling, selection, stdin."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import FIXTURES
from urdflint.cli import main
from urdflint.model import optional

GOOD = FIXTURES / "models" / "template_good.urdf"
BROKEN_XML = FIXTURES / "rules" / "X001" / "bad.urdf"
NO_LIMIT = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base_link"/>
  <joint name="shoulder" type="revolute">
    <origin xyz="0 0 0.1"/>
    <parent link="base_link"/>
    <child link="upper_arm"/>
    <axis xyz="0 0 1"/>
  </joint>
  <link name="upper_arm">
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0.00833" ixy="0" ixz="0" iyy="0.00833" iyz="0" izz="0.00167"/>
    </inertial>
  </link>
</robot>
"""


def run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture
def no_limit(tmp_path: Path) -> Path:
    path = tmp_path / "arm.urdf"
    path.write_text(NO_LIMIT)
    return path


def test_clean_file_exits_0(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "check", "--format", "text", str(GOOD))
    assert code == 0
    assert out.strip().endswith("no problems in 1 file")


def test_text_format_is_path_line_col_severity_code_name_message(capsys, no_limit: Path) -> None:
    code, out, _ = run(capsys, "check", "--format", "text", "--select", "J001", str(no_limit))
    assert code == 1
    first = out.splitlines()[0]
    assert first.startswith(f"{no_limit}:4:3: error J001 ")
    assert "'shoulder'" in first


def test_json_envelope(capsys, no_limit: Path) -> None:
    code, out, _ = run(
        capsys, "check", "--format", "json", "--select", "J001", str(no_limit), str(GOOD)
    )
    assert code == 1
    data = json.loads(out)
    assert data["version"] == 1
    assert data["tool"]["name"] == "urdflint" and data["tool"]["version"]
    assert data["summary"] == {"files": 2, "error": 1, "warning": 0, "info": 0}
    (finding,) = data["findings"]
    assert set(finding) == {
        "path",
        "line",
        "column",
        "code",
        "name",
        "severity",
        "message",
        "element",
        "fix",
        "trace",
        "effects",
        "engine",
        "autofix",
    }
    assert finding["element"] == "/robot/joint[@name='shoulder']"
    assert finding["severity"] == "error" and finding["line"] == 4
    assert finding["fix"]


def test_github_format_and_auto_detection(capsys, no_limit: Path, monkeypatch) -> None:
    monkeypatch.setenv("GITHUB_ACTIONS", "true")
    code, out, _ = run(capsys, "check", "--select", "J001", str(no_limit))
    assert code == 1
    lines = out.splitlines()
    assert lines[0] == f"::group::{no_limit}"
    assert lines[1].startswith(
        f"::error file={no_limit},line=4,endLine=4,col=3,title=urdflint (J001)::J001 "
    )
    assert lines[2] == "::endgroup::"


def test_github_escapes_property_and_message_data() -> None:
    from urdflint.model.finding import Finding, Severity
    from urdflint.outputs.formatters import RunInfo, github

    finding = Finding(
        "a,b:c.urdf", 2, 1, "X001", "invalid-xml", Severity.ERROR, "50% bad\nline", "/robot"
    )
    out = github.render([finding], RunInfo("0", ("a,b:c.urdf",)))
    assert "file=a%2Cb%3Ac.urdf," in out
    assert "::X001 invalid-xml: 50%25 bad%0Aline" in out


def test_syntax_error_is_a_finding_exit_1(capsys) -> None:
    code, out, _ = run(capsys, "check", "--format", "text", str(BROKEN_XML))
    assert code == 1
    assert ":7:10: error X001 invalid-xml: " in out


def test_missing_path_exits_2_but_lints_the_rest(capsys, no_limit: Path) -> None:
    code, out, err = run(capsys, "check", "--format", "text", str(no_limit), "does/not/exist.urdf")
    assert code == 2
    assert "does/not/exist.urdf: no such file or directory" in err
    assert "J001" in out


def test_unknown_selector_is_a_usage_error(capsys, no_limit: Path) -> None:
    code, _, err = run(capsys, "check", "--select", "Q123", str(no_limit))
    assert code == 2
    assert "Q123" in err


def test_select_and_ignore_take_codes_names_and_families(capsys, no_limit: Path) -> None:
    assert run(capsys, "check", "--select", "missing-limit", str(no_limit))[0] == 1
    assert run(capsys, "check", "--select", "J", "--ignore", "J001", str(no_limit))[0] == 0
    # P001: Pinocchio is never handed a model urdfdom refuses, and says so
    assert run(capsys, "check", "--ignore", "J,P", str(no_limit))[0] == 0


def test_fail_on_threshold(capsys, tmp_path: Path) -> None:
    path = tmp_path / "calib.urdf"
    path.write_text(
        GOOD.read_text().replace(
            '<axis xyz="0 0 1"/>', '<axis xyz="0 0 1"/><calibration rising="0.1"/>'
        )
    )
    assert run(capsys, "check", "--select", "J002", str(path))[0] == 0
    assert run(capsys, "check", "--select", "J002", "--fail-on", "info", str(path))[0] == 1
    assert (
        run(capsys, "check", "--select", "J002", "--fail-on", "info", "--exit-zero", str(path))[0]
        == 0
    )


def test_directory_is_searched_recursively_for_urdf(capsys, tmp_path: Path) -> None:
    (tmp_path / "a" / "b").mkdir(parents=True)
    (tmp_path / "a" / "b" / "deep.urdf").write_text(NO_LIMIT)
    (tmp_path / "a" / "notes.txt").write_text("not a robot")
    (tmp_path / ".hidden").mkdir()
    (tmp_path / ".hidden" / "skip.urdf").write_text("<robot")
    code, out, _ = run(capsys, "check", "--format", "json", "--select", "J001,X001", str(tmp_path))
    data = json.loads(out)
    assert code == 1
    assert data["summary"]["files"] == 1
    assert data["findings"][0]["path"].endswith("deep.urdf")


def test_empty_directory_exits_2(capsys, tmp_path: Path) -> None:
    code, _, err = run(capsys, "check", str(tmp_path))
    assert code == 2 and "no *.urdf or *.xacro files" in err


def test_stdin(no_limit: Path) -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--format", "text", "--select", "J001", "-"],
        input=NO_LIMIT,
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode == 1
    assert proc.stdout.startswith("<stdin>:4:3: error J001")


def test_rules_and_explain(capsys) -> None:
    code, out, _ = run(capsys, "rules")
    assert code == 0 and "I005" in out and "X001" in out
    code, out, _ = run(capsys, "rules", "--format", "json")
    assert code == 0 and any(r["code"] == "J001" for r in json.loads(out)["rules"])
    code, out, _ = run(capsys, "explain", "I005")
    assert code == 0
    for part in (
        "I005 ",
        "## What it does",
        "## Why is this bad?",
        "## How to fix",
        "## Bad example",
        "## Good example",
    ):
        assert part in out
    assert run(capsys, "explain", "triangle-inequality")[0] == 0
    code, _, err = run(capsys, "explain", "Z999")
    assert code == 2 and "Z999" in err


def test_internal_error_becomes_u001_and_exit_2(capsys, no_limit: Path, monkeypatch) -> None:
    from urdflint.engine import registry
    from urdflint.model.finding import Severity

    def boom(doc):
        raise RuntimeError("kaboom")
        yield  # pragma: no cover

    monkeypatch.setitem(
        registry.RULES, "Z900", registry.Rule("Z900", "test-crash", Severity.ERROR, boom, "x")
    )
    monkeypatch.setitem(registry.FAMILIES, "Z", "test")
    code, out, _ = run(capsys, "check", "--format", "json", "--select", "Z900,J001", str(no_limit))
    data = json.loads(out)
    assert code == 2
    codes = [f["code"] for f in data["findings"]]
    assert "U001" in codes and "J001" in codes  # the run went on
    crash = next(f for f in data["findings"] if f["code"] == "U001")
    assert "Z900" in crash["message"] and "kaboom" in crash["message"]


def test_missing_extra_is_skipped_with_one_note(
    capsys, no_limit: Path, tmp_path: Path, monkeypatch
) -> None:
    from urdflint.engine import registry
    from urdflint.model.finding import Severity

    def needs_pin(doc):
        yield from ()

    monkeypatch.setitem(
        registry.RULES,
        "Z901",
        registry.Rule(
            "Z901", "test-needs", Severity.ERROR, needs_pin, "x", needs=("urdflint_no_such_module",)
        ),
    )
    other = tmp_path / "second.urdf"
    other.write_text(NO_LIMIT)
    _, out, _ = run(capsys, "check", "--format", "json", str(no_limit), str(other))
    notes = [f for f in json.loads(out)["findings"] if f["code"] == "U004"]
    assert len(notes) == 1
    assert "Z901" in notes[0]["message"] and "urdflint_no_such_module" in notes[0]["message"]


def test_python_dash_m_works() -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "--version"], capture_output=True, text=True
    )
    assert proc.returncode == 0 and proc.stdout.startswith("urdflint ")


def test_expectations_without_pinocchio_fail_the_run(capsys, no_limit: Path, monkeypatch) -> None:
    monkeypatch.setattr(optional, "available", lambda module: module != "pinocchio")
    code, out, _ = run(
        capsys, "check", "--format", "json", "--select", "X,P", "--expect-mass", "1", str(GOOD)
    )
    [note] = [f for f in json.loads(out)["findings"] if f["code"] == "U004"]
    assert code == 1 and note["severity"] == "error" and "NOT checked" in note["message"]
    code, out, _ = run(capsys, "check", "--format", "json", "--select", "X,P,U", str(GOOD))
    [note] = [f for f in json.loads(out)["findings"] if f["code"] == "U004"]
    assert code == 0 and note["severity"] == "info"


@pytest.mark.parametrize("target", ["nonexist.urdf", "emptydir"])
def test_no_file_checked_is_never_no_problems(tmp_path, capsys, target: str) -> None:
    """A path that does not exist, or a folder without robots: exit 2, an error on stderr,
    and a summary that does not read as a clean result (issue 25)."""
    (tmp_path / "emptydir").mkdir()
    code = main(["check", str(tmp_path / target)])
    out, err = capsys.readouterr()
    assert code == 2
    assert out.strip() == "urdflint: no files checked"
    assert "no problems" not in out and err.startswith("urdflint: error: ")
