"""One generic runner over every rule and its fixtures (fixtures/rules/<CODE>/).

``good*.urdf`` must produce no finding of the rule; ``bad*.urdf`` must produce
exactly the ``(line, code, element)`` triples written as ``<!-- expect: ... -->``
comments on the offending lines.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.conftest import FIXTURES
from tests.helpers import expectations, fixture_settings, lint_file
from urdflint.engine import registry
from urdflint.model.finding import Severity

# Rules that cannot have a file fixture: produced by the engine itself.
EXEMPT = {"E007", "U001", "U004", "U005"}  # about the run or the machine, not a model

RULES = sorted(registry.load_rules().values(), key=lambda r: r.code)


SUFFIXES = (".urdf", ".xacro")


def fixtures(code: str, prefix: str) -> list:
    folder = FIXTURES / "rules" / code
    return sorted(p for p in folder.glob(f"{prefix}*") if p.suffix in SUFFIXES)


@pytest.mark.parametrize("rule", [r for r in RULES if r.code not in EXEMPT], ids=lambda r: r.code)
def test_rule_has_fixtures(rule: registry.Rule) -> None:
    assert fixtures(rule.code, "good"), f"{rule.code}: no good*.urdf or good*.xacro"
    assert fixtures(rule.code, "bad"), f"{rule.code}: no bad*.urdf or bad*.xacro"


def _cases(prefix: str) -> list[tuple[str, object]]:
    cases = []
    for rule in RULES:
        for path in fixtures(rule.code, prefix):
            slow = [pytest.mark.slow] if fixture_settings(path).confirm else []  # the engines
            cases.append(pytest.param(rule, path, id=f"{rule.code}/{path.name}", marks=slow))
    return cases


def _skip_without_engines(path: Path) -> None:
    """A fixture confirmed with engines (``confirm`` in its settings: the E rules) runs only
    when every one of them is installed (``urdflint[engines]``)."""
    from urdflint.engines.runner import installed

    missing = [e for e in fixture_settings(path).confirm if not installed(e)]
    if missing:
        pytest.skip(f"{', '.join(missing)} not installed")


@pytest.mark.parametrize(("rule", "path"), _cases("good"))
def test_good_fixture_is_clean(rule: registry.Rule, path) -> None:
    _skip_without_engines(path)
    found = [f for f in lint_file(path, select=(rule.code,)) if f.code == rule.code]
    assert found == [], "\n".join(f"{f.line}: {f.code} {f.message}" for f in found)


@pytest.mark.parametrize(("rule", "path"), _cases("good"))
def test_good_fixture_has_no_errors_from_any_rule(rule: registry.Rule, path) -> None:
    _skip_without_engines(path)
    found = [f for f in lint_file(path) if f.severity is Severity.ERROR]
    assert found == [], "\n".join(f"{f.line}: {f.code} {f.message}" for f in found)


@pytest.mark.parametrize(("rule", "path"), _cases("bad"))
def test_bad_fixture_matches_expectations(rule: registry.Rule, path) -> None:
    _skip_without_engines(path)
    findings = [f for f in lint_file(path, select=(rule.code,)) if f.code == rule.code]
    # a xacro fixture's finding may belong to a file it includes: expectations live there
    files = {path} | {Path(f.path) for f in findings if Path(f.path).is_file()}
    expected = {(p.name, *e) for p in files for e in expectations(p)}
    assert expected, f"{path} has no <!-- expect: ... --> comment"
    assert {code for _, _, code, _ in expected} == {rule.code}, (
        "a bad fixture expects only its own rule"
    )
    found = {(Path(f.path).name, f.line, f.code, f.element) for f in findings}
    assert found == expected
