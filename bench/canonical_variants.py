"""Canonical inputs: how well the default model plans KanjiVG drawn other ways.

  PYTHONPATH=. nice -n 5 python bench/canonical_variants.py --n 100 --split train
  PYTHONPATH=. nice -n 5 python bench/canonical_variants.py --n 100 --no-plan  # seconds
  PYTHONPATH=. python bench/canonical_variants.py --n 96 --split val \
      --styles clean,cv2,thick2,thick3 --splitter runs/splitter_patch/bundle

Draws N characters of a split (training by default: develop on it, not on
the test split) in several styles, canonicalises them
(:func:`jdraw.images.canonical.canonicalise`) and prints per style: line ends and
junctions of the canonical image against jdraw's own drawing (a quick proxy
for stroke breaks), tolerant pixel agreement with it, canonicalise's time
per character, and, with ``--plan``, the default model's stroke accuracy,
drawn/true strokes and tolerant pixel accuracy (:func:`jdraw.evaluation.metrics.score`,
``tol=1``), planned with the checkpoint's stroke splitter, none, or another's
(``--splitter``). About 1 s per character and style with planning on a 2-core CPU.

Styles: ``clean`` (jdraw's rasteriser), ``cv2`` / ``aa`` (OpenCV 1-pixel
LINE_8 / anti-aliased lines thresholded, as :func:`jdraw.evaluation.evaluate.rasterise`),
``thick2``, ``thick3``, ``thick5`` (LINE_8 with that ``thickness``: 3, 5
and 7 pixels wide; OpenCV draws 4 as 3) and ``gap`` (cv2 with the pixel
halfway along each stroke removed).

Result (100 training characters, default model, ``tol=1``; stroke accuracy /
drawn-to-true strokes / all-pairs order; canonicalise ms per character;
"after" is 576a207, before a lone lump was kept as jdraw's own corner):

  style    before (61e2254)          after (576a207)           ms
  clean    0.982 / 0.99 / 0.945      0.982 / 0.99 / 0.944      0.7
  cv2      0.917 / 1.10 / 0.933      0.964 / 1.01 / 0.929      1.2
  aa       0.529 / 2.55 / 0.923      0.962 / 0.98 / 0.869      5.7
  thick2   0.859 / 0.98 / 0.695      0.879 / 0.94 / 0.703      5.4
  thick3   0.774 / 0.96 / 0.551      0.820 / 0.88 / 0.558      5.5
  thick5   0.673 / 1.07 / 0.489      0.725 / 0.92 / 0.481      5.6
  gap      0.662 / 1.48 / 0.782      0.841 / 1.12 / 0.810      2.3
"""

from __future__ import annotations

import argparse
import pathlib
import time

import cv2
import numpy as np

from jdraw.data import demos as demo
from jdraw.data import kanji
from jdraw.evaluation import metrics
from jdraw.images import canonical
from jdraw.io import figures
from jdraw.planner import plan as api
from jdraw.planner import ranker

STYLES = ("clean", "cv2", "aa", "thick2", "thick3", "thick5", "gap")  # thick2: 3 px wide


def draw(ks: kanji.KanjiSet, i: int, style: str, d: demo.Demo) -> np.ndarray:
    """``bool [100, 100]`` character ``i`` drawn in ``style``."""
    if style == "clean":
        return d.target.copy()
    img = np.zeros((100, 100), np.uint8)
    thick, line = 1, cv2.LINE_8
    if style == "aa":
        line = cv2.LINE_AA
    elif style.startswith("thick"):
        thick = int(style[5:])
    for c in ks.strokes(i):
        pts = np.rint(kanji.sample_cubics(c, step=1.5)).astype(np.int32)
        stroke = np.zeros_like(img)
        cv2.polylines(stroke, [pts.reshape(-1, 1, 2)], False, 255, thick, line)
        if style == "gap" and len(pts) > 8:
            p = pts[len(pts) // 2]  # a 1-pixel break halfway along the stroke
            stroke[p[1], p[0]] = 0
        img = np.maximum(img, stroke)
    return img >= 128


def structure(c: np.ndarray) -> tuple[int, int]:
    """Line ends and junction clusters of a 1-pixel image."""
    n8 = np.array([[1, 1, 1], [1, 0, 1], [1, 1, 1]], np.float32)
    deg = np.rint(cv2.filter2D(c.astype(np.float32), -1, n8, borderType=cv2.BORDER_CONSTANT))
    ends = int(np.count_nonzero(c & (deg == 1)))
    junc = (c & (deg >= 3)).astype(np.uint8)
    nj = cv2.connectedComponents(junc, connectivity=8)[0] - 1
    return ends, nj


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=100)
    ap.add_argument("--split", default="train")
    ap.add_argument("--styles", default=",".join(STYLES))
    ap.add_argument("--plan", action=argparse.BooleanOptionalAction, default=True)
    ap.add_argument("--fn", default="canonicalise", help="function of jdraw.images.canonical")
    ap.add_argument("--checkpoint", default=None, help="bundle folder (default: the bundled)")
    ap.add_argument("--dump", default="", help="folder for PNGs of the worst characters")
    ap.add_argument(
        "--splitter",
        default="auto",
        help="stroke splitter: auto (the checkpoint's, if any), no, or a folder holding one",
    )
    args = ap.parse_args()

    ks = kanji.load(progress=False)
    idx = kanji.split_indices(ks, args.split)
    idx = np.random.default_rng(1).choice(idx, args.n, replace=False)
    demos = [demo.sample(ks, int(i)) for i in idx]
    rk = api.load_ranker(args.checkpoint)
    rows = []
    for style in args.styles.split(","):
        inputs = np.stack([draw(ks, int(i), style, d) for i, d in zip(idx, demos)])
        t = time.perf_counter()
        fn = getattr(canonical, args.fn)
        canon = np.stack([fn(x) for x in inputs])
        ms = 1e3 * (time.perf_counter() - t) / len(inputs)
        ends = jun = 0
        tpa = []
        for d, c in zip(demos, canon):
            e, j = structure(c)
            e0, j0 = structure(d.target)
            ends += abs(e - e0)
            jun += abs(j - j0)
            tpa.append(metrics.tolerant_pixel_accuracy(d.target, c, 1))
        row = {
            "style": style,
            "ms": ms,
            "d_ends": ends / len(idx),
            "d_junc": jun / len(idx),
            "tpa_clean": float(np.mean(tpa)),
            "same": float(np.mean([np.array_equal(d.target, c) for d, c in zip(demos, canon)])),
        }
        if args.plan:
            split = {"auto": None, "no": False}.get(args.splitter, args.splitter)
            # The images as drawn: plan canonicalises them as above, and the splitter sees both.
            own = args.fn == "canonicalise"
            p = api.plan(
                inputs if own else canon,
                checkpoint=args.checkpoint,
                order="model",
                canonicalise=own,
                split=split,
            )
            p = ranker.reorder(p, "ranker", rk) if rk is not None else p  # else as traced
            s = metrics.score(demos, p, inputs, tol=0 if style == "clean" else 1)
            row.update(
                stroke=s["stroke_acc"],
                ratio=s["stroke_ratio"],
                pixel=s["pixel_acc"],
                order=s["order_all_pairs"],
            )
            if args.dump:
                out = pathlib.Path(args.dump)
                out.mkdir(parents=True, exist_ok=True)
                per = [len(s) - len(d.strokes) for d, s in zip(demos, p.strokes)]
                for b in np.argsort(per)[::-1][:6]:
                    panel = np.concatenate(
                        [
                            figures.target_panel(inputs[b]),
                            figures.target_panel(canon[b]),
                            figures.strokes_panel(p.strokes[b], target=canon[b]),
                        ],
                        1,
                    )
                    figures.save_png(out / f"{style}_{int(idx[b])}_{per[b]:+d}.png", panel)
        rows.append(row)
        print(" ".join(f"{k}={v:.4f}" if isinstance(v, float) else f"{v}" for k, v in row.items()))


if __name__ == "__main__":
    main()
