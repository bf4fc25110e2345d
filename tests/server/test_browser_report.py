"""The dataset report page (``urdflint report --html``) in a real headless Chromium.

The page is opened from disk (``file://``: it must work offline, with nothing to fetch):
its sections render, the three plots are visible SVGs with bars, the load matrix shows the
numbers of the JSON summary, a path with ``<script>`` in it is text, the rule table sorts,
and the console stays clean. A screenshot (1400 px wide) goes to the test's folder, and to
``$URDFLINT_SCREENSHOTS`` when set.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("selenium.webdriver")

from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import WebDriverWait

from tests.server.browsing import CHROMEDRIVER, CHROMIUM, screenshot
from tests.test_report import DATASET, HOSTILE, hostile, record, write

pytestmark = [
    pytest.mark.slow,  # a real browser
    pytest.mark.skipif(
        CHROMIUM is None or CHROMEDRIVER is None,
        reason="needs chromium and chromedriver (Debian: apt-get install chromium chromium-driver)",
    ),
]

SECTIONS = ("headline", "severities", "rules", "matrix", "worst", "distributions", "diff")


@pytest.fixture(scope="module")
def report(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict[str, Any]]:
    """The page of a run with a hostile path, against an earlier run; and its JSON summary."""
    folder = tmp_path_factory.mktemp("report")
    new = write(folder / "new.jsonl", hostile())
    old = write(folder / "old.jsonl", [*DATASET[:3], record(HOSTILE)])
    page = folder / "report.html"
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "urdflint",
            "report",
            str(new),
            "--against",
            str(old),
            "--html",
            str(page),
            "--format",
            "json",
        ],
        capture_output=True,
        text=True,
        check=True,
    )
    return page, json.loads(done.stdout)


@pytest.fixture
def shown(driver: Any, report: tuple[Path, dict[str, Any]]) -> dict[str, Any]:
    """The page opened afresh; its summary."""
    page, summary = report
    driver.get_log("browser")  # start with an empty console
    driver.get(page.as_uri())
    ready = "return document.readyState"
    WebDriverWait(driver, 20).until(lambda d: d.execute_script(ready) == "complete")
    return summary


def console_errors(driver: Any) -> list[str]:
    return [e["message"] for e in driver.get_log("browser") if e["level"] in ("SEVERE", "ERROR")]


def test_every_section_renders_and_the_console_is_clean(driver, shown, tmp_path) -> None:
    for section in SECTIONS:
        element = driver.find_element(By.ID, section)
        assert element.is_displayed(), section
        assert element.size["height"] > 40, section
    stats = {
        e.get_attribute("data-stat"): e.find_element(By.CLASS_NAME, "value").text
        for e in driver.find_elements(By.CSS_SELECTOR, "#headline .stat")
    }
    assert stats["files"] == str(shown["files"])
    assert stats["errors"] == str(shown["status"]["errors"])
    assert stats["clean"] == str(shown["status"]["clean"])
    diff = {
        e.get_attribute("data-stat"): int(e.get_attribute("data-value"))
        for e in driver.find_elements(By.CSS_SELECTOR, "#diff-stats .stat")
    }
    files = shown["diff"]["files"]
    assert diff["worse"] == files["worse"] and diff["added"] == files["added"]
    assert diff["new"] == shown["diff"]["new_findings"]["count"]
    assert console_errors(driver) == []
    target = screenshot(driver, tmp_path / "dataset-report.png")
    if os.environ.get("URDFLINT_SCREENSHOTS"):
        shutil.copy(target, Path(os.environ["URDFLINT_SCREENSHOTS"]) / target.name)


def test_the_plots_are_visible_svgs_with_bars(driver, shown) -> None:
    plots = driver.execute_script("""
      return Array.from(document.querySelectorAll('svg.plot'), (svg) => {
        const box = svg.getBoundingClientRect();
        const bars = Array.from(svg.querySelectorAll('g.bin rect'),
                                (r) => r.getBoundingClientRect().height);
        return {plot: svg.dataset.plot, width: box.width, height: box.height,
                visible: getComputedStyle(svg).visibility === 'visible' && box.width > 0,
                bars: bars.length, drawn: bars.filter((h) => h > 0).length,
                counts: Array.from(svg.querySelectorAll('g.bin'), (g) => Number(g.dataset.count))};
      });""")
    assert [p["plot"] for p in plots] == ["mass", "links", "findings"]
    for p in plots:
        bins = shown["distributions"][p["plot"]]["bins"]
        assert p["visible"] and p["width"] > 200 and p["height"] > 100, p
        assert p["bars"] == len(bins) and p["counts"] == [b["count"] for b in bins]
        assert p["drawn"] == sum(1 for b in bins if b["count"]), p


def test_the_matrix_shows_the_numbers_of_the_summary(driver, shown) -> None:
    cells = driver.execute_script("""
      return Array.from(document.querySelectorAll('#matrix-table td.cell'), (td) => ({
        target: td.dataset.target, outcome: td.dataset.outcome,
        count: Number(td.dataset.count), shown: td.firstChild.textContent.trim(),
        background: getComputedStyle(td).backgroundColor}));""")
    expected = {
        (t["target"], o): t[o]
        for t in shown["matrix"]["targets"]
        for o in ("loads", "changes", "refused", "crashes")
    }
    assert {(c["target"], c["outcome"]): c["count"] for c in cells} == expected
    assert {(c["target"], c["outcome"]): int(c["shown"].replace(",", "")) for c in cells} == (
        expected
    )
    transparent = "rgba(0, 0, 0, 0)"
    assert all((c["background"] != transparent) == bool(c["count"]) for c in cells)


def test_a_path_with_a_script_in_it_is_text(driver, shown) -> None:
    assert driver.execute_script("return window.owned === undefined")
    assert len(driver.find_elements(By.TAG_NAME, "script")) == 1
    rows = driver.find_elements(By.CSS_SELECTOR, "#worst-table tr[data-path]")
    paths = [r.get_attribute("data-path") for r in rows]
    assert HOSTILE in paths
    row = rows[paths.index(HOSTILE)]
    assert row.find_element(By.CLASS_NAME, "path").text == HOSTILE
    assert [w["path"] for w in shown["worst"]] == paths


def test_the_rule_table_sorts(driver, shown) -> None:
    def findings() -> list[int]:
        return [
            int(r.get_attribute("data-findings"))
            for r in driver.find_elements(By.CSS_SELECTOR, "#rule-table tbody tr")
        ]

    assert findings() == [r["findings"] for r in shown["rules"]]
    head = driver.find_elements(By.CSS_SELECTOR, "#rule-table thead th")[3]
    head.click()
    assert findings() == sorted(findings(), reverse=True)
    assert head.get_attribute("aria-sort") == "descending"
    head.click()
    assert findings() == sorted(findings())
    code = driver.find_elements(By.CSS_SELECTOR, "#rule-table thead th")[0]
    code.click()
    codes = [
        r.get_attribute("data-code")
        for r in driver.find_elements(By.CSS_SELECTOR, "#rule-table tbody tr")
    ]
    assert codes == sorted(codes, key=str.lower, reverse=True)
    assert console_errors(driver) == []
