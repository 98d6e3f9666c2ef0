"""The screenshot of ``jdraw serve``'s page in docs/web.png.

    python examples/web_screenshot.py      # ~1 min on a 2-core CPU (the model compiles first)

Serves the page on a free loopback port, opens it in Debian's headless
chromium (``apt-get install chromium chromium-driver``), chooses
``examples/images/kanji.png``, sets a 150 mm width, and takes the picture
with the plan two thirds drawn.
"""

from __future__ import annotations

import argparse
import pathlib
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the server-in-a-thread and browser helpers are the tests'

from selenium.webdriver.common.by import By  # noqa: E402

from jdraw.web.app import create_app  # noqa: E402
from tests.web_helpers import chromium, live_server  # noqa: E402


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--image", default=str(ROOT / "examples" / "images" / "kanji.png"))
    p.add_argument("--out", default=str(ROOT / "docs" / "web.png"))
    p.add_argument("--at", type=float, default=0.67, help="how much of the plan is drawn")
    args = p.parse_args()
    app = create_app()
    print("compiling the model...", flush=True)
    app.state.queue.warm_up().result()  # so the page shows the time of a plan, not of compiling
    with live_server(app) as url:
        driver = chromium(size=(1280, 900))
        try:
            driver.get(url)
            driver.find_element(By.NAME, "width-mm").send_keys("150")
            driver.find_element(By.ID, "file").send_keys(args.image)
            body = driver.find_element(By.TAG_NAME, "body")
            deadline = time.monotonic() + 600
            while body.get_attribute("data-state") not in ("done", "error"):
                if time.monotonic() > deadline:
                    raise SystemExit("the page did not finish planning")
                time.sleep(0.2)
            if body.get_attribute("data-state") == "error":
                raise SystemExit(driver.find_element(By.ID, "error").text)
            driver.execute_script(
                "const s = document.getElementById('scrub');"
                "s.value = String(Math.round(arguments[0] * 1000));"
                "s.dispatchEvent(new Event('input'));",
                args.at,
            )
            driver.execute_script("window.scrollTo(0, 0)")
            driver.save_screenshot(args.out)
            print(f"{args.out}: {driver.find_element(By.ID, 'stat-strokes').text} strokes")
        finally:
            driver.quit()


if __name__ == "__main__":
    main()
