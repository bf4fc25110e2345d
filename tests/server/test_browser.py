"""The web page in a real headless Chromium: upload, findings table, model, tree, errors.

Needs Selenium 4 and Debian's ``chromium`` and ``chromium-driver`` (``.ci/run`` installs
them); without them every test here is skipped. The browser and the helpers are in
``tests/server/browsing.py`` (the 3D view's tests, ``test_browser_scene.py``, share
them). The server is the real ``urdflint serve``
process of ``live_server`` (tests/server/conftest.py) on a free loopback port.
"""

from __future__ import annotations

import importlib.util
import time
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import CORPUS, FIXTURES, ROOT

pytest.importorskip("selenium.webdriver")
pytest.importorskip("fastapi")
pytest.importorskip("uvicorn")

from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import WebDriverWait

from tests.server.browsing import (
    CHROMEDRIVER,
    CHROMIUM,
    check,
    rows,
    rules,
    screenshot,
    tree,
)

pytestmark = [
    pytest.mark.slow,  # a real browser
    pytest.mark.skipif(
        CHROMIUM is None or CHROMEDRIVER is None,
        reason="needs chromium and chromedriver (Debian: apt-get install chromium chromium-driver)",
    ),
]

BROKEN = FIXTURES / "models" / "broken_arm.urdf"


# -- tests ------------------------------------------------------------------------------------


def test_broken_arm_findings_model_and_tree(driver: Any, base_url: str, tmp_path: Path) -> None:
    assert check(driver, base_url, BROKEN) == "results"
    assert driver.find_element(By.ID, "banner").get_attribute("data-passed") == "false"
    assert driver.find_element(By.ID, "verdict").text == "Failed"
    assert driver.find_element(By.ID, "file-name").text == "broken_arm.urdf"

    found = rows(driver)
    pairs = {(r["line"], r["code"]) for r in found}
    expected = {("24", "X007"), ("33", "J001"), ("37", "J007"), ("44", "I002"), ("45", "I005")}
    expected |= {("61", "J009"), ("76", "S005"), ("82", "S006"), ("85", "S003"), ("91", "G001")}
    assert expected <= pairs
    groups = [r["group"] for r in found]
    assert groups == sorted(groups, key=["error", "warning", "info"].index)  # errors first
    assert all(r["group"] == r["severity"] for r in found)
    j001 = next(r for r in found if r["code"] == "J001")
    assert j001["href"] == "/rules/J001" and j001["name"] == "missing-limit"
    assert j001["element"] == j001["shownElement"] == "/robot/joint[@name='shoulder']"
    assert j001["message"] == "revolute joint 'shoulder' has no <limit>; urdfdom refuses the model"
    assert j001["fix"] and "<limit" in j001["fix"]
    for item in driver.find_elements(By.CSS_SELECTOR, "#counts li"):
        severity, count = item.get_attribute("data-severity"), item.get_attribute("data-count")
        assert int(count) == sum(r["severity"] == severity for r in found)
    assert driver.find_element(By.ID, "targets-line").text == (
        "Checked for gz-sim, ros (assumed: nothing in the model names a simulator)"
    )

    model = driver.find_element(By.CSS_SELECTOR, "#summary .model")
    assert model.get_attribute("data-built") == "false"  # urdfdom (so Pinocchio) refuses it
    assert "not built" in model.text

    picture = tree(driver)
    links = {item["name"]: item for item in picture["links"]}
    joints = {item["name"]: item for item in picture["joints"]}
    assert set(links) == {"base_footprint", "base_link", "upper_arm", "forearm", "hand"}
    assert set(joints) == {"base_joint", "shoulder", "elbow", "forearm_brace", "wrist"}
    assert links["upper_arm"]["severity"] == "error" and "I002" in links["upper_arm"]["codes"]
    assert links["base_link"]["severity"] == "warning"
    assert links["hand"]["kind"] == "missing"
    assert joints["forearm_brace"]["extra"] == "true" and joints["wrist"]["severity"] == "error"
    assert links["base_footprint"]["severity"] is None
    assert picture["scripts"] == 0 and picture["width"] > 100

    screenshot(driver, tmp_path / "broken_arm.png")


@pytest.mark.skipif(not (CORPUS / "spot" / "model.urdf").is_file(), reason="needs the corpus")
def test_corpus_robot_matches_the_api(driver: Any, base_url: str, tmp_path: Path) -> None:
    httpx = pytest.importorskip("httpx")
    path = CORPUS / "spot" / "model.urdf"
    assert check(driver, base_url, path, **{"target": "gz-sim"}) == "results"
    with path.open("rb") as handle:
        answer = httpx.post(
            f"{base_url}/v1/check",
            files={"urdf": ("model.urdf", handle, "application/xml")},
            data={"target": "gz-sim"},
            timeout=120,
        )
    assert answer.status_code == 200
    api = answer.json()
    found = rows(driver)
    order = {"error": 0, "warning": 1, "info": 2}
    # by severity, then by rule; within a rule, as the API lists them (by line)
    expected = sorted(api["findings"], key=lambda f: (order[f["severity"]], f["code"]))
    assert [(r["line"], r["code"], r["message"]) for r in found] == [
        (str(f["line"]), f["code"], f["message"]) for f in expected
    ]
    assert any(r["code"] == "I001" and r["severity"] == "error" for r in found)
    passed = driver.find_element(By.ID, "banner").get_attribute("data-passed")
    assert passed == str(api["passed"]).lower()

    model = api["models"]["model.urdf"]
    summary = driver.find_element(By.ID, "summary")
    if model is None:
        assert "not built" in summary.text
    else:
        fields = {
            dd.get_attribute("data-field"): dd.text
            for dd in summary.find_elements(By.CSS_SELECTOR, "dd")
        }
        assert fields["name"] == model["name"] == "spot"
        assert fields["root-link"] == model["root"] and fields["dof"] == str(model["dof"])
        assert fields["mass"].endswith(" kg")

    picture = tree(driver)
    links = {item["name"]: item for item in picture["links"]}
    assert len(links) == 18
    flagged = {r["element"].split("'")[1] for r in found if r["code"] == "I001"}
    assert flagged and all(links[name]["severity"] == "error" for name in flagged)

    screenshot(driver, tmp_path / "spot.png")


def test_pasted_xml_that_is_not_well_formed(driver: Any, base_url: str) -> None:
    driver.get(f"{base_url}/")
    driver.find_element(By.XPATH, "//input[@name='mode'][@value='paste']/parent::label").click()
    area = driver.find_element(By.ID, "urdf-text")
    assert area.is_displayed() and not driver.find_element(By.ID, "urdf-file").is_displayed()
    area.send_keys('<robot name="r">\n  <link name="a">\n</robot>\n')
    driver.find_element(By.ID, "submit").click()
    WebDriverWait(driver, 60).until(lambda d: d.find_element(By.ID, "results").is_displayed())
    found = rows(driver)
    assert [(r["code"], r["severity"]) for r in found] == [("X001", "error")]
    assert driver.find_element(By.ID, "file-name").text == "pasted.urdf"
    assert "No kinematic tree" in driver.find_element(By.ID, "tree").text


def test_a_rejected_request_shows_the_reason(driver: Any, base_url: str) -> None:
    assert check(driver, base_url, BROKEN, **{"expect-mass": "heavy"}) == "error"
    alert = driver.find_element(By.ID, "error")
    assert alert.get_attribute("role") == "alert"
    assert alert.get_attribute("data-status") == "422"
    assert "rejected" in alert.text and "heavy" in alert.text
    assert not driver.find_element(By.ID, "results").is_displayed()


def test_the_form_says_what_is_missing(driver: Any, base_url: str) -> None:
    assert check(driver, base_url) == "error"
    assert "Choose a URDF or xacro file" in driver.find_element(By.ID, "error").text


def test_the_page_loads_nothing_from_elsewhere(driver: Any, base_url: str) -> None:
    driver.get(f"{base_url}/")
    urls = driver.execute_script(
        "return performance.getEntriesByType('resource').map((e) => e.name)"
    )
    assert urls and all(url.startswith(base_url) for url in urls)
    html = (ROOT / "server" / "static" / "index.html").read_text()
    assert "http://" not in html.replace("http://www.w3.org", "")
    assert "https://" not in html


HOSTILE = '<img src=x onerror="window.pwned=1"><script>window.pwned=2</script>'


def test_hostile_names_stay_text(driver: Any, base_url: str) -> None:
    name = HOSTILE.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    name = name.replace('"', "&quot;")
    urdf = (
        '<robot name="r">\n  <link name="base"/>\n'
        f'  <link name="{name}"/>\n'
        f'  <joint name="{name}" type="fixed"><parent link="base"/><child link="{name}"/></joint>\n'
        "</robot>\n"
    )
    driver.get(f"{base_url}/")
    driver.find_element(By.XPATH, "//input[@name='mode'][@value='paste']/parent::label").click()
    driver.execute_script("document.getElementById('urdf-text').value = arguments[0]", urdf)
    driver.find_element(By.ID, "submit").click()
    WebDriverWait(driver, 60).until(lambda d: d.find_element(By.ID, "results").is_displayed())
    time.sleep(0.5)  # give an injected handler the chance it must not get
    assert driver.execute_script("return window.pwned === undefined")
    assert not driver.find_elements(By.CSS_SELECTOR, "#results img, #results script")
    found = rows(driver)
    assert any(r["code"] == "J011" and HOSTILE in r["message"] for r in found)
    assert driver.find_element(By.ID, "verdict").text == "Passed"  # one info only
    picture = tree(driver)
    assert HOSTILE in {item["name"] for item in picture["links"]}
    assert HOSTILE in {item["name"] for item in picture["joints"]}
    assert picture["scripts"] == 0


# -- the rules pages and the API documentation --------------------------------------------------


def same_origin_only(driver: Any, base_url: str) -> list[str]:
    """Every resource the page loaded (asserted to come from this server)."""
    urls = list(
        driver.execute_script("return performance.getEntriesByType('resource').map((e) => e.name)")
    )
    assert urls and all(url.startswith(base_url) for url in urls), urls
    return urls


def test_the_rules_page_is_a_table_linking_each_explanation(driver: Any, base_url: str) -> None:
    httpx = pytest.importorskip("httpx")
    catalogue = httpx.get(f"{base_url}/v1/rules").json()["rules"]
    driver.get(f"{base_url}/")
    driver.find_element(By.LINK_TEXT, "Rules").click()
    WebDriverWait(driver, 20).until(
        lambda d: len(d.find_elements(By.CSS_SELECTOR, "#rules tbody tr")) == len(catalogue)
    )
    assert driver.current_url == f"{base_url}/rules"
    script = """
      return Array.from(document.querySelectorAll('#rules tbody tr'), (tr) => ({
        code: tr.dataset.code, href: tr.querySelector('td.code a').getAttribute('href'),
        name: tr.querySelector('td.name').textContent,
        severity: tr.querySelector('.sev').textContent,
        summary: tr.querySelector('td.summary').textContent}));
    """
    shown = driver.execute_script(script)
    assert [r["code"] for r in shown] == [r["code"] for r in catalogue]
    j001 = next(r for r in shown if r["code"] == "J001")
    assert j001["href"] == "/rules/J001" and j001["name"] == "missing-limit"
    assert j001["severity"] == "error" and "<limit>" in j001["summary"]  # `code` as text
    same_origin_only(driver, base_url)

    driver.find_element(By.ID, "filter").send_keys("missing-limit")
    visible = driver.find_elements(By.CSS_SELECTOR, "#rules tbody tr:not([hidden])")
    assert [row.get_attribute("data-code") for row in visible] == ["J001"]
    visible[0].find_element(By.CSS_SELECTOR, "td.code a").click()
    WebDriverWait(driver, 20).until(lambda d: d.find_element(By.ID, "rule").is_displayed())
    assert driver.current_url == f"{base_url}/rules/J001"
    assert driver.find_element(By.ID, "rule-heading").text == "J001 missing-limit"
    assert driver.find_element(By.ID, "rule-severity").text == "error"
    doc = driver.find_element(By.ID, "rule-doc")
    headings = [h.text for h in doc.find_elements(By.TAG_NAME, "h2")]
    assert headings[:3] == ["What it does", "Why is this bad?", "How to fix"]
    assert doc.find_elements(By.CSS_SELECTOR, "ul li") and doc.find_elements(
        By.CSS_SELECTOR, "p code"
    )
    assert "<robot" in doc.find_element(By.CSS_SELECTOR, "pre code").text  # examples as text
    assert not doc.find_elements(By.CSS_SELECTOR, "script, img, robot")
    same_origin_only(driver, base_url)


def test_an_unknown_rule_page_says_so(driver: Any, base_url: str) -> None:
    driver.get(f"{base_url}/rules/Z999")
    WebDriverWait(driver, 20).until(lambda d: d.find_element(By.ID, "error").is_displayed())
    assert "unknown rule 'Z999'" in driver.find_element(By.ID, "error").text
    assert not driver.find_element(By.ID, "rule").is_displayed()


def test_the_api_docs_render_offline(driver: Any, base_url: str) -> None:
    driver.get(f"{base_url}/")
    driver.find_element(By.LINK_TEXT, "API").click()
    WebDriverWait(driver, 30).until(
        lambda d: d.find_elements(By.CSS_SELECTOR, "#swagger-ui .opblock-summary-path")
    )
    paths = {
        e.get_attribute("data-path")
        for e in driver.find_elements(By.CSS_SELECTOR, "#swagger-ui .opblock-summary-path")
    }
    assert {"/v1/check", "/v1/rules", "/readyz"} <= paths
    urls = same_origin_only(driver, base_url)
    assert any(url.endswith("/static/swagger-ui/swagger-ui-bundle.js") for url in urls)
    refused = [
        entry["message"]
        for entry in driver.get_log("browser")
        if "Content Security Policy" in entry["message"]
    ]
    assert refused == []


# -- the simulators (the compatibility matrix) ---------------------------------------------------

TWO_ROOTS = """<robot name="r">
  <link name="base"/>
  <link name="arm"/>
  <link name="stray"/>
  <joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint>
</robot>
"""


def matrix_rows(driver: Any) -> list[dict[str, Any]]:
    """The Simulators table as data: one dict per row, in page order."""
    script = """
      return Array.from(document.querySelectorAll('#matrix tr.matrix-row'), (tr) => ({
        target: tr.dataset.target, outcome: tr.dataset.outcome, confirmed: tr.dataset.confirmed,
        selected: tr.dataset.selected,
        note: Array.from(tr.querySelectorAll('th.target .basis'), (s) => s.textContent).join(' '),
        label: tr.querySelector('th.target').firstChild.textContent,
        shown: tr.querySelector('td.predicted .outcome').textContent,
        colour: getComputedStyle(tr.querySelector('td.predicted .outcome')).color,
        engine: tr.querySelector('td.engine').textContent,
        links: Array.from(tr.querySelectorAll('a.finding-link'), (a) => ({
          text: a.textContent, row: a.dataset.finding, code: a.dataset.code}))}));
    """
    return list(driver.execute_script(script))


def test_the_simulators_table_matches_the_api(driver: Any, base_url: str, tmp_path: Path) -> None:
    httpx = pytest.importorskip("httpx")
    from urdflint.model import targets

    path = tmp_path / "two_roots.urdf"
    path.write_text(TWO_ROOTS)
    driver.get(f"{base_url}/")
    WebDriverWait(driver, 20).until(
        lambda d: d.execute_script("return document.readyState") == "complete"
    )
    assert driver.find_element(By.ID, "want-matrix").is_selected()  # on by default
    assert not driver.find_element(By.ID, "confirm-field").is_displayed()  # not allowed here
    assert check(driver, base_url, path) == "results"
    assert driver.find_element(By.ID, "matrix-card").is_displayed()
    api = httpx.post(
        f"{base_url}/v1/check",
        files={"urdf": ("two_roots.urdf", TWO_ROOTS.encode(), "application/xml")},
        data={"matrix": "true", "target": "all"},
        timeout=120,
    ).json()
    shown = matrix_rows(driver)
    assert [r["target"] for r in shown] == [r["target"] for r in api["matrix"]]
    assert [r["target"] for r in shown] == list(targets.TARGETS)
    for row, expected in zip(shown, api["matrix"], strict=True):
        assert row["outcome"] == expected["predicted"]["outcome"]
        assert row["label"] == expected["label"] and row["confirmed"] == ""
        # the deciding findings by rule: "CODE line N" for one, "CODE ×N" for several
        by_rule: dict[str, list[dict[str, Any]]] = {}
        for found in expected["predicted"]["findings"]:
            by_rule.setdefault(found["code"], []).append(found)
        assert [link["code"] for link in row["links"]] == list(by_rule)
        for link, (code, same) in zip(row["links"], by_rule.items(), strict=True):
            one = len(same) == 1
            assert link["text"] == (
                f"{code} line {same[0]['line']}" if one else f"{code} ×{len(same)}"
            )
            target = driver.find_element(By.ID, link["row"])  # the row, or the rule's group
            assert target.get_attribute("data-code") == code
            if one:
                assert target.get_attribute("data-line") == str(same[0]["line"])
    linked = [link for row in shown for link in row["links"]]
    if linked:  # the rules' effects decide whether any finding is linked
        driver.find_element(By.CSS_SELECTOR, "#matrix a.finding-link").click()
        WebDriverWait(driver, 5).until(
            lambda d: d.find_elements(By.CSS_SELECTOR, "#findings tr.highlight")
        )
        row = driver.find_element(By.CSS_SELECTOR, "#findings tr.highlight")
        # a finding's row, or the header of its rule's group
        assert linked[0]["row"] in (
            row.get_attribute("id"),
            row.find_element(By.XPATH, "..").get_attribute("id"),
        )
        assert row.is_displayed()


# a check answer with every outcome, a confirmation and deciding findings, served by a stub
STUB = {
    "version": 1,
    "summary": {"files": 1, "error": 1, "warning": 1, "info": 0},
    "passed": False,
    "models": {"r.urdf": None},
    "findings": [
        {
            "code": "S004",
            "name": "multiple-roots",
            "severity": "error",
            "path": "r.urdf",
            "line": 4,
            "column": 3,
            "element": "/robot/link[@name='stray']",
            "message": "link 'stray' is a second root",
            "fix": None,
        },
        {
            "code": "E001",
            "name": "engine-refused",
            "severity": "warning",
            "path": "r.urdf",
            "line": 1,
            "column": 1,
            "element": "/robot",
            "message": "Pinocchio refused the model: two root links",
            "fix": None,
        },
    ],
    "matrix": [
        {
            "path": "r.urdf",
            "target": "mujoco",
            "label": "MuJoCo",
            "basis": "engine",
            "predicted": {"outcome": "loads", "findings": []},
            "confirmed": None,
        },
        {
            "path": "r.urdf",
            "target": "drake",
            "label": "Drake",
            "basis": "engine",
            "predicted": {
                "outcome": "changes",
                "findings": [
                    {
                        "code": "S004",
                        "path": "r.urdf",
                        "line": 4,
                        "element": "/robot/link[@name='stray']",
                        "consequence": "link dropped",
                        "detail": "drops it",
                    }
                ],
            },
            "confirmed": {"engine": "drake", "outcome": "not-installed", "findings": []},
        },
        {
            "path": "r.urdf",
            "target": "pinocchio",
            "label": "Pinocchio",
            "basis": "engine",
            "predicted": {
                "outcome": "refused",
                "findings": [
                    {
                        "code": "S004",
                        "path": "r.urdf",
                        "line": 4,
                        "element": "/robot/link[@name='stray']",
                        "consequence": "refused",
                        "detail": "Two root links found",
                    }
                ],
            },
            "confirmed": {
                "engine": "pinocchio",
                "outcome": "refused",
                "findings": [
                    {
                        "code": "E001",
                        "path": "r.urdf",
                        "line": 1,
                        "message": "Pinocchio refused the model: two root links",
                    }
                ],
            },
        },
        {
            "path": "r.urdf",
            "target": "ros",
            "label": "ROS (KDL, MoveIt)",
            "basis": "source and documentation",
            "predicted": {
                "outcome": "crashes",
                "findings": [
                    {
                        "code": "S004",
                        "path": "r.urdf",
                        "line": 4,
                        "element": "/robot/link[@name='stray']",
                        "consequence": "crash",
                        "detail": "<img src=x onerror=window.pwned=1>",
                    }
                ],
            },
            "confirmed": None,
        },
    ],
}
STUB_FETCH = """
  const answer = arguments[0];
  const real = window.fetch;
  window.sent = null;
  window.fetch = (url, options) => {
    if (!String(url).includes('/v1/check')) return real(url, options);
    window.sent = Array.from(options.body.entries(),
      ([k, v]) => [k, typeof v === 'string' ? v : 'file']);
    return Promise.resolve(new Response(JSON.stringify(answer),
      {status: 200, headers: {'Content-Type': 'application/json'}}));
  };
"""


def test_simulators_outcomes_engines_and_links(driver: Any, base_url: str) -> None:
    driver.get(f"{base_url}/")
    WebDriverWait(driver, 20).until(
        lambda d: d.execute_script("return document.readyState") == "complete"
    )
    driver.execute_script(STUB_FETCH, STUB)
    driver.find_element(By.XPATH, "//input[@name='mode'][@value='paste']/parent::label").click()
    driver.find_element(By.ID, "urdf-text").send_keys(TWO_ROOTS)
    driver.find_element(By.ID, "submit").click()
    WebDriverWait(driver, 30).until(lambda d: d.find_element(By.ID, "matrix-card").is_displayed())
    sent = dict(driver.execute_script("return window.sent"))
    # no target: the server infers them, as the CLI does (one verdict everywhere)
    assert sent["matrix"] == "true" and "target" not in sent and "confirm" not in sent

    shown = {row["target"]: row for row in matrix_rows(driver)}
    assert [shown[t]["outcome"] for t in ("mujoco", "drake", "pinocchio", "ros")] == [
        "loads", "changes", "refused", "crashes"]  # fmt: skip
    assert shown["drake"]["shown"] == "loads with changes"
    colours = {t: shown[t]["colour"] for t in shown}
    assert len({colours["mujoco"], colours["drake"], colours["pinocchio"]}) == 3
    assert colours["pinocchio"] == colours["ros"]  # refused and crashes: both red
    assert shown["mujoco"]["engine"] == "—"
    assert "pinocchio" in shown["pinocchio"]["engine"] and "refused" in shown["pinocchio"]["engine"]
    assert "not installed" in shown["drake"]["engine"]
    assert driver.execute_script("return window.pwned === undefined")  # details stay text

    e001 = next(link for link in shown["pinocchio"]["links"] if link["code"] == "E001")
    s004 = shown["ros"]["links"][0]
    assert s004["text"] == "S004 line 4"
    for link in (s004, e001):
        driver.find_element(By.CSS_SELECTOR, f"#matrix a[data-finding='{link['row']}']").click()
        WebDriverWait(driver, 5).until(
            lambda d, row=link["row"]: (
                "highlight" in d.find_element(By.ID, row).get_attribute("class")
            )
        )
        assert len(driver.find_elements(By.CSS_SELECTOR, "#findings tr.highlight")) == 1
        row = driver.find_element(By.ID, link["row"])
        assert row.get_attribute("data-code") == link["code"]
        assert driver.execute_script("return document.activeElement === arguments[0]", row)
        WebDriverWait(driver, 5).until(
            lambda d, row=row: d.execute_script(
                "const r = arguments[0].getBoundingClientRect();"
                "return r.top >= 0 && r.bottom <= window.innerHeight",
                row,
            )
        )

    # at phone width the page does not overflow: the table scrolls inside its own box
    driver.set_window_size(390, 900)
    try:
        time.sleep(0.3)
        widths = driver.execute_script(
            "const box = document.querySelector('#matrix-card .table-wrap');"
            "return [document.documentElement.scrollWidth, document.documentElement.clientWidth,"
            " box.scrollWidth, box.clientWidth, getComputedStyle(box).overflowX]"
        )
        page, room, table, boxed, overflow = widths
        assert page <= room and overflow == "auto" and table > boxed
    finally:
        driver.set_window_size(1400, 1000)


# -- the findings by rule: counts, "Show N more", filters -------------------------------------


def _finding(
    code: str, name: str, severity: str, line: int, link: str, message: str, fix: str
) -> dict[str, Any]:
    return {
        "code": code, "name": name, "severity": severity, "path": "r.urdf", "line": line,
        "column": 3, "element": f"/robot/link[@name='{link}']", "message": message, "fix": fix,
    }  # fmt: skip


MESH = "package://a_rather_long_package_name/meshes/with/many/folders/deep/down/{}.stl"
GROUPED_FINDINGS = [
    *(
        _finding("C009", "unsupported-mesh-format", "error", 10 + i, f"part{i}",
                 f"Drake cannot load STL collision mesh '{MESH.format(f'm{i}')}' of link 'part{i}'",
                 "Convert the mesh to OBJ.")
        for i in range(7)
    ),
    _finding("G005", "deprecated-gazebo-element", "warning", 40, "part0",
             "<stopKd> of joint 'j0' is no longer read by sdformat", "Use <stopErp>."),
    *(
        _finding("J003", "safety-controller-ignored", "info", 50 + i, f"part{i}",
                 f"joint 'j{i}' has a <safety_controller>", f"Narrow the limits of j{i}.")
        for i in range(2)
    ),
]  # fmt: skip


def _scene_link(name: str, findings: list[int]) -> dict[str, Any]:
    return {
        "name": name, "at": [0, 0, 0, 0, 0, 0, 1], "severity": "error" if findings else None,
        "inertia_severity": None, "findings": findings, "visual": [], "collision": [],
        "inertial": None, "parent": None,
    }  # fmt: skip


def _grouped_answer() -> dict[str, Any]:
    findings = GROUPED_FINDINGS
    links = [
        _scene_link(
            f"part{i}",
            [n for n, f in enumerate(findings) if f["element"] == f"/robot/link[@name='part{i}']"],
        )
        for i in range(8)
    ]
    deciding = [
        {"code": f["code"], "path": "r.urdf", "line": f["line"], "element": f["element"],
         "consequence": "refused", "detail": "MakeConvexHull only applies to .obj"}
        for f in findings if f["code"] == "C009"
    ]  # fmt: skip
    return {
        "version": 1,
        "summary": {"files": 1, "error": 7, "warning": 1, "info": 2},
        "passed": False,
        "models": {"r.urdf": None},
        "findings": findings,
        "scene": {"r.urdf": {"version": 1, "robot": "r", "q": {}, "links": links, "joints": [],
                             "meshes": [], "notes": []}},
        "matrix": [
            {"path": "r.urdf", "target": "drake", "label": "Drake", "basis": "engine",
             "predicted": {"outcome": "refused", "findings": deciding}, "confirmed": None},
            {"path": "r.urdf", "target": "mujoco", "label": "MuJoCo", "basis": "engine",
             "predicted": {"outcome": "loads", "findings": deciding[:1]}, "confirmed": None},
        ],
    }  # fmt: skip


def _filter(driver: Any, name: str, value: str) -> None:
    box = driver.find_element(By.ID, f"filter-{name}")
    if box.tag_name == "select":
        driver.execute_script(
            "arguments[0].value = arguments[1]; arguments[0].dispatchEvent(new Event('change'))",
            box,
            value,
        )
    else:
        box.clear()
        if value:
            box.send_keys(value)


def test_findings_are_grouped_by_rule_folded_and_filtered(driver: Any, base_url: str) -> None:
    driver.get(f"{base_url}/")
    WebDriverWait(driver, 20).until(
        lambda d: d.execute_script("return document.readyState") == "complete"
    )
    driver.execute_script(STUB_FETCH, _grouped_answer())
    driver.find_element(By.XPATH, "//input[@name='mode'][@value='paste']/parent::label").click()
    driver.find_element(By.ID, "urdf-text").send_keys(TWO_ROOTS)
    driver.find_element(By.ID, "submit").click()
    WebDriverWait(driver, 30).until(lambda d: d.find_element(By.ID, "results").is_displayed())

    # one group per rule, errors first, each with its count; three rows, then "Show 4 more"
    groups = {g["code"]: g for g in rules(driver)}
    assert [g["code"] for g in rules(driver)] == ["C009", "G005", "J003"]
    assert groups["C009"]["count"] == "×7" and groups["C009"]["visible"] == 3
    assert groups["C009"]["more"] == "Show 4 more" and groups["C009"]["moreExpanded"] == "false"
    assert groups["J003"]["count"] == "×2" and groups["J003"]["visible"] == 2
    assert groups["J003"]["more"] is None
    found = rows(driver)
    assert len(found) == 10 and sum(r["shown"] for r in found) == 6
    c009 = [r for r in found if r["code"] == "C009"]
    assert all(r["fix"] == "Convert the mesh to OBJ." for r in c009)  # said once, in the header
    assert (
        driver.execute_script(
            "return document.querySelectorAll('#findings tr.finding .fix').length"
        )
        == 3
    )  # their own: J003 has two different ones, G005 is one finding
    assert c009[0]["href"] == "/rules/C009" and c009[0]["name"] == "unsupported-mesh-format"
    count = driver.find_element(By.ID, "findings-count").text
    assert "10 findings in 3 rules" in count and "6 shown" in count

    more = driver.find_element(By.CSS_SELECTOR, "#rule-error-C009 button.more")
    more.click()
    assert {g["code"]: g for g in rules(driver)}["C009"]["visible"] == 7
    assert more.get_attribute("aria-expanded") == "true" and more.text == "Show fewer"
    more.click()
    assert {g["code"]: g for g in rules(driver)}["C009"]["visible"] == 3
    fold = driver.find_element(By.CSS_SELECTOR, "#rule-error-C009 button.rule-toggle")
    fold.click()
    after = {g["code"]: g for g in rules(driver)}["C009"]
    assert after["expanded"] == "false" and after["visible"] == 0 and after["more"] is None
    fold.click()
    driver.find_element(By.ID, "findings-expand").click()  # "Show all"
    assert all(g["visible"] == g["rows"] for g in rules(driver))
    driver.find_element(By.ID, "findings-expand").click()

    # every filter has a label
    for name in ("severity", "rule", "link", "text"):
        label = driver.find_element(By.CSS_SELECTOR, f"label[for='filter-{name}']")
        assert label.text
    # by severity, by rule (the only rule left shows whole), by link, by text
    _filter(driver, "severity", "info")
    assert [g["code"] for g in rules(driver) if g["shown"]] == ["J003"]
    assert "2 of 10 findings match" in driver.find_element(By.ID, "findings-count").text
    _filter(driver, "severity", "")
    _filter(driver, "rule", "C009")
    shown = [g for g in rules(driver) if g["shown"]]
    assert [g["code"] for g in shown] == ["C009"] and shown[0]["visible"] == 7
    _filter(driver, "rule", "")
    _filter(driver, "link", "part1")
    assert sorted(r["code"] for r in rows(driver) if r["shown"]) == ["C009", "J003"]
    _filter(driver, "link", "")
    _filter(driver, "text", "M6.STL")
    assert [(r["code"], r["line"]) for r in rows(driver) if r["shown"]] == [("C009", "16")]
    assert {g["code"]: g["count"] for g in rules(driver) if g["shown"]} == {"C009": "×1 of 7"}
    _filter(driver, "text", "nothing like this")
    assert driver.find_element(By.ID, "no-match").is_displayed()
    driver.find_element(By.ID, "filter-clear").click()
    assert sum(r["shown"] for r in rows(driver)) == 6
    assert not driver.find_element(By.ID, "filter-clear").is_displayed()

    # the simulators group their deciding findings by rule; a group links to its rule
    drake = {r["target"]: r for r in matrix_rows(driver)}["drake"]
    assert [link["text"] for link in drake["links"]] == ["C009 ×7"]
    assert drake["links"][0]["row"] == "rule-error-C009"
    mujoco = {r["target"]: r for r in matrix_rows(driver)}["mujoco"]
    assert [link["text"] for link in mujoco["links"]] == ["C009 line 10"]
    _filter(driver, "severity", "info")  # hides C009: following the link clears the filters
    driver.find_element(By.CSS_SELECTOR, "#matrix a[data-finding='rule-error-C009']").click()
    WebDriverWait(driver, 5).until(
        lambda d: d.find_elements(By.CSS_SELECTOR, "#rule-error-C009 tr.rule-row.highlight")
    )
    assert driver.find_element(By.ID, "filter-severity").get_attribute("value") == ""
    assert driver.find_element(By.CSS_SELECTOR, "#rule-error-C009 tr.rule-row").is_displayed()

    # a finding past the first rows, reached from the selected link's box, is shown
    driver.execute_script(
        "document.dispatchEvent(new CustomEvent('urdflint:select',"
        " {detail: {link: 'part5', from: 'outline'}}))"
    )
    link = driver.find_element(By.CSS_SELECTOR, "#picked a.finding-link")
    target = link.get_attribute("data-finding")
    assert not driver.find_element(By.ID, target).is_displayed()
    link.click()
    WebDriverWait(driver, 5).until(lambda d: d.find_element(By.ID, target).is_displayed())
    assert "highlight" in driver.find_element(By.ID, target).get_attribute("class")


@pytest.mark.skipif(importlib.util.find_spec("pinocchio") is None, reason="needs pinocchio")
def test_confirm_in_the_installed_engines(driver: Any, tmp_path: Path) -> None:
    """A server started with confirm allowed offers the box; the engine's verdict is shown."""
    from tests.server.conftest import running_server

    path = tmp_path / "two_roots.urdf"
    path.write_text(TWO_ROOTS)
    env = {"URDFLINT_ALLOW_CONFIRM": "1", "URDFLINT_JOBS": "1"}
    with running_server(env, log=tmp_path / "serve.log") as base:
        driver.get(f"{base}/")
        WebDriverWait(driver, 20).until(
            lambda d: d.find_element(By.ID, "confirm-field").is_displayed()
        )
        driver.execute_script(
            "arguments[0].value = 'pinocchio'", driver.find_element(By.ID, "target")
        )
        driver.execute_script(
            "document.getElementById('target').dispatchEvent(new Event('change'))"
        )
        assert "pinocchio" in driver.find_element(By.ID, "confirm-engines").text
        driver.find_element(By.ID, "want-confirm").click()
        driver.find_element(By.ID, "urdf-file").send_keys(str(path))
        driver.find_element(By.ID, "submit").click()
        WebDriverWait(driver, 120).until(
            lambda d: d.find_element(By.ID, "matrix-card").is_displayed()
        )
        # every target has a row (the matrix is a display); the one checked is marked
        shown = {row["target"]: row for row in matrix_rows(driver)}
        assert [t for t, row in shown.items() if row["selected"] == "true"] == ["pinocchio"]
        assert shown["pinocchio"]["confirmed"] in {"loads", "changes", "refused", "crashes"}
        assert shown["pinocchio"]["engine"].startswith("pinocchio")
        assert "not checked" in shown["mujoco"]["note"]
        codes = {r["code"] for r in rows(driver)}
        assert "E001" in codes  # what Pinocchio said, in the findings


# -- Fix: the diff and the download ---------------------------------------------------------------

# a non-unit axis (safe fix) and inverted limits (unsafe fix), with markup in a comment that
# the diff shows as context: it must stay text
FIXABLE = f"""<?xml version="1.0"?>
<robot name="arm">
  <link name="base_link"/>
  <joint name="shoulder" type="revolute">
    <!-- {HOSTILE.replace("--", "")} -->
    <parent link="base_link"/>
    <child link="upper_arm"/>
    <axis xyz="0 0 2"/>
    <limit lower="1.57" upper="-1.57" effort="30" velocity="2"/>
  </joint>
  <link name="upper_arm">
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial>
  </link>
</robot>
"""


def press_fix(driver: Any, unsafe: bool = False) -> None:
    box = driver.find_element(By.ID, "want-unsafe")
    if box.is_selected() != unsafe:
        box.click()
    driver.find_element(By.ID, "fix").click()
    WebDriverWait(driver, 90).until(
        lambda d: (
            d.find_element(By.ID, "fix-card").is_displayed()
            or d.find_element(By.ID, "error").is_displayed()
        )
    )
    assert driver.find_element(By.ID, "fix-card").is_displayed(), driver.find_element(
        By.ID, "error"
    ).text


def diff_lines(driver: Any) -> list[tuple[str, str]]:
    script = """
      return Array.from(document.querySelectorAll('#diff span.line'),
        (s) => [s.dataset.kind, s.textContent]);
    """
    return [(kind, text) for kind, text in driver.execute_script(script)]


def test_fix_shows_the_diff_and_downloads_the_fixed_file(
    driver: Any, base_url: str, tmp_path: Path
) -> None:
    httpx = pytest.importorskip("httpx")
    path = tmp_path / "my_arm.urdf"
    path.write_text(FIXABLE)
    downloads = tmp_path / "downloads"
    downloads.mkdir()
    driver.execute_cdp_cmd(
        "Browser.setDownloadBehavior", {"behavior": "allow", "downloadPath": str(downloads)}
    )
    driver.get_log("browser")  # start with an empty console

    # Check first: the findings with a fix say so; no fix card
    assert check(driver, base_url, path) == "results"
    badges = {
        r["code"]: r
        for r in driver.execute_script("""
      return Array.from(document.querySelectorAll('#findings tr.finding'), (tr) => {
        const badge = tr.querySelector('.badge.fixable');
        return {code: tr.dataset.code, badge: badge && badge.textContent,
                kind: badge && badge.dataset.applicability};
      });""")
    }
    assert badges["J008"]["badge"] == "fixable" and badges["J008"]["kind"] == "safe"
    assert badges["J009"]["badge"] == "fixable, unsafe"
    assert not driver.find_element(By.ID, "fix-card").is_displayed()

    # Fix: the safe fix; the diff is coloured by line, the unsafe one waits
    press_fix(driver)
    lines = diff_lines(driver)
    assert ("file", "--- my_arm.urdf") in lines and lines[2][0] == "hunk"
    assert [(k, t) for k, t in lines if k in ("add", "del")] == [
        ("del", '-    <axis xyz="0 0 2"/>'),
        ("add", '+    <axis xyz="0 0 1"/>'),
    ]
    colours = driver.execute_script("""
      const of = (kind) =>
        getComputedStyle(document.querySelector(`#diff .${kind}`)).backgroundColor;
      return [of('add'), of('del'), of('context')];""")
    assert len(set(colours)) == 3
    summary = driver.find_element(By.ID, "fix-summary").text
    assert "Applied 1 fix" in summary and "1 more with" in summary
    assert {r["code"] for r in rows(driver)} >= {"J009"} and "J008" not in {
        r["code"] for r in rows(driver)
    }
    assert driver.execute_script("return window.pwned === undefined")
    assert not driver.find_elements(By.CSS_SELECTOR, "#diff img, #diff script, #diff *:not(span)")
    assert any(HOSTILE.replace("--", "") in text for _, text in lines)  # shown as text

    # with the unsafe fixes, the limits too; the download is the fixed file, by its name
    press_fix(driver, unsafe=True)
    WebDriverWait(driver, 30).until(lambda d: sum(kind == "add" for kind, _ in diff_lines(d)) == 2)
    link = driver.find_element(By.ID, "download")
    assert link.is_displayed() and link.text == "Download fixed file"
    assert link.get_attribute("download") == "my_arm.urdf"
    assert link.get_attribute("href").startswith(f"blob:{base_url}/")
    link.click()
    target = downloads / "my_arm.urdf"
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline and not target.is_file():
        time.sleep(0.1)
    assert target.is_file(), sorted(p.name for p in downloads.iterdir())
    with path.open("rb") as handle:
        api = httpx.post(
            f"{base_url}/v1/fix",
            files={"urdf": ("my_arm.urdf", handle, "application/xml")},
            data={"unsafe_fixes": "true"},
            timeout=120,
        ).json()
    assert target.read_text() == api["fixed"]
    assert 'lower="-1.57" upper="1.57"' in api["fixed"]
    assert not [
        entry["message"]
        for entry in driver.get_log("browser")
        if "Content Security Policy" in entry["message"] or "Refused" in entry["message"]
    ]

    screenshot(driver, tmp_path / "fixed.png")

    # Check again: the fix card goes away (its Blob URL is revoked)
    driver.find_element(By.ID, "submit").click()
    WebDriverWait(driver, 60).until(lambda d: not d.find_element(By.ID, "fix-card").is_displayed())


def test_fix_with_nothing_to_fix_offers_no_download(driver: Any, base_url: str) -> None:
    driver.get(f"{base_url}/")
    driver.find_element(By.XPATH, "//input[@name='mode'][@value='paste']/parent::label").click()
    driver.execute_script(
        "document.getElementById('urdf-text').value = arguments[0]",
        '<robot name="r">\n  <link name="a"/>\n</robot>\n',
    )
    press_fix(driver)
    assert "No automatic fix" in driver.find_element(By.ID, "fix-summary").text
    assert not driver.find_element(By.ID, "download").is_displayed()
    assert diff_lines(driver) == []
