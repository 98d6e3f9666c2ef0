"""``jdraw serve``'s API: the same files as ``jdraw draw``, its errors, limits and queue."""

from __future__ import annotations

import concurrent.futures
import contextlib
import json
import os
import pathlib
import socket
import subprocess
import sys
import threading
import time

import cv2
import numpy as np
import pytest

from jdraw import cli
from jdraw.io.plan_json import to_json
from jdraw.tiling import plan_image as tiling
from tests.doubles import trace_planner
from tests.web_helpers import bomb_png, live_server

if os.environ.get("CI"):  # CI installs the [web] extra: a missing one is a failure there
    import httpx
    import starlette
else:
    httpx = pytest.importorskip("httpx")
    starlette = pytest.importorskip("starlette")
    pytest.importorskip("uvicorn")

from jdraw.images import load  # noqa: E402
from jdraw.web import app as web_app  # noqa: E402
from jdraw.web import planning, upload  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]
KANJI = ROOT / "examples" / "images" / "kanji.png"
STATIC = ROOT / "jdraw" / "web" / "static"


@contextlib.contextmanager
def serving(limits: web_app.Limits | None = None):
    """An HTTP client of the app served by uvicorn on a free loopback port."""
    with live_server(web_app.create_app(limits)) as url:
        with httpx.Client(base_url=url, timeout=600) as client:
            yield client


def _png(img: np.ndarray) -> bytes:
    ok, buf = cv2.imencode(".png", img)
    assert ok
    return buf.tobytes()


def _lines(seed: int, size: int = 120) -> np.ndarray:
    """A small dark-on-white drawing of two lines, different for each seed."""
    rng = np.random.default_rng(seed)
    img = np.full((size, size), 255, np.uint8)
    for _ in range(2):
        a, b = rng.integers(10, size - 10, 2), rng.integers(10, size - 10, 2)
        cv2.line(img, tuple(int(v) for v in a), tuple(int(v) for v in b), 0, 3)
    return img


def _post(client, data: bytes, name="x.png", fmt=None, **fields):
    url = "/api/plan" + (f"?format={fmt}" if fmt else "")
    return client.post(url, files={"image": (name, data, "image/png")}, data=fields)


def _error(r, status: int) -> str:
    assert r.status_code == status, r.text
    body = r.json()
    assert list(body) == ["error"] and "\n" not in body["error"], body
    return body["error"]


@pytest.fixture
def traced(monkeypatch):
    """Plans with the model-free double (the tests of errors and the queue need no model)."""
    monkeypatch.setattr(tiling, "default_planner", trace_planner)


def test_kanji_plan_is_what_jdraw_draw_writes(tmp_path):
    """The bundled model through the API and through the command: the same bytes."""
    # The first plan compiles the model: a time limit a shared CPU cannot trip.
    with serving(web_app.Limits(plan_timeout_s=3600)) as client:
        data = KANJI.read_bytes()
        out = {f: tmp_path / f"cli.{f}" for f in ("json", "svg", "gcode")}
        argv = ["draw", str(KANJI), "--no-progress", "--width-mm", "150", "--preset", "servo"]
        argv += ["--feed", "2000", "--origin-mm", "10", "20"]
        for f, p in out.items():
            argv += [f"--{f}", str(p)]
        assert cli.main(argv) == 0
        fields = {"width-mm": "150", "preset": "servo", "feed": "2000", "origin-mm": "10 20"}
        for f, p in out.items():
            r = _post(client, data, "kanji.png", fmt=None if f == "json" else f, **fields)
            assert r.status_code == 200, r.text
            assert r.content == p.read_bytes(), f
        assert r.headers["content-type"].startswith("text/plain")
        plan = json.loads(out["json"].read_text())
        assert (
            plan["stats"]["strokes"] == len(plan["strokes"]) > 1 and plan["stats"]["units"] == "mm"
        )
        # Defaults: no field at all is `jdraw draw IMAGE --json OUT`.
        assert cli.main(["draw", str(KANJI), "--no-progress", "--json", str(out["json"])]) == 0
        r = _post(client, data, "kanji.png")
        assert r.headers["content-type"] == "application/json"
        assert r.content == out["json"].read_bytes()
        assert json.loads(r.content)["strokes"] == plan["strokes"]


def test_user_errors_are_400_with_one_line(traced):
    with serving() as client:
        good = _png(_lines(0))
        assert "not an image" in _error(_post(client, b"hello, world\n" * 20, "a.txt"), 400)
        bad_png = b"\x89PNG\r\n\x1a\n" + b"\0" * 40
        assert _error(_post(client, bad_png, "bad.png"), 400)
        broken = good[: len(good) // 2]  # a real header, half the data
        assert "broken.png" in _error(_post(client, broken, "broken.png"), 400)
        blank = _png(np.full((60, 80), 250, np.uint8))
        assert "nothing to draw" in _error(_post(client, blank), 400)
        assert "width-mm" in _error(_post(client, good, **{"width-mm": "-3"}), 400)
        assert "width-mm" in _error(_post(client, good, **{"width-mm": "wide"}), 400)
        assert "preset" in _error(_post(client, good, preset="laser"), 400)
        assert "pen-up" in _error(_post(client, good, **{"pen-up": "G0 Z{oops}"}), 400)
        assert "origin-mm" in _error(_post(client, good, **{"origin-mm": "1"}), 400)
        assert "colour" in _error(_post(client, good, colour="red"), 400)
        assert "format" in _error(_post(client, good, fmt="pdf"), 400)
        assert "image" in _error(client.post("/api/plan", data={"preset": "servo"}), 400)
        assert "multipart" in _error(client.post("/api/plan", content=good), 400)
        # The same image with good options still plans: nothing above broke the server.
        r = _post(client, good, fmt="svg", **{"width-mm": "80", "height_mm": ""})
        assert r.status_code == 200 and 'width="80mm"' in r.text, r.text[:300]


def test_byte_limit_is_413(traced):
    data = _png(_lines(1, size=300))
    limits = web_app.Limits(max_bytes=len(data) - 1)
    with serving(limits) as client:
        assert "limit" in _error(_post(client, data), 413)  # the image, after parsing the form
        huge = data + bytes(200_000)  # refused from its Content-Length, before it is read
        assert f"the limit is {len(data) - 1} bytes" in _error(_post(client, huge), 413)
        assert _post(client, _png(_lines(1, size=40))).status_code == 200


def test_pixel_limit_is_413_before_decoding(traced, monkeypatch):
    def no_decoding(path):
        raise AssertionError("an image over the pixel limit was decoded")

    monkeypatch.setattr(load, "load_image", no_decoding)
    with serving() as client:
        bomb = bomb_png(20000, 20000)
        assert len(bomb) < 100_000  # 400 Mpx in a small file: only its header may be read
        assert "400000000 pixels" in _error(_post(client, bomb, "bomb.png"), 413)
        under_pillow_guard = bomb_png(8000, 8000)  # 64 Mpx: over ours, under Pillow's own
        assert "8000 x 8000" in _error(_post(client, under_pillow_guard), 413)
    with serving(web_app.Limits(max_pixels=120 * 120 - 1)) as small:
        assert "120 x 120" in _error(_post(small, _png(_lines(2))), 413)


def test_header_size_reads_only_the_header():
    data = bomb_png(10000, 9000)[:200]  # the header and no pixel data at all
    assert upload.header_size(data, 10**8) == (10000, 9000)
    with pytest.raises(upload.TooManyPixels):
        upload.header_size(data, 50_000_000)
    with pytest.raises(upload.NotAnImage):
        upload.header_size(b"GIF89a", 10**9)  # a signature without a header


def test_plan_over_the_time_limit_is_503_and_the_server_stays_up(monkeypatch):
    lost = {"s": 0.0}  # the time limit's clock runs this much ahead of the real one

    def slow(images, **kwargs):
        lost["s"] += 60.0  # a planner call that "takes" a minute
        return trace_planner(images, **kwargs)

    monkeypatch.setattr(planning, "_clock", lambda: time.monotonic() + lost["s"])
    monkeypatch.setattr(tiling, "default_planner", slow)
    with serving(web_app.Limits(plan_timeout_s=30.0)) as client:
        assert "limit" in _error(_post(client, _png(_lines(3))), 503)
        monkeypatch.setattr(tiling, "default_planner", trace_planner)
        assert _post(client, _png(_lines(4))).status_code == 200


def test_a_bug_is_500_and_the_server_stays_up(monkeypatch):
    def broken(images, **kwargs):
        raise RuntimeError("boom")

    monkeypatch.setattr(tiling, "default_planner", broken)
    with serving() as client:
        assert "RuntimeError: boom" in _error(_post(client, _png(_lines(5))), 500)
        monkeypatch.setattr(tiling, "default_planner", trace_planner)
        assert _post(client, _png(_lines(5))).status_code == 200


def _counting(planner, delay_s: float):
    """``planner`` that records how many of its calls overlap (must stay 1)."""
    lock = threading.Lock()
    state = {"now": 0, "most": 0, "calls": 0}

    def counted(images, **kwargs):
        with lock:
            state["now"] += 1
            state["calls"] += 1
            state["most"] = max(state["most"], state["now"])
        try:
            time.sleep(delay_s)
            return planner(images, **kwargs)
        finally:
            with lock:
                state["now"] -= 1

    return counted, state


def _post_many(url: str, images: list[bytes]) -> list[httpx.Response]:
    def one(i):
        files = {"image": (f"{i}.png", images[i], "image/png")}
        return httpx.post(f"{url}/api/plan", files=files, timeout=120)

    with concurrent.futures.ThreadPoolExecutor(len(images)) as pool:
        return list(pool.map(one, range(len(images))))


def test_twelve_concurrent_requests_queue_for_one_planner(monkeypatch):
    planner, state = _counting(trace_planner, 0.05)
    monkeypatch.setattr(tiling, "default_planner", planner)
    images = [_png(_lines(10 + i)) for i in range(12)]
    with live_server(web_app.create_app()) as url:
        responses = _post_many(url, images)
        assert [r.status_code for r in responses] == [200] * 12, [r.text for r in responses]
        for r, img in zip(responses, images):
            want = tiling.plan_image(cv2.imdecode(np.frombuffer(img, np.uint8), 0), progress=False)
            assert r.json()["strokes"] == to_json(want.strokes, want.shape)["strokes"]
        assert httpx.get(f"{url}/api/options").status_code == 200  # still up
    assert state["most"] == 1  # never two plans at once
    assert state["calls"] >= 24  # 12 served, 12 planned again above for the check


def test_a_full_queue_is_503_and_the_rest_are_served(monkeypatch):
    planner, state = _counting(trace_planner, 0.3)
    monkeypatch.setattr(tiling, "default_planner", planner)
    images = [_png(_lines(30 + i)) for i in range(6)]
    with live_server(web_app.create_app(web_app.Limits(max_queue=2))) as url:
        codes = sorted(r.status_code for r in _post_many(url, images))
        assert codes.count(200) >= 2 and set(codes) <= {200, 503} and 503 in codes, codes
        r = httpx.post(
            f"{url}/api/plan", files={"image": ("a.png", images[0], "image/png")}, timeout=60
        )
        assert r.status_code == 200  # the queue drained; still up
    assert state["most"] == 1


def test_page_is_served_from_the_package_and_needs_no_network():
    with serving() as client:
        page = client.get("/")
        assert page.status_code == 200 and "text/html" in page.headers["content-type"]
        for name in ("app.js", "style.css"):
            assert f"/static/{name}" in page.text
            assert client.get(f"/static/{name}").status_code == 200
        for path in STATIC.iterdir():  # no CDN, no remote font: it works offline
            text = path.read_text()
            assert "http://" not in text and "https://" not in text and "//cdn" not in text, path
        opts = client.get("/api/options").json()
        assert opts["presets"] == ["servo", "servo-s", "zaxis"]
        assert (
            opts["limits"]["max_bytes"] == 20_000_000 and opts["limits"]["max_pixels"] == 50_000_000
        )


def test_serve_flags(capsys):
    with pytest.raises(SystemExit) as e:
        cli.main(["serve", "--help"])
    assert e.value.code == 0
    text = capsys.readouterr().out
    for flag in ("--host", "--port", "--max-mb", "--max-mpx", "--plan-timeout", "--max-queue"):
        assert flag in text
    assert "127.0.0.1" in text
    # Bad limits are refused before anything listens.
    assert cli.main(["serve", "--max-mb", "0"]) == 2
    assert "--max-mb" in capsys.readouterr().err
    assert cli.main(["serve", "--port", "70000"]) == 2


def test_upload_decodes_as_the_command_line(tmp_path):
    data = (ROOT / "examples" / "images" / "hello.jpg").read_bytes()
    path = tmp_path / "hello.jpg"
    path.write_bytes(data)
    np.testing.assert_array_equal(upload.decode(data), load.load_image(path))
    with pytest.raises(load.ImageError, match="'mine.png'"):
        upload.decode(b"\x89PNG\r\n\x1a\n" + b"\0" * 40, "mine.png")


def test_jdraw_serve_listens_on_loopback_and_answers():
    """The command itself: starts, serves the page and the API on 127.0.0.1, stops on SIGTERM."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    cmd = [sys.executable, "-m", "jdraw.cli", "serve", "--port", str(port), "--no-warm-up"]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    server = subprocess.Popen(cmd, env=env, stderr=subprocess.PIPE, text=True)
    try:
        url = f"http://127.0.0.1:{port}"
        deadline = time.monotonic() + 120
        while True:
            try:
                page = httpx.get(url, timeout=5)
                break
            except httpx.TransportError:
                assert server.poll() is None and time.monotonic() < deadline, "did not start"
                time.sleep(0.2)
        assert page.status_code == 200 and "jdraw" in page.text
        r = httpx.post(f"{url}/api/plan", files={"image": ("a.txt", b"no", "text/plain")})
        assert r.status_code == 400 and "not an image" in r.json()["error"]
    finally:
        server.terminate()
        _, err = server.communicate(timeout=30)
    assert f"http://127.0.0.1:{port}/" in err
