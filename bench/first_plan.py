"""How long a user waits for ``jdraw draw``: fresh processes, cold and warm compilation cache.

  nice -n 10 python bench/first_plan.py            # every row, ~4-8 minutes on a 2-core CPU
  python bench/first_plan.py --rows readme_cold,readme_warm

Each row is one new ``python -m jdraw.cli ...`` process (through this script's
``--child`` mode, which counts XLA programs with JAX's monitoring events);
wall seconds are from process start to exit, measured by this parent. Rows:

* ``readme``: the README's ``jdraw draw examples/images/kanji.png --png ... --svg ...``,
  with an empty compilation cache (cold) and then with the cache it left (warm);
* ``word``: a 401x160 cursive-looking word (joined loops, 3-px pen; :func:`word_image`),
  cold and warm;
* ``one``/``set20``: one generated word, then 20 of them in one command (``--out-dir``), warm
  (an unmeasured run of the 20 first compiles every program they need);
* ``big10k``: a 10000x10000 PNG of one line, planned (peak RSS is the row's point);
* ``big20k``: a 20000x20000 PNG of one line, refused by the pixel limit;
* ``import``: ``python -c "import jdraw"``.

"programs" counts XLA executables the process needed, "compiled" those XLA
compiled (the rest were read from JAX's cache or jdraw's program store),
"compile s" the seconds spent compiling or reading them, "peak RSS" the
process's own. The rows run with Python's default of writing bytecode
(``PYTHONDONTWRITEBYTECODE`` is dropped from their environment), as on a
user's machine. The images are generated under a temporary folder. Results and
the load they were measured under: docs/speed.md.
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import resource
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
WORDS = (
    "minimum hello quill arrow dune lake moon river cloud snow "
    "light stone field ocean forest bridge garden window mirror candle"
).split()


def word_image(seed: int, height: int = 160, pen: int = 3):
    """``uint8 [height, W]`` dark ink on white: a cursive-looking word, one connected stroke.

    A run of loops (a prolate cycloid, like joined-up e's and l's), each letter's
    height and width drawn from ``seed``, with a 3-px pen.
    """
    import cv2
    import numpy as np

    rng = np.random.default_rng(seed)
    n = 7
    pts, x0 = [], 12.0
    for _ in range(n):
        tall = rng.random() < 0.3
        r = rng.uniform(18, 24)
        hgt = (height - 30) if tall else rng.uniform(50, 70)
        t = np.linspace(0, 2 * np.pi, 60)
        x = x0 + r * (t / np.pi) * 1.2 - r * 0.8 * np.sin(t)
        y = height - 14 - hgt / 2 * (1 + np.cos(t))
        pts.append(np.stack([x, y], 1))
        x0 = x[-1]
    line = np.concatenate(pts)
    img = np.full((height, int(x0) + 14), 255, np.uint8)
    cv2.polylines(img, [np.round(line * 4).astype(np.int32)], False, 0, pen, cv2.LINE_AA, 2)
    return img


def line_image(side: int):
    """``uint8 [side, side]``: one thick diagonal-ish line of ink on white."""
    import cv2
    import numpy as np

    img = np.full((side, side), 255, np.uint8)
    cv2.line(img, (side // 10, side // 5), (side - side // 10, side - side // 4), 0, 12)
    return img


def _one(image, out) -> list[str]:
    return ["draw", str(image), "--svg", str(out / f"{image.stem}.svg"), "--no-progress"]


def _size(path) -> str:
    from PIL import Image

    with Image.open(path) as im:
        return f"{im.width}x{im.height}"


def child(stats_path: str, argv: list[str]) -> int:
    """Runs ``jdraw`` with ``argv``, counting XLA programs; writes the counts as JSON at exit."""
    from jax import monitoring

    programs: list[list] = []  # [fun_name, seconds, from cache]
    hits = [0]

    def on_duration(event, secs, **kw):
        if event == "/jax/core/compile/backend_compile_duration":
            programs.append([kw.get("fun_name", "?"), secs, hits[0] > 0])
            hits[0] = 0
        elif event == "/jdraw/program_store/load_duration":  # jdraw.planner.executables
            programs.append(["stored program", secs, True])

    def on_event(event, **kw):
        if event == "/jax/compilation_cache/cache_hits":
            hits[0] += 1

    monitoring.register_event_duration_secs_listener(on_duration)
    monitoring.register_event_listener(on_event)
    from jdraw import cli

    try:
        status = cli.main(argv)
    finally:
        rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20  # KB -> GB
        pathlib.Path(stats_path).write_text(json.dumps({"programs": programs, "rss_gb": rss}))
    return status


def run_row(argv: list[str], env: dict, cwd) -> dict:
    """One fresh process; returns wall seconds, exit status, programs and peak RSS."""
    with tempfile.NamedTemporaryFile(suffix=".json", delete=False) as f:
        stats = f.name
    cmd = [sys.executable, str(pathlib.Path(__file__).resolve()), "--child", stats, "--", *argv]
    t0 = time.perf_counter()
    p = subprocess.run(cmd, env=env, cwd=cwd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    try:
        info = json.loads(pathlib.Path(stats).read_text())
    except (OSError, ValueError):
        info = {"programs": [], "rss_gb": float("nan")}
    os.unlink(stats)
    progs = info["programs"]
    return {
        "wall": wall,
        "rc": p.returncode,
        "programs": len(progs),
        "compiled": sum(1 for _, _, cached in progs if not cached),
        "compile_s": sum(s for _, s, _ in progs),
        "rss_gb": info["rss_gb"],
        "out": (p.stdout.strip().splitlines() or [""])[-1],
        "err": (p.stderr.strip().splitlines() or [""])[-1],
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rows", default="all", help="comma-separated row names, or 'all'")
    ap.add_argument("--keep", metavar="DIR", help="work folder to keep (default: a temporary one)")
    args = ap.parse_args()
    rows = args.rows.split(",") if args.rows != "all" else None
    work = pathlib.Path(args.keep or tempfile.mkdtemp(prefix="jdraw-first-plan-"))
    work.mkdir(parents=True, exist_ok=True)
    import cv2

    images = work / "images"
    images.mkdir(exist_ok=True)
    for i, w in enumerate(WORDS):
        cv2.imwrite(str(images / f"{w}.png"), word_image(i))
    word = images / f"{WORDS[0]}.png"
    if rows is None or "big10k" in rows:
        cv2.imwrite(str(work / "line10k.png"), line_image(10000))
    if rows is None or "big20k" in rows:
        cv2.imwrite(str(work / "line20k.png"), line_image(20000))
    cache = work / "cache"
    env = dict(os.environ, JDRAW_CACHE_DIR=str(cache), PYTHONPATH=str(ROOT))
    env.pop("JAX_COMPILATION_CACHE_DIR", None)
    # Python writes bytecode by default, so a user's second run reads jdraw's modules
    # compiled; a sandbox that turns it off (PYTHONDONTWRITEBYTECODE=1) would make every
    # row compile them from source again (0.2-0.3 s a start on a 2-core CPU).
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    out = work / "out"
    out.mkdir(exist_ok=True)
    readme = ["draw", "examples/images/kanji.png", "--png", str(out / "k.png")]
    readme += ["--svg", str(out / "k.svg"), "--no-progress"]
    table = [
        ("readme_cold", "README example, cold cache", readme, True),
        ("readme_warm", "README example, warm cache", readme, False),
        ("word_cold", f"word {word.stem!r} ({_size(word)}), cold", None, True),
        ("word_warm", f"word {word.stem!r}, warm", None, False),
        ("one", "one word image, warm (--out-dir)", [str(images / "hello.png")], False),
        ("set20", "20 word images in one command, warm", [str(images)], False),
        ("big10k", "10000x10000 PNG of one line", _one(work / "line10k.png", out), False),
        ("big20k", "20000x20000 PNG of one line (refused)", _one(work / "line20k.png", out), False),
    ]
    print(
        f"{'row':<44} {'wall s':>7} {'exit':>4} {'programs':>8} {'compiled':>8} "
        f"{'compile s':>9} {'peak RSS GB':>11}"
    )
    warmed = False
    for name, label, argv, cold in table:
        if rows is not None and name not in rows:
            continue
        if cold and cache.exists():
            import shutil

            shutil.rmtree(cache)
        if argv is None:
            argv = ["draw", str(word), "--svg", str(out / "w.svg"), "--no-progress"]
        elif argv[0] != "draw":
            argv = ["draw", *argv, "--out-dir", str(out / name), "--svg", "--no-progress"]
        if name in ("one", "set20") and not warmed:  # the set's programs, compiled unmeasured
            run_row(
                ["draw", str(images), "--out-dir", str(out / "warm"), "--no-progress"], env, ROOT
            )
            warmed = True
        r = run_row(argv, env, ROOT)
        print(
            f"{label:<44} {r['wall']:7.1f} {r['rc']:4d} {r['programs']:8d} {r['compiled']:8d} "
            f"{r['compile_s']:9.1f} {r['rss_gb']:11.2f}"
        )
        if r["rc"] not in (0,):
            print(f"    stderr: {r['err']}")
    if rows is None or "import" in rows:
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", "import jdraw"], env=env, check=True)
        label = 'python -c "import jdraw"'
        print(f"{label:<44} {time.perf_counter() - t0:7.1f}")
    print(f"(work folder: {work})")


if __name__ == "__main__":
    if len(sys.argv) > 2 and sys.argv[1] == "--child":
        stats, rest = sys.argv[2], sys.argv[3:]
        if rest and rest[0] == "--":
            rest = rest[1:]
        from jdraw import cli

        cli.quick_exit(child(stats, rest))  # leaves as the jdraw command does
    main()
