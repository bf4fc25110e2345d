"""The text format: errors and warnings listed, infos summarised unless asked for."""

from __future__ import annotations

import subprocess
import sys

from tests.conftest import FIXTURES, ROOT
from urdflint.model.finding import Finding, Severity
from urdflint.outputs.formatters import RunInfo, text


def finding(code: str, severity: Severity, line: int = 1) -> Finding:
    return Finding("r.urdf", line, 1, code, "name", severity, "message", "/robot")


FINDINGS = [
    finding("J001", Severity.ERROR, 3),
    finding("J011", Severity.INFO, 4),
    finding("C001", Severity.INFO, 5),
    finding("J011", Severity.INFO, 6),
    finding("X007", Severity.WARNING, 7),
]


def test_infos_are_one_summary_line_by_default() -> None:
    out = text.render(FINDINGS, RunInfo("0", ("r.urdf",), show_info=False)).splitlines()
    assert [line.split(": ")[1].split()[1] for line in out[:2]] == ["J001", "X007"]
    assert out[2] == "3 infos not shown: J011 ×2, C001 ×1 (--show-info lists them)"
    assert out[3] == "urdflint: 1 error, 1 warning, 3 infos in 1 file"


def test_show_info_lists_every_finding() -> None:
    out = text.render(FINDINGS, RunInfo("0", ("r.urdf",), show_info=True)).splitlines()
    assert len(out) == 6 and "not shown" not in "\n".join(out)


def run(*args: str) -> str:
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--isolated", *args],
        capture_output=True, text=True, cwd=ROOT, check=False,
    )  # fmt: skip
    return proc.stdout


def test_the_cli_hides_infos_unless_asked() -> None:
    broken = str(FIXTURES / "models" / "broken_arm.urdf")
    quiet, shown = run(broken), run("--show-info", broken)
    assert " info C001 " not in quiet and "infos not shown: C001 ×1, J002 ×1" in quiet
    assert " info C001 " in shown and "not shown" not in shown
    assert " info C001 " in run("--fail-on", "info", broken)
