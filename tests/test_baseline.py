"""Baselines: --write-baseline records, --baseline reports only new findings and stale entries."""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path

import pytest

from tests.conftest import CORPUS, needs_corpus
from tests.test_cli import NO_LIMIT
from urdflint.cli import main
from urdflint.engine.baseline import relative

ROBOTS = ("rrbot", "r2d2", "pr2")  # small, medium, large (pr2 has many findings)

TWO_BAD_NUMBERS = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base_link"/>
  <joint name="j" type="fixed">
    <origin xyz="a b c" rpy="x y z"/>
    <parent link="base_link"/>
    <child link="arm"/>
  </joint>
  <link name="arm"/>
</robot>
"""

LIMIT = '<axis xyz="0 0 1"/>\n    <limit lower="-1" upper="1" effort="10" velocity="1"/>'


def check(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, list[dict], str]:
    """Run ``urdflint check --format json``; exit code, findings (minus U004), stderr."""
    code = main(["check", "--format", "json", *args])
    out, err = capsys.readouterr()
    findings = [f for f in json.loads(out)["findings"] if f["code"] != "U004"] if out else []
    return code, findings, err


def keys(baseline: Path) -> list[tuple[str, ...]]:
    entries = json.loads(baseline.read_text())["findings"]
    return [(e["path"], e["code"], e["element"], e["fingerprint"], e["count"]) for e in entries]


@pytest.fixture
def robots(tmp_path: Path) -> Path:
    if not CORPUS.is_dir():
        pytest.skip("../shared/corpus is not present")
    folder = tmp_path / "robots"
    for name in ROBOTS:
        shutil.copytree(CORPUS / name, folder / name)
    return folder


@needs_corpus
def test_corpus_baseline_then_one_planted_defect(capsys, robots: Path, tmp_path: Path) -> None:
    base = tmp_path / "urdflint-baseline.json"
    code, findings, err = check(capsys, "--write-baseline", str(base), str(robots))
    assert code == 0 and findings == []
    assert "recorded" in err
    data = json.loads(base.read_text())
    assert data["version"] == 1 and data["tool"] == "urdflint"
    assert sum(e["count"] for e in data["findings"]) > 50  # pr2 alone has dozens
    assert all(not e["path"].startswith(("/", "..")) for e in data["findings"])

    code, findings, _ = check(capsys, "--baseline", str(base), str(robots))
    assert (code, findings) == (0, [])

    model = robots / "rrbot" / "model.urdf"
    text = model.read_text()
    planted = re.sub(r'<mass value="[^"]*"', '<mass value="-1"', text, count=1)
    assert planted != text
    model.write_text(planted)
    code, findings, _ = check(capsys, "--baseline", str(base), str(robots))
    assert code == 1
    [finding] = findings
    assert finding["code"] == "I002" and finding["path"].endswith("rrbot/model.urdf")
    assert finding["element"].endswith("/inertial/mass")


@needs_corpus
def test_baseline_survives_reformatting(capsys, robots: Path, tmp_path: Path) -> None:
    base = tmp_path / "baseline.json"
    assert check(capsys, "--write-baseline", str(base), str(robots))[0] == 0
    for model in robots.glob("*/model.urdf"):
        lines = model.read_text().splitlines()
        out = []
        for line in lines:
            stripped = line.strip()
            if stripped.startswith(("<link ", "<joint ")):
                out += ["", "<!-- a comment and blank lines above every link and joint -->", ""]
            out.append("    " + line if line[:1].isspace() else line)  # re-indent
        model.write_text("\n".join(out) + "\n")
    code, findings, _ = check(capsys, "--baseline", str(base), str(robots))
    assert (code, findings) == (0, [])


@needs_corpus
def test_baseline_bytes_are_stable_from_any_cwd(
    capsys, robots: Path, tmp_path: Path, monkeypatch
) -> None:
    first, second = tmp_path / "a" / "baseline.json", tmp_path / "b" / "baseline.json"
    first.parent.mkdir()
    second.parent.mkdir()
    check(capsys, "--write-baseline", str(first), str(robots))
    again = first.read_bytes()
    check(capsys, "--write-baseline", str(first), str(robots))
    assert first.read_bytes() == again
    # the same files seen from elsewhere: relative paths from another working directory
    # (the same keys; only informational messages that quote a path may differ)
    monkeypatch.chdir(robots)
    check(capsys, "--write-baseline", "../b/baseline.json", ".")
    assert keys(second) == keys(first)
    monkeypatch.chdir(tmp_path)
    assert check(capsys, "--baseline", "a/baseline.json", "robots")[:2] == (0, [])


@needs_corpus
def test_subset_run_reports_no_stale_entries_for_files_not_checked(
    capsys, robots: Path, tmp_path: Path
) -> None:
    base = tmp_path / "baseline.json"
    check(capsys, "--write-baseline", str(base), str(robots))
    one = robots / "rrbot" / "model.urdf"
    assert check(capsys, "--baseline", str(base), str(one))[:2] == (0, [])
    # nor for rules that did not run
    assert check(capsys, "--baseline", str(base), "--select", "I", str(robots))[:2] == (0, [])


def test_fixed_finding_is_reported_stale(capsys, tmp_path: Path) -> None:
    model = tmp_path / "arm.urdf"
    model.write_text(NO_LIMIT)
    base = tmp_path / "baseline.json"
    check(capsys, "--write-baseline", str(base), str(model))
    [entry] = [e for e in json.loads(base.read_text())["findings"] if e["code"] == "J001"]
    assert entry["path"] == "arm.urdf" and entry["element"] == "/robot/joint[@name='shoulder']"

    model.write_text(NO_LIMIT.replace('<axis xyz="0 0 1"/>', LIMIT))
    code, findings, _ = check(capsys, "--baseline", str(base), str(model))
    assert code == 0  # stale entries are info
    [stale] = [f for f in findings if f["element"] != "/robot"]  # (P001 followed J001)
    assert stale["code"] == "U005" and stale["name"] == "stale-baseline-entry"
    assert stale["severity"] == "info" and stale["path"] == str(model)
    assert stale["element"] == "/robot/joint[@name='shoulder']"
    assert "J001" in stale["message"]
    # a CI job can insist that baselines shrink
    assert check(capsys, "--baseline", str(base), "--fail-on", "info", str(model))[0] == 1
    # ... and U005 can be ignored like any rule
    assert check(capsys, "--baseline", str(base), "--select", "J001", str(model))[0] == 0
    assert check(capsys, "--baseline", str(base), "--ignore", "U005,P", str(model))[:2] == (0, [])


def test_repeated_findings_on_one_element_are_counted(capsys, tmp_path: Path) -> None:
    model = tmp_path / "arm.urdf"
    model.write_text(TWO_BAD_NUMBERS)
    base = tmp_path / "baseline.json"
    check(capsys, "--write-baseline", str(base), "--select", "X004", str(model))
    [entry] = json.loads(base.read_text())["findings"]
    assert entry["code"] == "X004" and entry["count"] == 2

    model.write_text(TWO_BAD_NUMBERS.replace('<link name="arm"/>', _bad_inertial()))
    code, findings, _ = check(capsys, "--baseline", str(base), "--select", "X004", str(model))
    assert code == 1 and [f["element"] for f in findings] == [
        "/robot/link[@name='arm']/inertial/mass"
    ]

    model.write_text(TWO_BAD_NUMBERS.replace('rpy="x y z"', 'rpy="0 0 0"'))
    code, findings, _ = check(capsys, "--baseline", str(base), "--select", "X004,U005", str(model))
    assert code == 0
    [stale] = findings
    assert stale["code"] == "U005" and "(1 of 2)" in stale["message"]


def _bad_inertial() -> str:
    return (
        '<link name="arm"><inertial><mass value="heavy"/>'
        '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>'
    )


@pytest.mark.parametrize(
    ("text", "reason"),
    [
        ("{not json", "not valid JSON"),
        ("[]", "not a urdflint baseline"),
        ('{"version": 2, "tool": "urdflint", "findings": []}', "unsupported version"),
        ('{"version": 1, "tool": "urdflint", "findings": {}}', "must be a list"),
        ('{"version": 1, "tool": "urdflint", "findings": [{"path": "a"}]}', "'code'"),
        (
            '{"version": 1, "tool": "urdflint", "findings": [{"path": "a", "code": "X001",'
            ' "element": "/robot", "fingerprint": "f", "count": 0}]}',
            "'count'",
        ),
    ],
)
def test_malformed_baseline_is_a_usage_error(capsys, tmp_path: Path, text: str, reason: str):
    model = tmp_path / "arm.urdf"
    model.write_text(NO_LIMIT)
    base = tmp_path / "baseline.json"
    base.write_text(text)
    code = main(["check", "--baseline", str(base), str(model)])
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and reason in err and "baseline" in err


def test_missing_baseline_is_a_usage_error(capsys, tmp_path: Path) -> None:
    model = tmp_path / "arm.urdf"
    model.write_text(NO_LIMIT)
    code = main(["check", "--baseline", str(tmp_path / "nope.json"), str(model)])
    assert code == 2 and "cannot read" in capsys.readouterr().err


def test_write_and_read_baseline_are_exclusive(capsys, tmp_path: Path) -> None:
    with pytest.raises(SystemExit) as exc:
        main(["check", "--baseline", "a.json", "--write-baseline", "b.json", str(tmp_path)])
    assert exc.value.code == 2


def test_relative_paths_are_posix_and_relative_to_the_baseline_folder(tmp_path: Path) -> None:
    (tmp_path / "sub").mkdir()
    assert relative(str(tmp_path / "sub" / "m.urdf"), tmp_path) == "sub/m.urdf"
    assert relative(str(tmp_path / "m.urdf"), tmp_path / "sub") == "../m.urdf"


def test_summaries_say_what_the_baseline_recorded_and_hid(capsys, tmp_path: Path) -> None:
    """Never "no problems" for a file with errors: the summary counts what the baseline took
    (issue 25)."""
    from tests.conftest import FIXTURES

    broken = tmp_path / "broken_arm.urdf"
    shutil.copy(FIXTURES / "models" / "broken_arm.urdf", broken)
    baseline = tmp_path / "baseline.json"
    assert main(["check", "--write-baseline", str(baseline), str(broken)]) == 0
    out, err = capsys.readouterr()
    recorded = int(re.search(r"recorded (\d+) finding", err).group(1))  # type: ignore[union-attr]
    assert recorded > 10
    assert out.splitlines()[-1] == (
        f"urdflint: no new problems in 1 file ({recorded} findings in the baseline)"
    )
    assert main(["check", "--baseline", str(baseline), str(broken)]) == 0
    out, _ = capsys.readouterr()
    assert out.splitlines()[-1].endswith(f"({recorded} findings in the baseline)")
