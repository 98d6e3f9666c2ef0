"""The page in a real browser: Debian's chromium, driven by Selenium through /usr/bin/chromedriver.

Nothing is downloaded: the driver's path is given, so Selenium Manager is not
run. CI installs chromium and chromium-driver (.ci/run); there a missing
browser fails the test instead of skipping it.
"""

from __future__ import annotations

import base64
import json
import os
import time

import pytest

from jdraw import cli
from tests.web_helpers import CHROMEDRIVER, CHROMIUM

if os.environ.get("CI"):
    import selenium  # noqa: F401
    import starlette  # noqa: F401
else:
    pytest.importorskip("selenium")
    pytest.importorskip("starlette")
    pytest.importorskip("uvicorn")
    if not (os.path.exists(CHROMIUM) and os.path.exists(CHROMEDRIVER)):
        pytest.skip("apt-get install chromium chromium-driver", allow_module_level=True)

import httpx  # noqa: E402
from selenium.webdriver.common.action_chains import ActionChains  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402

from jdraw.web.app import Limits, create_app  # noqa: E402
from tests.web_helpers import chromium, live_server  # noqa: E402

# The first plan compiles the bundled model (about 30 s on 2 idle cores, more when shared).
PLAN_WAIT_S = 600


def wait_for(driver, condition, timeout_s: float, what: str):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        value = condition(driver)
        if value:
            return value
        time.sleep(0.1)
    state = driver.find_element(By.TAG_NAME, "body").get_attribute("data-state")
    error = driver.find_element(By.ID, "error").text
    raise AssertionError(f"timed out waiting for {what} (page state {state!r}, error {error!r})")


def state(driver) -> str:
    return driver.find_element(By.TAG_NAME, "body").get_attribute("data-state")


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    downloads = tmp_path_factory.mktemp("downloads")
    # The first plan compiles the model: a time limit a shared CPU cannot trip.
    with live_server(create_app(Limits(plan_timeout_s=3600))) as url:
        driver = chromium(downloads)
        try:
            driver.get(url)
            yield driver, url, downloads
        finally:
            driver.quit()


def test_draw_plan_watch_download(page, tmp_path):
    driver, url, downloads = page
    pad = driver.find_element(By.ID, "pad")
    # A stroke with the mouse: pointerdown, pointermoves, pointerup on the pad.
    moves = ActionChains(driver).move_to_element_with_offset(pad, -110, -90).click_and_hold()
    for dx, dy in [(25, 5)] * 6 + [(0, 25)] * 5 + [(-20, 10)] * 4:
        moves.move_by_offset(dx, dy)
    moves.release().perform()
    png = base64.b64decode(
        driver.execute_script("return arguments[0].toDataURL('image/png')", pad).split(",")[1]
    )
    driver.find_element(By.ID, "plan").click()
    seen = set()

    def finished(d):
        seen.add(state(d))
        return state(d) in ("done", "error") and d.find_element(By.TAG_NAME, "body").get_attribute(
            "data-files"
        )

    wait_for(driver, finished, PLAN_WAIT_S, "the plan and its animation")
    assert state(driver) == "done", driver.find_element(By.ID, "error").text
    assert "animating" in seen  # it was drawn over time, not shown at once
    assert driver.find_element(By.ID, "scrub").get_attribute("value") == "1000"
    inked = driver.execute_script(
        "const c = document.getElementById('view');"
        "const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;"
        "let n = 0; for (let i = 0; i < d.length; i += 4) if (d[i] < 200) n++; return n;"
    )
    assert inked > 50

    # The stroke count shown is the API's for the same picture.
    r = httpx.post(f"{url}/api/plan", files={"image": ("d.png", png, "image/png")}, timeout=120)
    assert r.status_code == 200, r.text
    answer = r.json()
    shown = driver.find_element(By.ID, "stat-strokes").text
    assert shown == str(answer["stats"]["strokes"]) == str(len(answer["strokes"]))
    assert driver.find_element(By.ID, "stat-down").text.endswith(" px")

    # The files downloaded are `jdraw draw`'s for the same picture.
    source = tmp_path / "drawing.png"
    source.write_bytes(png)
    argv = ["draw", str(source), "--no-progress"]
    for ext in ("svg", "gcode", "json"):
        argv += [f"--{ext}", str(tmp_path / f"cli.{ext}")]
    assert cli.main(argv) == 0
    for ext in ("svg", "gcode", "json"):
        driver.find_element(By.ID, f"dl-{ext}").click()
        got = downloads / f"drawing.{ext}"
        wait_for(driver, lambda d, f=got: f.exists() and f.stat().st_size > 0, 30, got.name)
        assert got.read_bytes() == (tmp_path / f"cli.{ext}").read_bytes(), ext

    # A width in mm changes the statistics and the files, not the plan.
    width = driver.find_element(By.NAME, "width-mm")
    width.send_keys("120")
    driver.find_element(By.ID, "preset").click()  # moves focus: the change event fires
    wait_for(driver, lambda d: d.find_element(By.ID, "stat-down").text.endswith(" mm"), 60, "mm")
    assert driver.find_element(By.ID, "stat-strokes").text == shown


def test_an_error_reads_as_a_message_on_the_page(page, tmp_path):
    driver, _, _ = page
    bad = tmp_path / "notes.txt"
    bad.write_text("this is not a picture\n")
    driver.find_element(By.ID, "file").send_keys(str(bad))
    wait_for(driver, lambda d: state(d) == "error", 60, "the error")
    box = driver.find_element(By.ID, "error")
    assert box.is_displayed()
    assert "notes.txt" in box.text and "not an image" in box.text, box.text
    assert "{" not in box.text  # the message, not the JSON it came in
    assert box.get_attribute("role") == "alert"
    # And the page recovers: clearing goes back to the pad.
    driver.find_element(By.ID, "clear").click()
    assert not box.is_displayed() and driver.find_element(By.ID, "pad").is_displayed()


def test_page_shows_the_server_limits(page):
    driver, url, _ = page
    hint = driver.find_element(By.ID, "drop-hint").text
    limits = json.loads(httpx.get(f"{url}/api/options").text)["limits"]
    assert f"{limits['max_bytes'] / 1e6:g} MB" in hint
