"""``urdflint explain``: a short page by default (what, why, how to fix, one bad and one good
snippet, at most ``docs.SHORT_LIMIT`` lines), the full page with ``--long``; neither shows
the comments only the fixture runner reads."""

from __future__ import annotations

import re
import textwrap

import pytest

from tests.conftest import FIXTURES
from urdflint.cli import main
from urdflint.engine import docs, examples, prose, registry, snippets

RULES = sorted(registry.load_rules().values(), key=lambda r: r.code)
SECTIONS = ("## What it does\n", "## Why is this bad?\n", "## How to fix\n")
TEST_ONLY = re.compile(r"expect:|\.toml")  # the runner's expectations, its settings files


def explain(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    code = main(["explain", *args])
    out, err = capsys.readouterr()
    return code, out, err


def has_fixtures(rule: registry.Rule, prefix: str) -> bool:
    folder = FIXTURES / "rules" / rule.code
    return any(p.suffix in examples.SUFFIXES for p in folder.glob(f"{prefix}*"))


def fenced_after(page: str, heading: str) -> list[str]:
    """The lines of the code block under the first heading that starts with ``heading``."""
    match = re.search(rf"^{re.escape(heading)}[^\n]*\n```xml\n(.*?)\n```$", page, re.S | re.M)
    assert match, f"no {heading!r} with a code block"
    return match.group(1).splitlines()


@pytest.mark.parametrize("rule", RULES, ids=lambda r: r.code)
def test_the_short_page_is_short_and_complete(
    capsys: pytest.CaptureFixture[str], rule: registry.Rule
) -> None:
    code, page, _ = explain(capsys, rule.code)
    assert code == 0
    lines = page.splitlines()
    assert len(lines) <= docs.SHORT_LIMIT, f"{rule.code}: {len(lines)} lines"
    assert lines[0].startswith(f"{rule.code} {rule.name} (default severity: {rule.severity};")
    assert registry.FAMILIES[rule.family] in lines[0] and lines[1] == rule.summary
    for heading in SECTIONS:
        start = page.index(heading) + len(heading)
        assert page[start:].split("\n", 1)[0].strip(), f"{rule.code}: {heading.strip()} is empty"
    assert not TEST_ONLY.search(page), TEST_ONLY.search(page)
    if not lines[-1].startswith(f"More: `urdflint explain {rule.code} --long` ("):
        for heading in SECTIONS:  # the short page is all there is
            assert heading + rule.section(heading.strip("# \n")) in page
        assert not (rule.effects or examples.load(rule.code))
    if has_fixtures(rule, "bad") and has_fixtures(rule, "good"):
        bad, good = fenced_after(page, "## Bad example"), fenced_after(page, "## Good example")
        assert 1 <= len(bad) <= 12 and 1 <= len(good) <= 12
        assert bad != good or rule.code in ("P003", "P004")  # these differ in their settings


@pytest.mark.parametrize("rule", RULES, ids=lambda r: r.code)
def test_the_long_page_has_the_evidence_and_every_example(
    capsys: pytest.CaptureFixture[str], rule: registry.Rule
) -> None:
    code, page, _ = explain(capsys, rule.code, "--long")
    assert code == 0
    assert page == docs.page(rule)  # what the service's rule page shows
    short = docs.short_page(rule)
    assert len(page.splitlines()) > len(short.splitlines()) or "\nMore: " not in short
    assert not TEST_ONLY.search(page), TEST_ONLY.search(page)
    for heading in SECTIONS:
        assert heading + rule.section(heading.strip("# \n")) in page  # in full
    if rule.effects:
        assert "## What each target does\n" in page
    for example in examples.load(rule.code):
        assert f"example ({example.name}" in page


def test_the_long_page_says_what_each_target_does(capsys: pytest.CaptureFixture[str]) -> None:
    short, long = explain(capsys, "J001")[1], explain(capsys, "J001", "--long")[1]
    assert "## What each target does" in long and "## What each target does" not in short
    assert "- PyBullet (observed with PyBullet 3.2.7): refused, error:" in long
    assert long.count("## Bad example") == 3 and short.count("## Bad example") == 1


@pytest.mark.parametrize("args", [(), ("--long",)])
def test_names_work_like_codes(capsys: pytest.CaptureFixture[str], args: tuple[str, ...]) -> None:
    for rule in RULES[::7]:
        by_code = explain(capsys, rule.code, *args)
        assert explain(capsys, rule.name, *args) == by_code
        assert explain(capsys, rule.code.lower(), *args) == by_code


@pytest.mark.parametrize("args", [(), ("--long",)])
def test_an_unknown_rule_is_a_one_line_error(
    capsys: pytest.CaptureFixture[str], args: tuple[str, ...]
) -> None:
    code, out, err = explain(capsys, "Z999", *args)
    assert (code, out) == (2, "")
    assert err == "urdflint: error: unknown rule 'Z999' (see 'urdflint rules')\n"


def test_the_short_page_of_i005(capsys: pytest.CaptureFixture[str]) -> None:
    page = explain(capsys, "triangle-inequality")[1]
    assert page.startswith(
        "I005 triangle-inequality (default severity: error; family: inertial)\n"
        "The principal moments of inertia break the triangle inequality A + B ≥ C.\n"
        "Fix: automatic, but it changes the model's physics (`urdflint fix --unsafe-fixes`).\n"
    )
    bad, good = fenced_after(page, "## Bad example (bad.urdf)"), fenced_after(page, "## Good")
    flagged = '      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.01"/>'
    assert flagged in bad and bad[0].strip() == bad[-1].strip() == "…"
    assert '      <inertia ixx="0.0075" ixy="0" ixz="0" iyy="0.0025" iyz="0" izz="0.01"/>' in good


def test_a_short_flagged_element_is_shown_whole_with_what_the_good_one_adds(
    capsys: pytest.CaptureFixture[str],
) -> None:
    page = explain(capsys, "J001")[1]
    bad, good = fenced_after(page, "## Bad example"), fenced_after(page, "## Good example")
    assert bad[1:-1] == [
        '  <joint name="shoulder" type="revolute">',
        '    <origin xyz="0 0 0.1" rpy="0 0 0"/>',
        '    <axis xyz="0 0 1"/>',
        '    <parent link="base_link"/>',
        '    <child link="link1"/>',
        "  </joint>",
    ]
    assert '    <limit lower="-1.57" upper="1.57" effort="30" velocity="2"/>' in good
    assert set(good) - set(bad) == {good[4]}  # the one line the fix adds


def test_a_fix_far_from_the_flagged_line_is_shown_apart(capsys: pytest.CaptureFixture[str]) -> None:
    page = explain(capsys, "X012")[1]  # the namespace is declared on <robot>, far above
    bad, good = fenced_after(page, "## Bad example"), fenced_after(page, "## Good example")
    assert "      <drake:proximity_properties>" in bad and '<robot name="arm">' in bad
    assert any('xmlns:drake="http://drake.mit.edu"' in line for line in good)


def test_settings_are_named_in_the_example_heading(capsys: pytest.CaptureFixture[str]) -> None:
    page = explain(capsys, "C007")[1]
    assert "## Bad example (bad.urdf, with `rules.C007.max-faces = 10`)" in page
    assert "<!-- 12 triangles, over the max-faces of 10 -->" in page  # no "(bad.toml)"


def test_srdf_fixtures_are_examples_of_the_m_rules(capsys: pytest.CaptureFixture[str]) -> None:
    page = explain(capsys, "M001")[1]
    assert "## Bad example (bad.srdf)" in page and "  </grup>" in fenced_after(page, "## Bad")
    assert "  </group>" in fenced_after(page, "## Good example (good.srdf)")


def test_clean_removes_the_test_only_comments_and_keeps_the_others() -> None:
    text = (
        '<robot name="a">\n'
        "  <link name=\"b\"/>  <!-- expect: S001 /robot/link[@name='b'] -->\n"
        "  <!-- expect: S002 /robot -->\n"
        '  <link name="c"/>\n'
        "  <!-- MuJoCo reads STL only (bad_mujoco.toml selects it) -->\n"
        "  <!-- package paths come from config.toml -->\n"
        "  <!-- two lines, about\n       bad_q.toml -->\n"
        "  <!-- a note for the reader -->\n"
        "</robot>\n"
    )
    lines, flagged = examples.clean(text)
    assert lines == [
        '<robot name="a">',
        '  <link name="b"/>',
        '  <link name="c"/>',
        "  <!-- MuJoCo reads STL only -->",
        "  <!-- a note for the reader -->",
        "</robot>",
    ]
    assert flagged == [1, 2]  # an expectation alone on its line flags the next line


def test_every_snippet_shows_a_flagged_line() -> None:
    for rule in RULES:
        found = snippets.pair(examples.load(rule.code))
        if found is None:
            assert not (has_fixtures(rule, "bad") and has_fixtures(rule, "good")), rule.code
            continue
        bad = found[0]
        shown = bad.lines()
        assert any(bad.example.lines[f] in shown for f in bad.example.flagged), rule.code


def test_condense_cuts_at_a_sentence_and_says_so() -> None:
    text = "First sentence here. Second one is longer than the first.\n\n- an item\n- another"
    assert prose.condense(text, 10) == [
        "First sentence here. Second one is longer than the first.",
        "- an item",
        "- another",
    ]
    assert prose.condense(text, 2) == [
        "First sentence here. Second one is longer than the first.",
        "- an item …",
    ]
    long = textwrap.fill(" ".join(["A sentence of some ten words that goes on and on."] * 6))
    cut = prose.condense(long, 2)
    assert len(cut) == 2 and cut[-1].endswith(". …") and all(len(x) <= prose.WIDTH + 2 for x in cut)
    listed = "Reports two cases:\n\n- the first case, written out at some length to fill a line\n"
    assert prose.condense(listed + "- the second case", 2) == [
        "Reports two cases:",
        "- the first case, written out at some length to fill a line …",
    ]
    assert prose.condense("Intro:\n\n```toml\nx = 1\n```\n", 1) == ["Intro:"]
