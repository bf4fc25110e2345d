"""``--output FILE`` and repeatable ``--report FORMAT:PATH``: several formats from one run."""

from __future__ import annotations

import json
import os
from pathlib import Path
from xml.etree import ElementTree as ET

import pytest

from tests.conftest import FIXTURES
from urdflint.cli import main

BROKEN = FIXTURES / "models" / "broken_arm.urdf"
GOOD = FIXTURES / "models" / "template_good.urdf"


def run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


def test_one_run_prints_annotations_and_writes_sarif_and_junit(capsys, tmp_path: Path) -> None:
    sarif, xml = tmp_path / "urdflint.sarif", tmp_path / "urdflint.xml"
    code, out, err = run(
        capsys,
        "check",
        "--format",
        "github",
        "--report",
        f"sarif:{sarif}",
        "--report",
        f"junit:{xml}",
        str(BROKEN),
    )
    assert code == 1 and not err
    assert out.startswith("::group::") and "::error file=" in out
    log = json.loads(sarif.read_text(encoding="utf-8"))
    results = log["runs"][0]["results"]
    root = ET.parse(xml).getroot()
    failing = [c for c in root.iter("testcase") if c.find("failure") is not None]
    errors = {r["ruleId"] for r in results if r["level"] == "error"}
    assert {c.get("name", "").split()[0] for c in failing} == errors
    assert out.count("::error ") + out.count("::warning ") + out.count("::notice ") == len(results)


def test_output_replaces_stdout(capsys, tmp_path: Path) -> None:
    target = tmp_path / "out.json"
    code, out, _ = run(capsys, "check", "--format", "json", "--output", str(target), str(BROKEN))
    assert code == 1 and out == ""
    data = json.loads(target.read_text(encoding="utf-8"))
    assert data["findings"] and str(BROKEN) in data.get("models", {})


def test_json_report_keeps_models_and_fail_on_reaches_junit(capsys, tmp_path: Path) -> None:
    xml = tmp_path / "r.xml"
    code, out, _ = run(
        capsys,
        "check",
        "--format",
        "text",
        "--fail-on",
        "never",
        "--report",
        f"json:{tmp_path / 'r.json'}",
        "--report",
        f"junit:{xml}",
        str(GOOD),
    )
    assert code == 0 and out.splitlines()[-1].startswith("urdflint: ")
    assert "models" in json.loads((tmp_path / "r.json").read_text(encoding="utf-8"))
    assert ET.parse(xml).getroot().get("failures") == "0"


@pytest.mark.parametrize(
    ("report", "message"),
    [
        ("bogus:x.txt", "unknown format 'bogus'"),
        ("sarif", "expected FORMAT:PATH"),
        ("sarif:", "expected FORMAT:PATH"),
        (":x.sarif", "expected FORMAT:PATH"),
        ("sarif:{tmp}/missing/x.sarif", "no such directory"),
        ("sarif:{tmp}", "is a directory"),
    ],
)
def test_bad_reports_are_usage_errors(capsys, tmp_path: Path, report: str, message: str) -> None:
    code, out, err = run(
        capsys, "check", "--report", report.format(tmp=tmp_path), "--format", "text", str(GOOD)
    )
    assert code == 2 and out == ""  # checked before linting: nothing printed
    assert err.count("\n") == 1 and err.startswith("urdflint: error: --report ")
    assert message in err


def test_same_file_twice_is_a_usage_error(capsys, tmp_path: Path) -> None:
    target = tmp_path / "a.txt"
    code, _, err = run(
        capsys, "check", "--output", str(target), "--report", f"json:{target}", str(GOOD)
    )
    assert code == 2 and "written twice" in err and err.count("\n") == 1


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0, reason="needs a non-root POSIX user")
def test_unwritable_output_is_a_usage_error(capsys, tmp_path: Path) -> None:
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    try:
        code, out, err = run(capsys, "check", "--output", str(locked / "o.txt"), str(GOOD))
    finally:
        locked.chmod(0o700)
    assert code == 2 and out == "" and "not writable" in err and err.count("\n") == 1


def test_a_crashed_rule_is_a_junit_error(capsys, tmp_path: Path, monkeypatch) -> None:
    from urdflint.engine import registry
    from urdflint.model.finding import Severity

    def boom(doc):
        raise RuntimeError("kaboom")
        yield  # pragma: no cover

    monkeypatch.setitem(
        registry.RULES, "Z900", registry.Rule("Z900", "test-crash", Severity.ERROR, boom, "x")
    )
    monkeypatch.setitem(registry.FAMILIES, "Z", "test")
    xml = tmp_path / "r.xml"
    code, _, _ = run(
        capsys, "check", "--select", "Z900,J001", "--report", f"junit:{xml}", str(GOOD)
    )
    assert code == 2
    root = ET.parse(xml).getroot()
    cases = {c.get("name"): c for c in root.iter("testcase")}
    assert set(cases) == {"J001 missing-limit", "U001 internal-error"}  # Z900 did not run
    error = cases["U001 internal-error"].find("error")
    assert error is not None and "kaboom" in (error.get("message") or "")
    assert (root.get("tests"), root.get("failures"), root.get("errors")) == ("2", "0", "1")
