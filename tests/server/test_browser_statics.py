"""The statics panel and the support polygon in a real headless Chromium.

The page asks for ``statics=true`` with every check: the panel lists each actuated joint,
the weakest first, with a bar of the gravity torque it needs against its effort limit (red
when it cannot hold it: D001; amber under a 1.5x margin; green when it holds; grey when
the bound proves it, or it is passive or unloaded), the numbers and the verdict in words;
a click on a joint selects the link it moves everywhere. For a mobile base the 3D view
draws, when "support polygon" is ticked, the support polygon on the ground and the whole
robot's centre of mass over it, coloured by the stability margin; a fixed arm has none
(the box is disabled). Pictures are judged as in ``test_browser_scene.py``, by pixel
colours around points the page projects (``window.urdflintView.support()``). Screenshots
(1400 and 390 px) go to the test's folder, and to ``$URDFLINT_SCREENSHOTS`` when set.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import CORPUS, FIXTURES

pytest.importorskip("selenium.webdriver")
pytest.importorskip("fastapi")
pytest.importorskip("uvicorn")
pytest.importorskip("pinocchio")
np = pytest.importorskip("numpy")
pytest.importorskip("PIL.Image")

from selenium.webdriver.common.by import By  # noqa: E402
from selenium.webdriver.support.ui import WebDriverWait  # noqa: E402

from tests.server.browsing import CHROMEDRIVER, CHROMIUM, mesh_zip  # noqa: E402
from tests.server.test_browser_scene import (  # noqa: E402
    around,
    drawn,
    keep,
    picture,
    refused,
    selected,
)

pytestmark = [
    pytest.mark.slow,  # a real browser
    pytest.mark.skipif(
        CHROMIUM is None or CHROMEDRIVER is None,
        reason="needs chromium and chromedriver (Debian: apt-get install chromium chromium-driver)",
    ),
]

ARM = FIXTURES / "rules" / "D001" / "bad.urdf"  # a fixed arm whose shoulder cannot hold it
FALLS = FIXTURES / "rules" / "D003" / "bad.urdf"  # a base whose centre of mass is outside
TIAGO = CORPUS / "tiago"
GREEN, RED = (7, 148, 85), (217, 45, 32)  # the page's pass and error colours


def joints(driver: Any) -> list[dict[str, Any]]:
    """The statics panel's rows, in page order: the joint, its status and link, whether it
    shows, its text, the bar's fill colour and the fill's and the limit tick's extent."""
    script = """
      return Array.from(document.querySelectorAll('#statics-joints li.joint'), (li) => {
        const fill = li.querySelector('.bar .fill');
        const bar = li.querySelector('.bar').getBoundingClientRect();
        const tick = li.querySelector('.bar .limit');
        const f = fill.getBoundingClientRect();
        const detail = li.querySelector('.joint-detail');
        return {joint: li.dataset.joint, status: li.dataset.status, link: li.dataset.link || null,
          weakest: li.dataset.weakest === 'true', shown: !li.hidden,
          margin: li.dataset.margin ? Number(li.dataset.margin) : null,
          text: li.querySelector('.numbers').textContent,
          word: li.querySelector('.status').textContent,
          colour: getComputedStyle(fill).backgroundColor,
          fill: bar.width ? f.width / bar.width : 0,
          tick: tick ? (tick.getBoundingClientRect().left - bar.left) / bar.width : null,
          right: li.getBoundingClientRect().right,
          detail: detail.hidden ? '' : detail.textContent};
      });"""
    return list(driver.execute_script(script))


def rgb(text: str) -> tuple[int, ...]:
    return tuple(int(v) for v in text[text.index("(") + 1 : text.index(")")].split(",")[:3])


def support_box(driver: Any) -> Any:
    return driver.find_element(By.CSS_SELECTOR, "[data-show='support']")


def tick_support(driver: Any, on: bool, force: bool = False) -> None:
    """Tick or untick "support polygon" (``force``: even a disabled box, as a script could)."""
    box = support_box(driver)
    if force or box.is_selected() != on:
        driver.execute_script(
            "arguments[0].checked = arguments[1];arguments[0].dispatchEvent(new Event('change'))",
            box,
            on,
        )
    time.sleep(0.3)


def support_at(driver: Any, rect: dict[str, float]) -> dict[str, Any] | None:
    found = driver.execute_script("return window.urdflintView.support()")
    if found is None:
        return None
    shift = lambda p: (int(p["x"] - rect["x"]), int(p["y"] - rect["y"]))  # noqa: E731
    return {"com": shift(found["com"]), "corners": [shift(c) for c in found["corners"]]}


def near(pixels: Any, colour: tuple[int, int, int], tolerance: int = 60) -> Any:
    return np.abs(pixels - colour).sum(axis=2) < tolerance


def reddish(pixels: Any) -> Any:
    """The error's red, solid or as the polygon's light fill over grey or the background."""
    r, g, b = pixels[..., 0], pixels[..., 1], pixels[..., 2]
    return (r - g > 30) & (r - b > 30) & (np.abs(g - b) < 40)


def greenish(pixels: Any) -> Any:
    """The pass's green, solid or as a light fill."""
    r, g, b = pixels[..., 0], pixels[..., 1], pixels[..., 2]
    return (g - r > 25) & (g - b > 8)


def no_sideways_scroll(driver: Any) -> dict[str, Any]:
    found = driver.execute_script("""
      const page = document.documentElement;
      const card = document.getElementById('statics-card').getBoundingClientRect();
      return {page: page.scrollWidth, room: page.clientWidth, card: card.right};""")
    assert found["page"] <= found["room"] and found["card"] <= found["room"], found
    return dict(found)


def at_phone_width(driver: Any, name: str, folder: Path) -> None:
    """At 390 px: nothing scrolls sideways, every row fits; a screenshot of the panel."""
    driver.set_window_size(390, 900)
    try:
        time.sleep(0.5)
        no_sideways_scroll(driver)
        room = driver.execute_script("return document.documentElement.clientWidth")
        assert all(r["right"] <= room for r in joints(driver) if r["shown"])
        card = driver.find_element(By.ID, "statics-card")
        driver.execute_script("arguments[0].scrollIntoView({block: 'start'})", card)
        time.sleep(0.3)
        keep(driver.get_screenshot_as_png(), f"{name}_390", folder)
    finally:
        driver.set_window_size(1400, 1000)


def test_a_joint_that_cannot_hold_its_arm_has_a_red_bar(
    driver: Any, base_url: str, tmp_path: Path
) -> None:
    driver.get_log("browser")
    assert drawn(driver, base_url, ARM)["state"] == "ready"
    card = driver.find_element(By.ID, "statics-card")
    assert card.is_displayed()
    rows = joints(driver)
    assert [r["joint"] for r in rows] == ["shoulder", "elbow"]  # the weakest first
    shoulder, elbow = rows
    assert (
        shoulder["status"] == "fails" and shoulder["weakest"] and shoulder["word"] == "cannot hold"
    )
    assert "11.8 of 10 N·m" in shoulder["text"] and "margin 0.849" in shoulder["text"]
    assert rgb(shoulder["colour"]) == RED
    assert shoulder["fill"] > 0.99 and 0.8 < shoulder["tick"] < 0.9  # needs more than its limit
    assert elbow["status"] == "proven" and rgb(elbow["colour"]) == (152, 162, 179)  # grey
    assert 0.35 < elbow["fill"] < 0.45 and elbow["tick"] > 0.99
    assert "2 actuated joints · 1 cannot hold" in card.text
    keep(card.screenshot_as_png, "d001_statics_1400", tmp_path)

    # a joint selects the link it moves, everywhere; its row opens its details
    card.find_element(By.CSS_SELECTOR, "li[data-joint='shoulder'] button.joint-name").click()
    WebDriverWait(driver, 5).until(lambda d: selected(d)["view"] == "upper_arm")
    assert selected(driver)["outline"] == "upper_arm"
    [shoulder] = [r for r in joints(driver) if r["joint"] == "shoulder"]
    assert "D001" in shoulder["detail"] and "shoulder=0" in shoulder["detail"]
    # ... and a link selected elsewhere marks its joint
    driver.find_element(By.CSS_SELECTOR, "#outline li[data-link='forearm'] .name").click()
    WebDriverWait(driver, 5).until(lambda d: selected(d)["view"] == "forearm")
    assert [r["joint"] for r in joints(driver) if r["detail"]] == ["elbow"]

    # a fixed arm has no support polygon: the box is disabled, and forced, it draws nothing
    view = driver.find_element(By.ID, "view")
    assert view.get_attribute("data-support") == "none"
    assert not support_box(driver).is_enabled()
    before, _ = picture(driver, "d001_support_off", tmp_path)
    tick_support(driver, True, force=True)
    after, _ = picture(driver, "d001_support_forced", tmp_path)
    tick_support(driver, False, force=True)
    assert driver.execute_script("return window.urdflintView.support()") is None
    assert (np.abs(after - before).sum(axis=2) > 30).mean() < 0.001
    at_phone_width(driver, "d001_statics", tmp_path)
    assert refused(driver) == []


def test_a_base_that_falls_shows_a_red_support_polygon(
    driver: Any, base_url: str, tmp_path: Path
) -> None:
    assert drawn(driver, base_url, FALLS)["state"] == "ready"
    view = driver.find_element(By.ID, "view")
    assert view.get_attribute("data-support") == "falls" and support_box(driver).is_enabled()
    base = driver.find_element(By.ID, "statics-base")
    assert base.get_attribute("data-status") == "falls"
    assert "falls at the zero pose" in base.text and "12 mm outside" in base.text
    tick_support(driver, False)
    before, _ = picture(driver, "d003_support_off", tmp_path)
    base.find_element(By.ID, "statics-support").click()  # "Show it in 3D" ticks the box
    time.sleep(0.5)
    assert support_box(driver).is_selected()
    pixels, rect = picture(driver, "d003_support", tmp_path)
    found = support_at(driver, rect)
    assert found is not None and len(found["corners"]) == 4
    dot = around(pixels, found["com"], 1)
    assert near(dot, RED).mean() > 0.5  # the centre of mass's ground point, in red
    reddened = reddish(pixels) & ~reddish(before)
    print(f"d003: the support polygon turns {reddened.mean():.2%} of the view red")
    assert reddened.mean() > 0.02  # the polygon's fill and edge
    tick_support(driver, False)


@pytest.mark.skipif(not (TIAGO / "model.urdf").is_file(), reason="needs the corpus")
def test_tiago_s_statics_and_support_polygon(
    driver: Any, base_url: str, tmp_path: Path, tmp_path_factory: pytest.TempPathFactory
) -> None:
    """TIAGo with its meshes: arm_2_joint is its weakest joint (margin 1.28: amber); its
    base stands (green), the polygon under the base drawn over it."""
    driver.get_log("browser")
    meshes = mesh_zip(TIAGO, tmp_path_factory.mktemp("zips") / "tiago_meshes.zip")
    state = drawn(driver, base_url, TIAGO / "model.urdf", meshes=meshes)
    assert state["state"] == "ready"
    rows = joints(driver)
    assert len(rows) == 48 and sum(r["shown"] for r in rows) == 3
    first = rows[0]
    assert first["joint"] == "arm_2_joint" and first["weakest"] and first["status"] == "tight"
    assert "30.4 of 39 N·m · margin 1.28" in first["text"] and first["word"] == "tight"
    assert rgb(first["colour"]) == (247, 144, 9)  # amber
    assert [r["status"] for r in rows[1:3]] == ["proven", "proven"]
    margins = [r["margin"] for r in rows if r["margin"] is not None]
    assert len(margins) == 41 and margins == sorted(margins)  # the 7 unloaded at the end
    card = driver.find_element(By.ID, "statics-card")
    assert "48 actuated joints · 1 tight" in card.text and "1.27 kg at hand_palm_link" in card.text
    more = driver.find_element(By.ID, "statics-more")
    assert more.text == "Show all 48 joints (45 more)"
    more.click()
    assert all(r["shown"] for r in joints(driver))
    more.click()
    assert sum(r["shown"] for r in joints(driver)) == 3
    driver.execute_script("arguments[0].scrollIntoView({block: 'start'})", card)
    keep(card.screenshot_as_png, "tiago_statics_1400", tmp_path)

    # the support polygon: off at first; ticked, green over the base, the COM's ground point
    base = driver.find_element(By.ID, "statics-base")
    assert base.get_attribute("data-status") == "stands" and "117 mm inside" in base.text
    view = driver.find_element(By.ID, "view")
    assert view.get_attribute("data-support") == "stands"
    tick_support(driver, False)
    before, _ = picture(driver, "tiago_support_off", tmp_path)
    tick_support(driver, True)
    pixels, rect = picture(driver, "tiago_support", tmp_path)
    found = support_at(driver, rect)
    assert found is not None and len(found["corners"]) == 6
    assert near(around(pixels, found["com"], 1), GREEN).mean() > 0.5
    greened = greenish(pixels) & ~greenish(before)
    print(f"tiago: the support polygon turns {greened.mean():.2%} of the view green")
    assert greened.mean() > 0.005
    cardview = driver.find_element(By.ID, "view-card")
    driver.execute_script("arguments[0].scrollIntoView({block: 'start'})", cardview)
    time.sleep(0.3)
    keep(cardview.screenshot_as_png, "tiago_view_support_1400", tmp_path)

    # arm_2_joint selects arm_2_link in the view and the outline
    driver.execute_script("arguments[0].scrollIntoView({block: 'start'})", card)
    card.find_element(By.CSS_SELECTOR, "li[data-joint='arm_2_joint'] button.joint-name").click()
    WebDriverWait(driver, 5).until(lambda d: selected(d)["view"] == "arm_2_link")
    assert selected(driver)["outline"] == "arm_2_link"
    at_phone_width(driver, "tiago_statics", tmp_path)
    driver.execute_script(
        "document.dispatchEvent(new CustomEvent('urdflint:select',"
        " {detail: {link: null, from: 'scene'}}))"
    )
    driver.set_window_size(390, 900)
    try:  # the polygon at phone width too, the whole robot framed again
        time.sleep(0.6)
        driver.execute_script("document.getElementById('view-reset').click()")
        time.sleep(0.3)
        small, rect = picture(driver, "tiago_support_390", tmp_path)
        found = support_at(driver, rect)
        assert found is not None
        assert near(around(small, found["com"], 1), GREEN).mean() > 0.5
    finally:
        driver.set_window_size(1400, 1000)
    tick_support(driver, False)
    assert refused(driver) == []
    print(f"screenshots: {tmp_path}")
