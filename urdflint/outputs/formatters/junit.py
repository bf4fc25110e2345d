"""JUnit XML for CI test dashboards (``--format junit``, ``--report junit:urdflint.xml``).

The Ant/Jenkins dialect that Jenkins, GitLab, Azure DevOps and the GitHub test-report
actions read: one ``<testsuite>`` per checked file and one ``<testcase>`` per rule that
ran on it, named ``CODE rule-name`` (unique within the file, so GitLab, which keeps only
the first of duplicate names, shows them all) with ``classname`` = the file. A testcase
fails (``<failure>``) when the rule has findings at or above the run's ``--fail-on``; its
findings below the threshold are listed in ``<system-out>``. A rule that crashed is an
``<error>`` on the ``U001 internal-error`` testcase. A file without any testcase gets one
passing ``urdflint`` case, so ``tests`` never hides a checked file.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from xml.etree import ElementTree as ET

from urdflint.engine import registry
from urdflint.model.finding import Finding, Severity
from urdflint.outputs.formatters.run import RunInfo

INTERNAL_ERROR = "U001"
NOT_XML = re.compile("[^\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")


def _clean(text: str) -> str:
    """Text XML 1.0 can carry: characters it forbids become U+FFFD."""
    return NOT_XML.sub("\ufffd", text)


def _line(f: Finding) -> str:
    return _clean(f"{f.path}:{f.line}:{f.column}: {f.severity} {f.code} {f.name}: {f.message}")


def _name(code: str, sample: Finding | None) -> str:
    if sample is not None:
        return f"{code} {sample.name}"
    rule = registry.load_rules().get(code)
    return f"{code} {rule.name}" if rule is not None else code


def _threshold(fail_on: str) -> Severity | None:
    try:
        return Severity.parse(fail_on)
    except ValueError:
        return None  # "never": nothing fails


def _testcase(
    suite: ET.Element, path: str, code: str, found: list[Finding], threshold: Severity | None
) -> tuple[int, int]:
    """Append one testcase; returns (failures, errors) it adds."""
    case = ET.SubElement(
        suite,
        "testcase",
        name=_clean(_name(code, found[0] if found else None)),
        classname=_clean(path),
    )
    case.set("time", "0")
    if found:
        case.set("file", _clean(path))
        case.set("line", str(found[0].line))
    if code == INTERNAL_ERROR and found:
        error = ET.SubElement(case, "error", type=code, message=_clean(found[0].message))
        error.text = "\n".join(_line(f) for f in found)
        return 0, 1
    failing = [f for f in found if threshold is not None and f.severity >= threshold]
    passing = [f for f in found if threshold is None or f.severity < threshold]
    if failing:
        failure = ET.SubElement(case, "failure", type=code, message=_clean(failing[0].message))
        failure.text = "\n".join(_line(f) for f in failing)
    if passing:
        out = ET.SubElement(case, "system-out")
        out.text = "\n".join(_line(f) for f in passing)
    return (1 if failing else 0), 0


def document(findings: Sequence[Finding], run: RunInfo) -> ET.Element:
    """The ``<testsuites>`` element (``render`` serialises it)."""
    threshold = _threshold(run.fail_on)
    by_file: dict[str, dict[str, list[Finding]]] = {path: {} for path in run.files}
    for finding in findings:
        by_file.setdefault(finding.path, {}).setdefault(finding.code, []).append(finding)
    root = ET.Element("testsuites", name="urdflint")
    totals = [0, 0, 0]  # tests, failures, errors
    for path, by_code in by_file.items():
        suite = ET.SubElement(root, "testsuite", name=_clean(path))
        codes = sorted(set(run.rules.get(path, ())) | set(by_code))
        tests = failures = errors = 0
        for code in codes:
            failed, erred = _testcase(suite, path, code, by_code.get(code, []), threshold)
            tests, failures, errors = tests + 1, failures + failed, errors + erred
        if not codes:
            ET.SubElement(suite, "testcase", name="urdflint", classname=_clean(path), time="0")
            tests = 1
        for key, value in (
            ("tests", tests),
            ("failures", failures),
            ("errors", errors),
            ("skipped", 0),
            ("time", 0),
        ):
            suite.set(key, str(value))
        totals = [totals[0] + tests, totals[1] + failures, totals[2] + errors]
    for key, value in zip(("tests", "failures", "errors"), totals, strict=True):
        root.set(key, str(value))
    return root


def render(findings: Sequence[Finding], run: RunInfo) -> str:
    root = document(findings, run)
    ET.indent(root)
    body = ET.tostring(root, encoding="unicode")
    return f'<?xml version="1.0" encoding="UTF-8"?>\n{body}\n'
