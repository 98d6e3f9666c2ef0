"""Helpers for the web tests, bench/serve_load.py and examples/web_screenshot.py.

A server in a thread, Debian's headless chromium, a PNG decompression bomb.
"""

from __future__ import annotations

import contextlib
import pathlib
import struct
import threading
import time
import zlib


@contextlib.contextmanager
def live_server(app, timeout_s: float = 30.0):
    """Serves ``app`` with uvicorn on a free loopback port in a thread; yields its URL."""
    import uvicorn

    config = uvicorn.Config(app, host="127.0.0.1", port=0, log_level="warning", lifespan="on")
    server = uvicorn.Server(config)
    thread = threading.Thread(target=server.run, name="jdraw-test-server", daemon=True)
    thread.start()
    deadline = time.monotonic() + timeout_s
    while not server.started:
        if not thread.is_alive() or time.monotonic() > deadline:
            raise RuntimeError("the test server did not start")
        time.sleep(0.02)
    port = server.servers[0].sockets[0].getsockname()[1]
    try:
        yield f"http://127.0.0.1:{port}"
    finally:
        server.should_exit = True
        thread.join(timeout_s)


CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"


def chromium(download_dir: pathlib.Path | None = None, size=(1280, 900)):
    """Debian's chromium, headless, driven by Selenium; downloads go to ``download_dir``.

    The driver's path is given, so Selenium Manager is not run and nothing is downloaded.
    """
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    opts = webdriver.ChromeOptions()
    opts.binary_location = CHROMIUM
    for arg in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--disable-gpu"):
        opts.add_argument(arg)
    opts.add_argument(f"--window-size={size[0]},{size[1]}")
    if download_dir is not None:
        prefs = {
            "download.default_directory": str(download_dir),
            "download.prompt_for_download": False,
        }
        opts.add_experimental_option("prefs", prefs)
    return webdriver.Chrome(service=Service(executable_path=CHROMEDRIVER), options=opts)


def _chunk(kind: bytes, data: bytes) -> bytes:
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))


def bomb_png(width: int, height: int) -> bytes:
    """A valid 1-bit black PNG of ``width x height`` pixels, compressed to almost nothing.

    Written row by row, so making a 20000 x 20000 one (400 Mpx, about 50 MB
    decoded as bits, 400 MB as bytes) takes a few MB of memory and gives a
    file of tens of kilobytes: a decompression bomb.
    """
    header = struct.pack(">IIBBBBB", width, height, 1, 0, 0, 0, 0)  # 1-bit gray
    row = b"\0" * (1 + (width + 7) // 8)  # filter byte 0, then the bits
    z = zlib.compressobj(9)
    parts = []
    for _ in range(height):
        parts.append(z.compress(row))
    parts.append(z.flush())
    return (
        b"\x89PNG\r\n\x1a\n"
        + _chunk(b"IHDR", header)
        + _chunk(b"IDAT", b"".join(parts))
        + _chunk(b"IEND", b"")
    )
