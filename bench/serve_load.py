"""``jdraw serve`` under load: N requests from K concurrent clients, on this machine only.

  nice -n 10 python bench/serve_load.py                   # K = 1 and 8, 24 requests each
  python bench/serve_load.py --clients 1,4,8 --requests 48 --timeout 900

Starts ``jdraw serve`` on a free port of 127.0.0.1 (loopback only; nothing
else is ever sent a request), waits for its model to compile, then for each
K sends N ``POST /api/plan`` requests from K client threads. Every request
carries the same picture (``--image``, default examples/images/kanji.png)
re-encoded with a different PNG text chunk: the same pixels, so the same
plan, but different bytes, so the server's cache of finished plans does not
answer it and each one is planned (``--same-image`` measures cache hits
instead). Prints requests/s, p50 and p95 latency and errors per K. Then sends
a 20000 x 20000 PNG (a decompression bomb of ~50 kB) and prints how long
its 413 took and the server's peak memory before and after.

Bounded: at most N requests per K, none started after ``--timeout`` seconds,
each waiting at most that long; the server is stopped at the end.
"""

from __future__ import annotations

import argparse
import concurrent.futures
import io
import os
import pathlib
import socket
import subprocess
import sys
import time

import httpx
import numpy as np
from PIL import Image, PngImagePlugin

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the PNG bomb is the tests' (tests/web_helpers.py)

from tests.web_helpers import bomb_png  # noqa: E402

HOST = "127.0.0.1"  # loopback only, by design: no flag changes it


def free_port() -> int:
    with socket.socket() as s:
        s.bind((HOST, 0))
        return s.getsockname()[1]


def variants(path: pathlib.Path, n: int) -> list[bytes]:
    """``n`` PNG files of the same pixels, each with its own text chunk."""
    img = Image.open(path)
    img.load()
    out = []
    for i in range(n):
        info = PngImagePlugin.PngInfo()
        info.add_text("jdraw-bench", str(i))
        buf = io.BytesIO()
        img.save(buf, "PNG", pnginfo=info)
        out.append(buf.getvalue())
    return out


def peak_rss_mb(pid: int) -> float:
    """The process's peak resident memory (VmHWM), MB."""
    for line in pathlib.Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) / 1024
    return float("nan")


def load(url: str, bodies: list[bytes], clients: int, deadline: float) -> dict:
    """Sends every body once from ``clients`` threads; latencies and errors."""

    def one(body: bytes):
        if time.monotonic() > deadline:
            return None, "not sent (past --timeout)"
        t0 = time.perf_counter()
        try:
            r = httpx.post(
                f"{url}/api/plan",
                files={"image": ("bench.png", body, "image/png")},
                timeout=max(1.0, deadline - time.monotonic()),
            )
        except httpx.HTTPError as e:
            return None, f"{type(e).__name__}: {e}"
        dt = time.perf_counter() - t0
        if r.status_code != 200:
            return dt, f"{r.status_code}: {r.text.strip()}"
        return dt, None

    t0 = time.perf_counter()
    with concurrent.futures.ThreadPoolExecutor(clients) as pool:
        results = list(pool.map(one, bodies))
    wall = time.perf_counter() - t0
    ok = [dt for dt, err in results if err is None]
    errors = [err for _, err in results if err is not None]
    return {
        "ok": len(ok),
        "rps": len(ok) / wall,
        "p50": float(np.percentile(ok, 50)) if ok else float("nan"),
        "p95": float(np.percentile(ok, 95)) if ok else float("nan"),
        "errors": errors,
    }


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--clients", default="1,8", help="comma-separated K (default 1,8)")
    p.add_argument("--requests", type=int, default=24, help="N per K (default 24)")
    p.add_argument("--image", default=str(ROOT / "examples" / "images" / "kanji.png"))
    p.add_argument("--same-image", action="store_true", help="identical bytes: cache hits")
    p.add_argument("--timeout", type=float, default=600.0, help="seconds in all (default 600)")
    args = p.parse_args()
    ks = [int(k) for k in args.clients.split(",")]
    if not 1 <= args.requests <= 1000 or not all(1 <= k <= 64 for k in ks):
        raise SystemExit("--requests must be in 1..1000 and each K in 1..64")
    deadline = time.monotonic() + args.timeout

    port = free_port()
    url = f"http://{HOST}:{port}"
    server = subprocess.Popen(
        [sys.executable, "-m", "jdraw.cli", "serve", "--host", HOST, "--port", str(port)],
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    try:
        while True:
            try:
                httpx.get(f"{url}/api/options", timeout=2).raise_for_status()
                break
            except httpx.HTTPError:
                if server.poll() is not None or time.monotonic() > deadline:
                    raise SystemExit("jdraw serve did not start") from None
                time.sleep(0.3)
        bodies = variants(pathlib.Path(args.image), args.requests * len(ks) + 1)
        if args.same_image:
            bodies = [bodies[0]] * len(bodies)
        t0 = time.perf_counter()
        first = load(url, bodies[:1], 1, deadline)  # waits for the model to compile
        print(f"first plan (compiling the model): {time.perf_counter() - t0:.1f} s", flush=True)
        if first["errors"]:
            raise SystemExit(f"the first request failed: {first['errors'][0]}")

        rows = []
        for i, k in enumerate(ks):
            batch = bodies[1 + i * args.requests : 1 + (i + 1) * args.requests]
            rows.append((k, load(url, batch, k, deadline)))
            print(f"K={k} done", flush=True)

        bomb = bomb_png(20000, 20000)
        before = peak_rss_mb(server.pid)
        t0 = time.perf_counter()
        r = httpx.post(
            f"{url}/api/plan", files={"image": ("bomb.png", bomb, "image/png")}, timeout=60
        )
        bomb_s = time.perf_counter() - t0
        after = peak_rss_mb(server.pid)
        alive = httpx.get(f"{url}/api/options", timeout=10).status_code == 200
    finally:
        server.terminate()
        try:
            server.wait(timeout=30)
        except subprocess.TimeoutExpired:
            server.kill()

    image = pathlib.Path(args.image).name + (" (same bytes)" if args.same_image else "")
    print(f"\n{image}, {args.requests} requests per K, loopback\n")
    print("| clients K | requests | requests/s | p50 latency | p95 latency | errors |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: |")
    for k, row in rows:
        print(
            f"| {k} | {row['ok']} | {row['rps']:.2f} | {row['p50']:.2f} s | "
            f"{row['p95']:.2f} s | {len(row['errors'])} |"
        )
    for k, row in rows:
        for err in row["errors"][:3]:
            print(f"  K={k} error: {err}")
    print(
        f"\n20000 x 20000 PNG bomb ({len(bomb)} bytes): HTTP {r.status_code} "
        f"in {bomb_s:.2f} s; server peak RSS {before:.0f} MB before, {after:.0f} MB after; "
        f"server {'up' if alive else 'DOWN'} afterwards"
    )


if __name__ == "__main__":
    main()
