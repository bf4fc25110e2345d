"""SARIF 2.1.0 output: valid against the OASIS schema and usable by GitHub code scanning."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import FIXTURES, ROOT, corpus_models, needs_corpus
from urdflint import __version__
from urdflint.engine import registry
from urdflint.model.finding import Finding, Severity
from urdflint.outputs.formatters import NAMES, RunInfo, get, sarif

SCHEMA = ROOT / "tests" / "data" / "sarif-schema-2.1.0.json"  # the OASIS schema, shipped
BROKEN = FIXTURES / "models" / "broken_arm.urdf"


def _finding(code: str, severity: Severity, message: str, path: str = "robots/arm.urdf") -> Finding:
    rule = registry.lookup(code)
    assert rule is not None
    return Finding(
        path, 12, 5, code, rule.name, severity, message, "/robot/joint[@name='j']", "do X"
    )


def _validate(log: dict[str, object]) -> None:
    import jsonschema

    schema = json.loads(SCHEMA.read_text(encoding="utf-8"))
    validator = jsonschema.validators.validator_for(schema)(schema)
    errors = sorted(validator.iter_errors(log), key=lambda e: list(e.path))
    assert not errors, "\n".join(f"{list(e.path)}: {e.message}" for e in errors)


def _cli_sarif(*args: str) -> dict[str, Any]:
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--format", "sarif", *args],
        capture_output=True,
        text=True,
        cwd=ROOT,
        check=False,
    )
    assert proc.returncode in (0, 1), proc.stderr
    return json.loads(proc.stdout)


def test_registered_as_a_format() -> None:
    assert "sarif" in NAMES
    assert get("sarif") is sarif.render


def test_cli_output_on_a_broken_model_validates() -> None:
    _validate(_cli_sarif(str(BROKEN.relative_to(ROOT))))


def test_empty_run_validates() -> None:
    log = json.loads(sarif.render([], RunInfo(__version__, ("a.urdf",))))
    _validate(log)
    run = log["runs"][0]
    assert run["results"] == [] and run["tool"]["driver"]["rules"] == []


def test_special_characters_survive_and_validate() -> None:
    message = "link 'a\"b' has <mass> & \u00b5 = 1e-9 kg·m² \\ %0A\nsecond line \U0001f916"
    findings = [_finding("I002", Severity.ERROR, message, path="my robots/ärm #1.urdf")]
    text = sarif.render(findings, RunInfo(__version__, ("x",)))
    log = json.loads(text)
    _validate(log)
    result = log["runs"][0]["results"][0]
    assert result["message"]["text"] == message
    uri = result["locations"][0]["physicalLocation"]["artifactLocation"]["uri"]
    assert uri == "my%20robots/%C3%A4rm%20%231.urdf"


def test_structure_of_a_real_run() -> None:
    log = _cli_sarif(str(BROKEN.relative_to(ROOT)))
    assert log["$schema"] == sarif.SCHEMA and log["version"] == "2.1.0"
    (run,) = log["runs"]
    driver = run["tool"]["driver"]
    assert driver["name"] == "urdflint" and driver["version"] == __version__
    assert driver["informationUri"].startswith("https://")
    rules = driver["rules"]
    ids = [r["id"] for r in rules]
    assert ids == sorted(set(ids)), "one descriptor per rule, sorted by code"
    results = run["results"]
    assert results and {r["ruleId"] for r in results} == set(ids), "rules = the rules with results"
    for rule in rules:
        reg = registry.lookup(rule["id"])
        assert reg is not None and rule["name"] == reg.name
        for key in ("shortDescription", "fullDescription"):
            assert 0 < len(rule[key]["text"]) <= 1024
        assert rule["help"]["text"] and "## How to fix" in rule["help"]["markdown"]
        assert rule["defaultConfiguration"]["level"] == sarif.LEVEL[reg.severity]
        assert "urdf" in rule["properties"]["tags"] and len(rule["properties"]["tags"]) <= 20
    for result in results:
        assert rules[result["ruleIndex"]]["id"] == result["ruleId"]
        assert result["level"] in {"error", "warning", "note"}
        assert result["message"]["text"]
        assert "fingerprints" not in result
        assert set(result["partialFingerprints"]) == {sarif.FINGERPRINT_KEY}
        assert "primaryLocationLineHash" not in result["partialFingerprints"]
        (location,) = result["locations"]
        physical = location["physicalLocation"]
        assert physical["artifactLocation"]["uri"] == "fixtures/models/broken_arm.urdf"
        region = physical["region"]
        assert region["startLine"] >= 1 and region["startColumn"] >= 1
        assert region["endLine"] == region["startLine"]
        assert location["logicalLocations"][0]["fullyQualifiedName"].startswith("/robot")
    levels = {r["level"] for r in results}
    assert levels == {"error", "warning", "note"}, "broken_arm has errors, warnings and infos"
    by_line = {
        (r["ruleId"], r["locations"][0]["physicalLocation"]["region"]["startLine"]) for r in results
    }
    assert ("J001", 33) in by_line and ("I002", 44) in by_line


def test_same_findings_as_json() -> None:
    args = [str(BROKEN.relative_to(ROOT))]
    log = _cli_sarif(*args)
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--format", "json", *args],
        capture_output=True,
        text=True,
        cwd=ROOT,
        check=False,
    )
    expected = [
        (f["code"], f["line"], f["column"], f["message"])
        for f in json.loads(proc.stdout)["findings"]
    ]
    got = [
        (
            r["ruleId"],
            r["locations"][0]["physicalLocation"]["region"]["startLine"],
            r["locations"][0]["physicalLocation"]["region"]["startColumn"],
            r["message"]["text"],
        )
        for r in log["runs"][0]["results"]
    ]
    assert got == expected


def test_result_level_follows_the_finding_not_the_rule_default() -> None:
    # J001 defaults to error; a configured or target-specific severity must win per result.
    log = sarif.document([_finding("J001", Severity.INFO, "x")], RunInfo(__version__))
    run = log["runs"][0]
    assert run["results"][0]["level"] == "note"
    assert run["tool"]["driver"]["rules"][0]["defaultConfiguration"]["level"] == "error"


@pytest.mark.parametrize(
    ("path", "uri"),
    [
        ("robots/arm.urdf", "robots/arm.urdf"),
        ("./arm.urdf", "arm.urdf"),
        ("robots\\arm.urdf", "robots/arm.urdf"),
        ("<stdin>", "%3Cstdin%3E"),
        ("/elsewhere/arm.urdf", "file:///elsewhere/arm.urdf"),
        ("C:\\robots\\arm.urdf", "file:///C:/robots/arm.urdf"),
    ],
)
def test_artifact_uri(path: str, uri: str) -> None:
    assert sarif.artifact_uri(path, cwd=Path("/work")) == uri


def test_absolute_path_under_the_working_directory_becomes_relative(tmp_path: Path) -> None:
    assert sarif.artifact_uri(str(tmp_path / "a b" / "r.urdf"), cwd=tmp_path) == "a%20b/r.urdf"


def test_every_rule_has_a_describable_page() -> None:
    for code in sorted(registry.load_rules()):
        log = sarif.document([_finding(code, Severity.WARNING, "m")], RunInfo("0"))
        rule = log["runs"][0]["tool"]["driver"]["rules"][0]
        assert rule["id"] == code
        assert 0 < len(rule["shortDescription"]["text"]) <= 1024
        assert 0 < len(rule["fullDescription"]["text"]) <= 1024
        assert len(rule["name"]) <= 255


def test_the_schema_check_is_not_vacuous() -> None:
    log = sarif.document([_finding("J001", Severity.ERROR, "x")], RunInfo(__version__))
    del log["runs"][0]["results"][0]["message"]
    with pytest.raises(AssertionError, match="'message' is a required property"):
        _validate(log)


def test_schema_is_the_official_one() -> None:
    schema = json.loads(SCHEMA.read_text(encoding="utf-8"))
    assert schema["id"].startswith("https://docs.oasis-open.org/sarif/sarif/v2.1.0/")
    assert schema["properties"]["version"]["enum"] == ["2.1.0"]


def test_partial_fingerprint_ignores_line_and_message() -> None:
    a = _finding("J001", Severity.ERROR, "one")
    moved = Finding(a.path, 99, 1, a.code, a.name, a.severity, "reworded", a.element, a.fix)
    other = Finding(a.path, 12, 5, a.code, a.name, a.severity, "one", "/robot/joint[@name='k']")
    prints = [
        sarif.document([f], RunInfo("0"))["runs"][0]["results"][0]["partialFingerprints"]
        for f in (a, moved, other)
    ]
    assert prints[0] == prints[1] == {sarif.FINGERPRINT_KEY: a.fingerprint()}
    assert prints[2] != prints[0]


def test_paths_are_relative_to_the_repository_root(tmp_path: Path) -> None:
    (tmp_path / ".git").mkdir()
    sub = tmp_path / "robots" / "arm"
    sub.mkdir(parents=True)
    (sub / "model.urdf").write_text("<robot name='r'/>", encoding="utf-8")
    assert sarif.artifact_uri("model.urdf", cwd=sub) == "robots/arm/model.urdf"
    assert sarif.artifact_uri("./arm/model.urdf", cwd=sub.parent) == "robots/arm/model.urdf"
    assert sarif.artifact_uri(str(sub / "model.urdf"), cwd=sub) == "robots/arm/model.urdf"
    # a name that is no file here (stdin, a service upload) is kept as given
    assert sarif.artifact_uri("<stdin>", cwd=sub) == "%3Cstdin%3E"
    assert sarif.artifact_uri("/elsewhere/x.urdf", cwd=sub) == "file:///elsewhere/x.urdf"


@needs_corpus
def test_sarif_of_the_whole_corpus_validates() -> None:
    models = corpus_models()
    log = _cli_sarif(*(str(m) for m in models))
    _validate(log)
    (run,) = log["runs"]
    assert run["results"], "the corpus has findings"
    uris = {
        r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] for r in run["results"]
    }
    assert uris <= {sarif.artifact_uri(str(m), cwd=ROOT) for m in models}
    for result in run["results"]:
        assert len(result["partialFingerprints"][sarif.FINGERPRINT_KEY]) == 32


# -- helpUri: each rule's page ---------------------------------------------------------------


@pytest.mark.parametrize(
    ("template", "expected"),
    [
        (None, None),
        ("https://docs.example.org/rules/", "https://docs.example.org/rules/I005"),
        ("https://docs.example.org/rules/{code}.html", "https://docs.example.org/rules/I005.html"),
        ("https://x.org/{name}", "https://x.org/triangle-inequality"),
        (
            "https://github.com/o/urdflint/blob/v1/{path}",
            "https://github.com/o/urdflint/blob/v1/rules/inertial/i005_triangle_inequality.py",
        ),
    ],
)
def test_help_uri_follows_the_docs_url_template(template: str | None, expected: str | None) -> None:
    finding = _finding("I005", Severity.ERROR, "bad")
    log = sarif.document([finding], RunInfo(__version__, docs_url=template))
    (rule,) = log["runs"][0]["tool"]["driver"]["rules"]
    assert rule.get("helpUri") == expected
    _validate(log)


def test_every_rule_module_path_exists_for_the_path_template() -> None:
    for rule in registry.load_rules().values():
        path = sarif.help_uri("{path}", rule)
        assert path is not None and (ROOT / path).is_file(), path


def test_cli_help_uri_from_the_option_and_the_environment(tmp_path: Path) -> None:
    given = _cli_sarif("--docs-url", "https://d.example/{code}", str(BROKEN.relative_to(ROOT)))
    rules = given["runs"][0]["tool"]["driver"]["rules"]
    assert rules and all(r["helpUri"] == f"https://d.example/{r['id']}" for r in rules)
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--format", "sarif", str(BROKEN)],
        capture_output=True, text=True, cwd=ROOT, check=False,
        env={**os.environ, "URDFLINT_DOCS_URL": "https://e.example/r/"},
    )  # fmt: skip
    rules = json.loads(proc.stdout)["runs"][0]["tool"]["driver"]["rules"]
    assert all(r["helpUri"] == f"https://e.example/r/{r['id']}" for r in rules)
