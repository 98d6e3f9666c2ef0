"""The paper's Fig. 5, ours: "hello" in ten scripts and a sketch, planned by ``jdraw draw``.

  python examples/ten_scripts.py [--out docs/ten_scripts.png] [--checkpoint PATH]

Each word is set in a font from a Debian package with a thick anti-aliased
outline, as a marker on a whiteboard would write it (dark on white, 120 px
high), and the sketch (a house under the sun) is drawn with cv2 lines. Every
image is planned by its own ``jdraw draw IMAGE --json`` call, as a user
would run it (reading direction read from the image); the planned strokes,
coloured by order (blue first, red last, a dot at each start), make the
grid. Prints a table of script, strokes, direction and seconds. A missing
font is reported with the ``apt-get install`` line that provides it, and
its cell is left out. The images and JSON plans stay in ``--workdir``.
About 2-3 min on a 2-core CPU (JAX's compilation cache in ``--workdir``
makes later calls faster).
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import subprocess
import sys
import time

import cv2
import numpy as np
from PIL import Image

from jdraw.data import fonts as F
from jdraw.io.pictures import draw_strokes_png

# (label, text, font, fallback font)
WORDS = [
    ("English cursive", "hello", "dancing_script", None),
    ("Urdu", "ہیلو", "noto_nastaliq_urdu", "noto_naskh_arabic"),
    ("Greek", "γειά", "noto_sans", None),
    ("Japanese", "こんにちは", "noto_sans_cjk_jp", None),
    ("Korean", "안녕하세요", "noto_sans_cjk_kr", None),
    ("Chinese", "你好", "noto_sans_cjk_sc", None),
    ("Tamil", "வணக்கம்", "noto_sans_tamil", None),
    ("French", "bonjour", "noto_sans", None),
    ("Hindi", "नमस्ते", "noto_sans_devanagari", None),
    ("Yiddish", "שלום", "noto_sans_hebrew", None),
]
HEIGHT = 120  # px, ink height of a word
PEN = 0.02  # marker outline, fraction of the height (2-3 px each side)
CELL = (360, 200)  # px (w, h) of a grid cell's picture
LABEL = 34  # px of caption under it


def house(height: int = 2 * HEIGHT) -> np.ndarray:
    """``uint8 [H, W]`` a house under the sun, thick anti-aliased marker lines."""
    h, w, t = height, int(1.5 * height), 5
    img = np.full((h, w), 255, np.uint8)
    s = h / 240
    pts = lambda *p: np.round(np.array(p) * s).astype(np.int32)
    cv2.polylines(
        img, [pts((40, 220), (40, 120), (180, 120), (180, 220))], False, 0, t, cv2.LINE_AA
    )
    cv2.polylines(img, [pts((25, 125), (110, 50), (195, 125))], False, 0, t, cv2.LINE_AA)
    cv2.line(img, *map(tuple, pts((20, 222), (330, 222))), 0, t, cv2.LINE_AA)
    cv2.rectangle(img, *map(tuple, pts((95, 220), (125, 165))), 0, t, cv2.LINE_AA)
    cv2.rectangle(img, *map(tuple, pts((55, 135), (82, 160))), 0, t, cv2.LINE_AA)
    cv2.circle(img, tuple(map(int, pts(280, 60))), int(28 * s), 0, t, cv2.LINE_AA)
    return img


def images(workdir: pathlib.Path) -> list[tuple[str, str, pathlib.Path]]:
    """Writes each word's and the sketch's PNG; returns ``(label, font, path)`` per cell."""
    out = []
    for label, text, font, fallback in WORDS:
        use = font
        try:
            F.font_path(font)
        except F.FontMissing as e:
            if fallback is None:
                print(f"MISSING {label}: {e}; left out", file=sys.stderr)
                continue
            print(f"note: {e}; {label} uses {fallback}", file=sys.stderr)
            use = fallback
            try:
                F.font_path(use)
            except F.FontMissing as e2:
                print(f"MISSING {label}: {e2}; left out", file=sys.stderr)
                continue
        path = workdir / f"{label.split()[0].lower()}.png"
        Image.fromarray(F.render_word(text, use, HEIGHT, pen=PEN, margin=40)).save(path)
        out.append((label, use, path))
    path = workdir / "sketch.png"
    Image.fromarray(house()).save(path)
    out.append(("Sketch", "cv2 lines", path))
    return out


def plan(path: pathlib.Path, checkpoint: str | None, env: dict) -> tuple[dict, float, str]:
    """``jdraw draw path --json``: the plan's JSON, the call's seconds and its summary line."""
    out = path.with_suffix(".json")
    cmd = [sys.executable, "-m", "jdraw.cli", "draw", str(path), "--json", str(out)]
    cmd += ["--no-progress"] + (["--checkpoint", checkpoint] if checkpoint else [])
    t0 = time.perf_counter()
    run = subprocess.run(cmd, capture_output=True, text=True, env=env)
    dt = time.perf_counter() - t0
    if run.returncode != 0:
        raise SystemExit(f"jdraw draw {path} failed:\n{run.stderr}")
    return json.loads(out.read_text()), dt, run.stdout.strip()


def cell(img: np.ndarray, strokes: list[np.ndarray], caption: str) -> np.ndarray:
    """One grid cell: the strokes in order colours over the faint ink, and a caption."""
    h, w = img.shape
    scale = min((CELL[0] - 16) / w, (CELL[1] - 16) / h)
    pic = draw_strokes_png(img, strokes, scale=scale, line_width=3.0)
    out = np.full((CELL[1] + LABEL, CELL[0], 3), 255, np.uint8)
    y, x = (CELL[1] - pic.shape[0]) // 2, (CELL[0] - pic.shape[1]) // 2
    out[y : y + pic.shape[0], x : x + pic.shape[1]] = pic
    size = cv2.getTextSize(caption, cv2.FONT_HERSHEY_SIMPLEX, 0.6, 1)[0]
    org = ((CELL[0] - size[0]) // 2, CELL[1] + 24)
    cv2.putText(out, caption, org, cv2.FONT_HERSHEY_SIMPLEX, 0.6, (0, 0, 0), 1, cv2.LINE_AA)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default="docs/ten_scripts.png")
    ap.add_argument("--workdir", default="runs/ten_scripts", help="images, plans, JAX cache")
    ap.add_argument("--checkpoint", help="passed to jdraw draw (default: the bundled model)")
    ap.add_argument("--columns", type=int, default=4)
    args = ap.parse_args()
    workdir = pathlib.Path(args.workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, JAX_COMPILATION_CACHE_DIR=str((workdir / "jax_cache").resolve()))
    cells = []
    print("| script | font | strokes | direction | seconds |")
    print("| --- | --- | ---: | --- | ---: |")
    t0 = time.perf_counter()
    for label, font, path in images(workdir):
        data, dt, summary = plan(path, args.checkpoint, env)
        strokes = [np.asarray(s, np.float64).reshape(-1, 2) for s in data["strokes"]]
        direction = "right to left" if "right to left" in summary else "left to right"
        print(f"| {label} | {font} | {len(strokes)} | {direction} | {dt:.1f} |", flush=True)
        img = np.asarray(Image.open(path).convert("L"))
        caption = f"{label}: {len(strokes)} stroke{'s' * (len(strokes) != 1)}"
        cells.append(cell(img, strokes, caption))
    blank = np.full_like(cells[0], 255)
    cols = args.columns
    rows = [cells[k : k + cols] for k in range(0, len(cells), cols)]
    rows[-1] += [blank] * (cols - len(rows[-1]))
    grid = np.concatenate([np.concatenate(r, axis=1) for r in rows], axis=0)
    out = pathlib.Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    Image.fromarray(grid).quantize(64).save(out, optimize=True)
    print(f"\nwrote {out} ({out.stat().st_size // 1024} KB) in {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
