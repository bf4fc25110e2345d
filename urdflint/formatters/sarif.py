"""SARIF 2.1.0 for GitHub code scanning (``--format sarif``, ``?format=sarif``).

One run, one tool (urdflint). ``rules`` lists the rules that produced results,
sorted by code, and each result points at its rule by ``ruleId`` and
``ruleIndex``. Locations are the file as shown (a relative POSIX URI when the
path is relative or under the working directory), the element's start line and
the column of its start tag; the element path goes into a logical location.
No ``partialFingerprints``: the upload-sarif action computes them.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path, PurePosixPath, PureWindowsPath
from typing import Any
from urllib.parse import quote

from urdflint.finding import Finding, Severity
from urdflint.formatters import RunInfo

SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"
INFORMATION_URI = "https://github.com/urdflint/urdflint"
LEVEL = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "note"}
PROBLEM_SEVERITY = {
    Severity.ERROR: "error",
    Severity.WARNING: "warning",
    Severity.INFO: "recommendation",
}
FAMILY_TAGS = {
    "X": "document",
    "S": "structure",
    "I": "inertial",
    "C": "geometry",
    "G": "gazebo",
    "J": "joints",
    "T": "transmissions",
    "P": "physics",
    "U": "urdflint",
}
MAX_DESCRIPTION = 1024  # GitHub's cap on shortDescription/fullDescription text


def _clip(text: str, limit: int = MAX_DESCRIPTION) -> str:
    text = " ".join(text.split())
    if len(text) <= limit:
        return text
    cut = text[: limit - 1].rsplit(" ", 1)[0]
    return cut + "…"


def _rule_descriptor(code: str, sample: Finding) -> dict[str, Any]:
    from urdflint import registry

    registry.load_rules()
    rule = registry.RULES.get(code)
    if rule is None:  # not a registered rule (should not happen): describe it from the finding
        return {
            "id": code,
            "name": sample.name,
            "shortDescription": {"text": sample.name},
            "fullDescription": {"text": sample.name},
            "help": {"text": sample.fix or sample.name},
            "defaultConfiguration": {"level": LEVEL[sample.severity]},
            "properties": {"tags": ["urdf"]},
        }
    sections = [(h, rule.section(h)) for h in ("What it does", "Why is this bad?", "How to fix")]
    sections = [(h, body) for h, body in sections if body]
    markdown = "\n\n".join(f"## {h}\n\n{body}" for h, body in sections) or rule.summary
    text = "\n\n".join(f"{h}\n{body}" for h, body in sections) or rule.summary
    if rule.fix:
        markdown += f"\n\n**Quick fix:** {rule.fix}"
        text += f"\n\nQuick fix: {rule.fix}"
    tags = ["urdf", FAMILY_TAGS.get(rule.family, "urdf")]
    tags += [need for need in rule.needs if need not in tags]
    return {
        "id": rule.code,
        "name": rule.name,
        "shortDescription": {"text": _clip(rule.summary)},
        "fullDescription": {"text": _clip(rule.section("What it does") or rule.summary)},
        "help": {"text": text, "markdown": markdown},
        "defaultConfiguration": {"level": LEVEL[rule.severity]},
        "properties": {
            "tags": list(dict.fromkeys(tags)),
            "problem.severity": PROBLEM_SEVERITY[rule.severity],
        },
    }


def artifact_uri(path: str, cwd: Path | None = None) -> str:
    """The file as a URI reference: relative POSIX when possible, else ``file://``."""
    if "\\" in path and PureWindowsPath(path).is_absolute():
        return PureWindowsPath(path).as_uri()
    posix = PurePosixPath(path.replace("\\", "/"))
    if posix.is_absolute():
        base = PurePosixPath((cwd or Path.cwd()).resolve().as_posix())
        try:
            posix = posix.relative_to(base)
        except ValueError:
            return posix.as_uri()
    parts = [p for p in posix.parts if p != "."]
    return quote("/".join(parts) or ".", safe="/")


def _result(finding: Finding, index: int) -> dict[str, Any]:
    result: dict[str, Any] = {
        "ruleId": finding.code,
        "ruleIndex": index,
        "level": LEVEL[finding.severity],
        "message": {"text": finding.message},
        "locations": [
            {
                "physicalLocation": {
                    "artifactLocation": {"uri": artifact_uri(finding.path)},
                    "region": {
                        "startLine": finding.line,
                        "startColumn": finding.column,
                        "endLine": finding.line,
                    },
                },
                "logicalLocations": [{"fullyQualifiedName": finding.element, "kind": "element"}],
            }
        ],
    }
    if finding.fix:
        result["properties"] = {"fix": finding.fix}
    return result


def document(findings: Sequence[Finding], run: RunInfo) -> dict[str, Any]:
    """The SARIF log as a dict (``render`` serialises it)."""
    samples: dict[str, Finding] = {}
    for finding in findings:
        samples.setdefault(finding.code, finding)
    codes = sorted(samples)
    index = {code: i for i, code in enumerate(codes)}
    return {
        "$schema": SCHEMA,
        "version": "2.1.0",
        "runs": [
            {
                "tool": {
                    "driver": {
                        "name": "urdflint",
                        "version": run.tool_version,
                        "informationUri": INFORMATION_URI,
                        "rules": [_rule_descriptor(code, samples[code]) for code in codes],
                    }
                },
                "columnKind": "unicodeCodePoints",
                "results": [_result(f, index[f.code]) for f in findings],
            }
        ],
    }


def render(findings: Sequence[Finding], run: RunInfo) -> str:
    return json.dumps(document(findings, run), indent=2, ensure_ascii=False) + "\n"
