"""JUnit XML: parses back, counts add up, one uniquely named testcase per rule per file."""

from __future__ import annotations

import subprocess
import sys
from xml.etree import ElementTree as ET

from tests.conftest import FIXTURES, ROOT, corpus_models, needs_corpus
from urdflint.engine import registry
from urdflint.model.finding import Finding, Severity
from urdflint.outputs.formatters import NAMES, RunInfo, get, junit

BROKEN = FIXTURES / "models" / "broken_arm.urdf"


def _finding(code: str, severity: Severity, message: str, line: int = 3) -> Finding:
    rule = registry.lookup(code)
    assert rule is not None
    return Finding("a.urdf", line, 1, code, rule.name, severity, message, "/robot")


def _parse(text: str) -> ET.Element:
    assert text.startswith('<?xml version="1.0" encoding="UTF-8"?>\n')
    return ET.fromstring(text.encode("utf-8"))


def _check_counts(root: ET.Element) -> None:
    """Every count attribute equals what the document holds, on suites and on the root."""
    assert root.tag == "testsuites"
    totals = {"tests": 0, "failures": 0, "errors": 0}
    for suite in root.findall("testsuite"):
        cases = suite.findall("testcase")
        counts = {
            "tests": len(cases),
            "failures": sum(c.find("failure") is not None for c in cases),
            "errors": sum(c.find("error") is not None for c in cases),
        }
        assert {k: int(suite.get(k, "-1")) for k in counts} == counts
        names = [c.get("name") for c in cases]
        assert len(names) == len(set(names)), "GitLab keeps only the first of duplicate names"
        assert all(c.get("classname") == suite.get("name") for c in cases)
        for key in totals:
            totals[key] += counts[key]
    assert {k: int(root.get(k, "-1")) for k in totals} == totals


def test_registered_as_a_format() -> None:
    assert "junit" in NAMES and get("junit") is junit.render


def test_one_testcase_per_rule_that_ran_failed_at_the_threshold() -> None:
    findings = [
        _finding("J001", Severity.ERROR, "joint 'j' has no <limit> & more", 3),
        _finding("J001", Severity.INFO, "a note", 9),
        _finding("C001", Severity.WARNING, "link 'l' has no collision", 5),
    ]
    run = RunInfo("0", ("a.urdf", "b.urdf"), rules={"a.urdf": ("C001", "J001", "X001")})
    root = _parse(junit.render(findings, run))
    _check_counts(root)
    a, b = root.findall("testsuite")
    assert a.get("name") == "a.urdf" and b.get("name") == "b.urdf"
    cases = {c.get("name"): c for c in a.findall("testcase")}
    assert set(cases) == {"C001 missing-collision", "J001 missing-limit", "X001 invalid-xml"}
    j001 = cases["J001 missing-limit"]
    failure = j001.find("failure")
    assert failure is not None and failure.get("type") == "J001"
    assert failure.get("message") == "joint 'j' has no <limit> & more"
    assert "a.urdf:3:1: error J001" in (failure.text or "")
    out = j001.find("system-out")
    assert out is not None and "a note" in (out.text or "") and "a note" not in failure.text
    assert cases["C001 missing-collision"].find("failure") is None  # warning < error
    assert "no collision" in (cases["C001 missing-collision"].findtext("system-out") or "")
    assert list(cases["X001 invalid-xml"]) == []  # ran, passed
    assert [c.get("name") for c in b.findall("testcase")] == ["urdflint"]  # never hidden
    assert (root.get("tests"), root.get("failures"), root.get("errors")) == ("4", "1", "0")


def test_fail_on_moves_the_threshold() -> None:
    findings = [_finding("C001", Severity.WARNING, "w"), _finding("J001", Severity.INFO, "i")]
    for fail_on, failures in (("warning", "1"), ("info", "2"), ("never", "0")):
        root = _parse(junit.render(findings, RunInfo("0", ("a.urdf",), fail_on=fail_on)))
        _check_counts(root)
        assert root.get("failures") == failures, fail_on


def test_internal_errors_are_errors_not_failures() -> None:
    findings = [_finding("U001", Severity.ERROR, "rule J001 missing-limit crashed: boom\x00")]
    root = _parse(junit.render(findings, RunInfo("0", ("a.urdf",))))
    _check_counts(root)
    (case,) = root.iter("testcase")
    error = case.find("error")
    assert error is not None and case.find("failure") is None
    assert error.get("message") == "rule J001 missing-limit crashed: boom\ufffd"
    assert (root.get("failures"), root.get("errors")) == ("0", "1")


def test_cli_run_parses_and_matches_the_exit_code() -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--format", "junit", str(BROKEN)],
        capture_output=True,
        text=True,
        cwd=ROOT,
        check=False,
    )
    assert proc.returncode == 1, proc.stderr
    root = _parse(proc.stdout)
    _check_counts(root)
    (suite,) = root.findall("testsuite")
    names = {c.get("name", "").split()[0] for c in suite.findall("testcase")}
    assert {"J001", "I002", "X001", "U002"} <= names, "every rule that ran, not only failing ones"
    assert int(root.get("failures", "0")) > 0


@needs_corpus
def test_corpus_run_parses() -> None:
    models = corpus_models()
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--format", "junit", *map(str, models)],
        capture_output=True,
        text=True,
        cwd=ROOT,
        check=False,
    )
    assert proc.returncode in (0, 1), proc.stderr
    root = _parse(proc.stdout)
    _check_counts(root)
    assert [s.get("name") for s in root.findall("testsuite")] == [str(m) for m in models]
    assert int(root.get("errors", "-1")) == 0


def test_junit_lists_only_the_rules_that_ran(tmp_path) -> None:
    """No passing testcase for a rule nothing asked of (issue 25): E without --confirm, N
    without --profile, P003/P004 without expectations; with them, they are listed."""
    import xml.etree.ElementTree as ET

    from tests.conftest import FIXTURES
    from urdflint.cli import main

    model = str(FIXTURES / "models" / "example_arm.urdf")
    plain, asked = tmp_path / "plain.xml", tmp_path / "asked.xml"
    main(["check", "--report", f"junit:{plain}", model])
    main(["check", "--report", f"junit:{asked}", "--profile", "industrial",
          "--expect-mass", "3±50%", model])  # fmt: skip

    def names(path) -> set[str]:
        return {case.get("name", "")[:4] for case in ET.parse(path).getroot().iter("testcase")}

    assert not {n for n in names(plain) if n[0] in "EN" or n in ("P003", "P004")}
    assert "P003" in names(asked) and any(n.startswith("N") for n in names(asked))
