"""The catalogue itself: codes, names, docs sections, family packages, README table."""

from __future__ import annotations

import importlib
import pkgutil
import re

import urdflint.rules

from tests.conftest import ROOT
from urdflint.engine import docs, registry

RULES = registry.load_rules()


def test_codes_and_names_are_well_formed_and_unique() -> None:
    names = [r.name for r in RULES.values()]
    assert len(names) == len(set(names))
    for code, rule in RULES.items():
        assert registry.CODE_RE.fullmatch(code)
        assert registry.NAME_RE.fullmatch(rule.name)
        assert rule.family in registry.FAMILIES


def test_every_rule_documents_what_why_and_how_to_fix() -> None:
    for rule in RULES.values():
        for heading in ("What it does", "Why is this bad?", "How to fix"):
            assert rule.section(heading), f"{rule.code}: missing '## {heading}'"
        assert rule.summary.endswith("."), f"{rule.code}: summary should be one sentence"


def test_every_rule_module_is_imported_and_registers_one_rule() -> None:
    by_module = {rule.check.__module__ for rule in RULES.values()}
    for family in pkgutil.iter_modules(urdflint.rules.__path__):
        if not family.ispkg:
            continue  # shared tables (consequences), not a family
        package = importlib.import_module(f"urdflint.rules.{family.name}")
        for module in pkgutil.iter_modules(package.__path__):
            name = f"urdflint.rules.{family.name}.{module.name}"
            if re.fullmatch(r"[a-z]\d{3}_\w+", module.name):
                assert name in by_module, f"{name} is not imported by its family __init__"
                code = module.name[:4].upper()
                assert RULES[code].check.__module__ == name


def test_selectors_accept_codes_names_and_families() -> None:
    assert registry.expand(["X001"]) == {"X001"}
    assert registry.expand(["invalid-xml"]) == {"X001"}
    assert "X002" in registry.expand(["X"])
    try:
        registry.expand(["nope"])
    except ValueError as exc:
        assert "nope" in str(exc)
    else:
        raise AssertionError("unknown selector accepted")


def test_readme_rule_table_is_current() -> None:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    match = re.search(r"<!-- rules:start -->\n(.*?)<!-- rules:end -->", readme, re.S)
    assert match, "README.md lacks the <!-- rules:start --> / <!-- rules:end --> markers"
    assert match.group(1) == docs.rule_table(), (
        "README rule table is stale: run python -m urdflint.engine.docs"
    )
