"""Shared by the browser tests: Chromium through Selenium, the page's form and its results.

Needs Selenium 4 and Debian's ``chromium`` and ``chromium-driver``; :data:`CHROMIUM` or
:data:`CHROMEDRIVER` is ``None`` when either is missing (the test modules skip then). The
driver is given explicitly, so Selenium Manager never runs and nothing is downloaded; the
browser starts with a fresh profile and its background networking off. WebGL is
SwiftShader's (software), which Chromium offers headless; ``--enable-unsafe-swiftshader``
opts in where a Chromium asks for it.
"""

from __future__ import annotations

import shutil
import struct
import time
import zipfile
from pathlib import Path
from typing import Any

import pytest

webdriver = pytest.importorskip("selenium.webdriver")

from selenium.common.exceptions import TimeoutException  # noqa: E402
from selenium.webdriver.chrome.service import Service  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402
from selenium.webdriver.support.ui import WebDriverWait  # noqa: E402


def _find(names: tuple[str, ...], default: str) -> str | None:
    if Path(default).is_file():
        return default
    found = (shutil.which(name) for name in names)
    return next((path for path in found if path), None)


CHROMIUM = _find(("chromium", "chromium-browser"), "/usr/bin/chromium")
CHROMEDRIVER = _find(("chromedriver",), "/usr/bin/chromedriver")
FLAGS = (
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-dev-shm-usage",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-extensions",
    "--disable-default-apps",
    "--no-first-run",
    "--no-default-browser-check",
    "--window-size=1400,1000",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
)


def new_driver(profile: Path) -> Any:
    """A headless Chromium with :data:`FLAGS`, a fresh profile, its console log kept."""
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in FLAGS:
        options.add_argument(flag)
    options.add_argument(f"--user-data-dir={profile}")
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})  # CSP reports, for one
    browser = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    browser.set_page_load_timeout(60)
    return browser


def mesh_zip(robot: Path, target: Path) -> Path:
    """A corpus robot's ``meshes`` folder as the zip the page uploads (its folders are the
    packages), written to ``target``."""
    meshes = robot / "meshes"
    with zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as zf:
        for path in sorted(meshes.rglob("*")):
            if path.is_file():
                zf.write(path, path.relative_to(meshes).as_posix())
    return target


def check(
    driver: Any, base_url: str, path: Path | None = None, meshes: Path | None = None, **fields: str
) -> str:
    """Open the page, fill it in (``meshes``: the zip), press Check; ``"results"`` or
    ``"error"`` when shown."""
    driver.get(f"{base_url}/")
    ready = "return document.readyState"
    WebDriverWait(driver, 20).until(lambda d: d.execute_script(ready) == "complete")
    driver.execute_script("document.querySelector('details.more').open = true")
    if path is not None:
        driver.find_element(By.ID, "urdf-file").send_keys(str(path))
    if meshes is not None:
        driver.find_element(By.ID, "meshes-file").send_keys(str(meshes))
    for name, value in fields.items():
        element = driver.find_element(By.ID, name)
        if element.tag_name == "select":
            driver.execute_script("arguments[0].value = arguments[1]", element, value)
        else:
            element.send_keys(value)
    driver.find_element(By.ID, "submit").click()

    def shown(d: Any) -> str | bool:
        for box in ("results", "error"):
            if d.find_element(By.ID, box).is_displayed():
                return box
        return False

    try:
        return str(WebDriverWait(driver, 90).until(shown))
    except TimeoutException:  # pragma: no cover - a diagnosis for a failing run
        pytest.fail(f"no result shown; page status: {driver.find_element(By.ID, 'status').text}")


def rows(driver: Any) -> list[dict[str, Any]]:
    """The findings table as data: one dict per finding row, in page order, shown or not
    (``shown``: not folded away nor filtered out). Rows are grouped by rule: the rule's page,
    name and (when every finding of the rule shares it) fix are in its group's header."""
    script = """
      return Array.from(document.querySelectorAll('#findings tr.finding'), (tr) => {
        const head = tr.parentElement.querySelector('tr.rule-row');
        return {line: tr.dataset.line, code: tr.dataset.code, severity: tr.dataset.severity,
          element: tr.dataset.element, group: tr.parentElement.dataset.severity,
          link: tr.dataset.link || null, rule: tr.parentElement.dataset.code,
          href: head.querySelector('a.rule-link').getAttribute('href'),
          name: head.querySelector('.rule-name').textContent,
          message: tr.querySelector('.message').textContent,
          fix: (tr.querySelector('.fix') || head.querySelector('.fix') || {}).textContent || null,
          shownLine: tr.querySelector('td.num').textContent,
          shownElement: tr.querySelector('.element').textContent,
          shown: !tr.hidden && !tr.parentElement.hidden};
      });
    """
    return list(driver.execute_script(script))


def rules(driver: Any) -> list[dict[str, Any]]:
    """The findings table's rule groups, in page order: code, severity, the header's count
    text, whether the group shows, how many of its rows show, and its "Show N more" text
    (``None`` when hidden)."""
    script = """
      return Array.from(document.querySelectorAll('#findings tbody.rule'), (body) => {
        const more = body.querySelector('tr.more-row');
        const fold = body.querySelector('button.rule-toggle');
        const found = Array.from(body.querySelectorAll('tr.finding'));
        return {code: body.dataset.code, severity: body.dataset.severity, id: body.id,
          count: body.querySelector('.rule-count').textContent, shown: !body.hidden,
          expanded: fold.getAttribute('aria-expanded'), rows: found.length,
          visible: found.filter((tr) => !tr.hidden).length,
          more: more.hidden ? null : more.querySelector('button').textContent,
          moreExpanded: more.querySelector('button').getAttribute('aria-expanded')};
      });
    """
    return list(driver.execute_script(script))


def tree(driver: Any) -> dict[str, Any]:
    script = """
      const svg = document.querySelector('#tree svg');
      if (!svg) return null;
      const pick = (sel, key) => Array.from(svg.querySelectorAll(sel), (g) => ({
        name: g.getAttribute(key), severity: g.getAttribute('data-severity'),
        codes: g.getAttribute('data-codes'), extra: g.getAttribute('data-extra'),
        kind: g.getAttribute('data-kind')}));
      return {links: pick('g.link', 'data-link'), joints: pick('g.joint', 'data-joint'),
              width: svg.getBoundingClientRect().width,
              scripts: svg.querySelectorAll('script, foreignObject').length};
    """
    found = driver.execute_script(script)
    assert found is not None, "no SVG in #tree"
    return dict(found)


def screenshot(driver: Any, target: Path) -> Path:
    """The whole page as a PNG (the window grown to the page's height); checked non-trivial."""
    driver.execute_script("window.scrollTo(0, 0)")
    height = int(driver.execute_script("return document.documentElement.scrollHeight"))
    driver.set_window_size(1400, min(max(height, 800), 6000))
    time.sleep(0.3)
    assert driver.save_screenshot(str(target))
    data = target.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    width, tall = struct.unpack(">II", data[16:24])
    assert width >= 1000 and tall >= 800 and len(data) > 30_000
    driver.set_window_size(1400, 1000)
    return target
