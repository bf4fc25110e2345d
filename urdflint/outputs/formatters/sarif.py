"""SARIF 2.1.0 for GitHub code scanning (``--format sarif``, ``?format=sarif``).

One run, one tool (urdflint). ``rules`` lists the rules that produced results,
sorted by code, and each result points at its rule by ``ruleId`` and
``ruleIndex``. Locations are the file as a URI relative to the repository root (see
:func:`artifact_uri`), the element's start line and the column of its start
tag; the element path goes into a logical location.

Fingerprints: each result carries ``partialFingerprints`` =
``{"urdflintFingerprint/v1": Finding.fingerprint()}``, a hash of path, rule code
and element path -- not the line, so a finding keeps its identity when lines
above it move. SARIF allows any key here (a ``name/vN`` versioned string).
GitHub code scanning matches alerts only on ``primaryLocationLineHash``, which
the ``upload-sarif`` action still computes and adds next to ours (it fills that
key only when absent), so we deliberately do not emit ``primaryLocationLineHash``
(a value not computed GitHub's way would be flagged as inconsistent). Other
consumers (SARIF viewers, DefectDojo, baselines) can use our key to follow a
finding across edits.
"""

from __future__ import annotations

import json
import posixpath
from collections.abc import Sequence
from pathlib import Path, PurePosixPath, PureWindowsPath
from typing import Any
from urllib.parse import quote

from urdflint.model.finding import Finding, Severity
from urdflint.outputs.formatters.run import RunInfo

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
FINGERPRINT_KEY = "urdflintFingerprint/v1"
MAX_DESCRIPTION = 1024  # GitHub's cap on shortDescription/fullDescription text


def _clip(text: str, limit: int = MAX_DESCRIPTION) -> str:
    text = " ".join(text.split())
    if len(text) <= limit:
        return text
    cut = text[: limit - 1].rsplit(" ", 1)[0]
    return cut + "…"


def help_uri(docs_url: str | None, rule: Any) -> str | None:
    """The rule page's URL from the ``docs_url`` template (:class:`RunInfo`)."""
    if not docs_url:
        return None
    module = rule.check.__module__.removeprefix("urdflint.")  # rules.inertial.i005_...
    fields = {"code": rule.code, "name": rule.name, "path": module.replace(".", "/") + ".py"}
    if not any("{" + key + "}" in docs_url for key in fields):
        return docs_url.rstrip("/") + "/" + rule.code
    for key, value in fields.items():
        docs_url = docs_url.replace("{" + key + "}", quote(value))
    return docs_url


def _rule_descriptor(code: str, sample: Finding, docs_url: str | None = None) -> dict[str, Any]:
    from urdflint.engine import registry

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
    link = help_uri(docs_url, rule)
    return {
        "id": rule.code,
        **({"helpUri": link} if link else {}),
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


def repo_root(cwd: Path) -> Path | None:
    """The git top-level holding ``cwd`` (a ``.git`` folder or worktree file), if any."""
    for folder in (cwd, *cwd.parents):
        if (folder / ".git").exists():
            return folder
    return None


def artifact_uri(path: str, cwd: Path | None = None, root: Path | None = None) -> str:
    """The file as a URI reference: relative POSIX when possible, else ``file://``.

    Relative to ``root`` (default: the git top-level holding the working directory,
    so ``cd robots && urdflint check .`` still gives ``robots/arm.urdf``, which is
    what GitHub code scanning resolves against the checkout), else to ``cwd``. A
    relative name that is no file under ``cwd`` (``<stdin>``, a service upload
    name) is kept as given; an absolute path outside the base stays a file URI.
    """
    if "\\" in path and PureWindowsPath(path).is_absolute():
        return PureWindowsPath(path).as_uri()
    here = (cwd or Path.cwd()).resolve()
    posix = PurePosixPath(path.replace("\\", "/"))
    if not posix.is_absolute():
        if root is None and not (here / posix.as_posix()).is_file():
            return _relative_uri(posix)
        posix = PurePosixPath(posixpath.normpath(PurePosixPath(here.as_posix()) / posix))
    base = root.resolve() if root is not None else (repo_root(here) or here)
    for candidate in (PurePosixPath(base.as_posix()), PurePosixPath(here.as_posix())):
        try:
            return _relative_uri(posix.relative_to(candidate))
        except ValueError:
            continue
    return posix.as_uri()


def _relative_uri(posix: PurePosixPath) -> str:
    parts = [p for p in posix.parts if p != "."]
    return quote("/".join(parts) or ".", safe="/")


def _result(finding: Finding, index: int, uri: str, uris: dict[str, str]) -> dict[str, Any]:
    result: dict[str, Any] = {
        "ruleId": finding.code,
        "ruleIndex": index,
        "level": LEVEL[finding.severity],
        "message": {"text": finding.message},
        "locations": [
            {
                "physicalLocation": {
                    "artifactLocation": {"uri": uri},
                    "region": {
                        "startLine": finding.line,
                        "startColumn": finding.column,
                        "endLine": finding.line,
                    },
                },
                "logicalLocations": [{"fullyQualifiedName": finding.element, "kind": "element"}],
            }
        ],
        "partialFingerprints": {FINGERPRINT_KEY: finding.fingerprint()},
    }
    if finding.fix:
        result["properties"] = {"fix": finding.fix}
    if finding.trace:
        _add_trace(result, finding, uri, uris)
    return result


def _location(uri: str, line: int, column: int, message: str | None = None) -> dict[str, Any]:
    region = {"startLine": line, "startColumn": column, "endLine": line}
    location: dict[str, Any] = {
        "physicalLocation": {"artifactLocation": {"uri": uri}, "region": region}
    }
    if message is not None:
        location["message"] = {"text": message}
    return location


def _add_trace(result: dict[str, Any], finding: Finding, uri: str, uris: dict[str, str]) -> None:
    """xacro: the macro calls as related locations and as a code flow, outermost call first."""
    calls = list(reversed(finding.trace))
    related = []
    for i, call in enumerate(calls, start=1):
        location = _location(uris[call.path], call.line, call.column, f"calls macro {call.macro}")
        related.append({"id": i, **location})
    result["relatedLocations"] = related
    steps = [{"location": _location(uris[c.path], c.line, c.column, f"calls macro {c.macro}")}
             for c in calls]  # fmt: skip
    steps.append({"location": _location(uri, finding.line, finding.column, finding.message)})
    result["codeFlows"] = [{"threadFlows": [{"locations": steps}]}]


def document(findings: Sequence[Finding], run: RunInfo) -> dict[str, Any]:
    """The SARIF log as a dict (``render`` serialises it)."""
    samples: dict[str, Finding] = {}
    for finding in findings:
        samples.setdefault(finding.code, finding)
    codes = sorted(samples)
    index = {code: i for i, code in enumerate(codes)}
    cwd = Path.cwd().resolve()
    paths = {f.path for f in findings} | {c.path for f in findings for c in f.trace}
    uris = {path: artifact_uri(path, cwd) for path in paths}
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
                        "rules": [
                            _rule_descriptor(code, samples[code], run.docs_url) for code in codes
                        ],
                    }
                },
                "columnKind": "unicodeCodePoints",
                "results": [_result(f, index[f.code], uris[f.path], uris) for f in findings],
            }
        ],
    }


def render(findings: Sequence[Finding], run: RunInfo) -> str:
    return json.dumps(document(findings, run), indent=2, ensure_ascii=False) + "\n"
