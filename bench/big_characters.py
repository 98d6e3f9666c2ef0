"""KanjiVG characters drawn large, through ``jdraw.plan_image``: the tiled pipeline on kanji.

  python bench/big_characters.py [--n 60] [--sizes 600x5,600x14,900x3] [--split val] [--width-scale]

Each of the first ``n`` characters of a KanjiVG split is drawn ``SIZE`` px
across with an ``PEN``-px anti-aliased OpenCV pen, large enough that
``plan_image`` tiles it instead of fitting it to one canvas, planned with the
bundled default and scored as the cursive words are
(:func:`jdraw.evaluation.words.score_word`, tolerance half the pen, at least
2 px): drawn / true strokes, stroke accuracy, order over all pairs, direction.
``--width-scale`` draws tiled drawings at ``min_gap / stroke width``, the
scale ``jdraw.tiling.layout.choose_scale`` used before 2026-12-04, for the
comparison in docs/scripts.md.
"""

from __future__ import annotations

import argparse
import time

import cv2
import numpy as np

from jdraw.data import demos, kanji
from jdraw.evaluation import words
from jdraw.tiling.plan_image import plan_image


def drawing(ks: kanji.KanjiSet, i: int, size: int, pen: int, pad: int = 10):
    """``(image uint8 [H, W], strokes)``: character ``i`` drawn ``size`` px across."""
    d = demos.from_control_points(ks.strokes(i))
    strokes = [np.asarray(s, float) * (size / 100.0) + pad for s in d.strokes]
    img = np.full((size + 2 * pad, size + 2 * pad), 255, np.uint8)
    for p in strokes:
        q = np.round(p * 16).astype(np.int32).reshape(-1, 1, 2)
        cv2.polylines(img, [q], False, 0, pen, cv2.LINE_AA, 4)
    return img, strokes


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=60)
    ap.add_argument("--split", default="val")
    ap.add_argument("--sizes", default="600x5,600x14,900x3", help="SIZExPEN, comma-separated")
    ap.add_argument("--width-scale", action="store_true", help="the scale rule before 2026-12-04")
    args = ap.parse_args()
    if args.width_scale:
        from jdraw.images import prepare

        prepare.Prepared.gap = property(lambda self: self.width)
    ks = kanji.load(progress=False)
    idx = kanji.split_indices(ks, args.split)[: args.n]
    print(f"scale rule: {'min_gap / width' if args.width_scale else 'min_gap / gap'}")
    print(
        "| size / pen (px) | characters | drawn / true | stroke acc | order, all pairs "
        "| direction | s |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for spec in args.sizes.split(","):
        size, pen = (int(v) for v in spec.split("x"))
        t0, per = time.perf_counter(), []
        for i in idx:
            img, strokes = drawing(ks, int(i), size, pen)
            plan = plan_image(img, polarity="dark", progress=False)
            per.append(words.score_word(img < 128, strokes, plan.strokes, tol=max(2, pen // 2)))
        m = {k: float(np.nanmean([p[k] for p in per])) for k in per[0]}
        print(
            f"| {size} / {pen} | {len(per)} | {m['stroke_ratio']:.3f} | {m['stroke_acc']:.3f} | "
            f"{m['order_all_pairs']:.3f} | {m['direction']:.3f} | {time.perf_counter() - t0:.0f} |",
            flush=True,
        )


if __name__ == "__main__":
    main()
