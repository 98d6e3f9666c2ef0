"""Which of the writer's cursive strokes the plan draws as strokes of their own.

  python bench/cursive_marks.py [--split val] [--n 40] [--checkpoint BUNDLE] [--traced]

Plans the first ``--n`` words of a split as :mod:`jdraw.evaluation.words` draws them
(100-300 px high, a 3-px marker) with ``plan_image``, and sorts the writer's strokes:

* ``body``: a stroke at least a fifth as long as the word's longest (the word's line,
  a capital, a letter after a lift);
* ``cross``: a shorter one that crosses or touches another stroke (a t's or an x's
  cross, a tail started on its letter);
* ``dot``: a shorter one that touches none (an i's or a j's dot).

For each kind it prints how many there are, their mean best IoU with a planned stroke
(:func:`jdraw.evaluation.metrics.stroke_iou`, the dev set's 2-px tolerance) and the
share matched by one (IoU >= 0.5); a cross drawn as part of the word's line has no
planned stroke of its own and matches none. ``--traced`` plans with
``plan_image(split=False)``: the strokes as traced and stitched, before the splitter's
cuts and joins, to tell which stage drew a cross into the line. About 20 s for 40 words
on the 2-core CPU.
"""

from __future__ import annotations

import argparse

import numpy as np

from jdraw.data import cursive
from jdraw.evaluation import metrics
from jdraw.evaluation import words as W
from jdraw.tiling.plan_image import plan_image

BODY = 0.2  # of the word's longest stroke: a stroke at least this long is the body's
MATCH = 0.5  # IoU at which a planned stroke draws a written one


def kinds(written, shape) -> list[str]:
    """Each written stroke's kind (module docstring)."""
    lengths = np.array([np.linalg.norm(np.diff(p, axis=0), axis=1).sum() for p in written])
    lines = W.stroke_images(written, shape)
    out = []
    for k, n in enumerate(lengths):
        if n >= BODY * lengths.max():
            out.append("body")
            continue
        others = lines[np.arange(len(lines)) != k].any(0)
        out.append("cross" if (lines[k] & others).any() else "dot")
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--split", default="val", choices=("train", "val", "test"))
    ap.add_argument("--n", type=int, default=40)
    ap.add_argument("--checkpoint", default=None)
    ap.add_argument("--traced", action="store_true", help="no splitter: strokes as traced")
    a = ap.parse_args()
    best: dict[str, list[float]] = {"body": [], "cross": [], "dot": []}
    for w in cursive.split_words(a.split)[: a.n]:
        img, written = W.render_word(w, W.word_height(w))
        plan = plan_image(
            img,
            polarity="dark",
            progress=False,
            checkpoint=a.checkpoint,
            split=False if a.traced else None,
        )
        t = W.stroke_images(written, img.shape)
        d = W.stroke_images(plan.strokes, img.shape)
        iou = metrics.stroke_iou(d, t, W.TOL).max(0) if len(d) else np.zeros(len(t))
        for kind, b in zip(kinds(written, img.shape), iou):
            best[kind].append(float(b))
    stage = "as traced" if a.traced else "planned"
    print(
        f"| the writer's strokes ({a.split}, {a.n} words, {stage}) | n | mean best IoU | matched |"
    )
    print("| --- | ---: | ---: | ---: |")
    for kind, v in best.items():
        v = np.asarray(v)
        if len(v):
            print(f"| {kind} | {len(v)} | {v.mean():.3f} | {(v >= MATCH).mean():.2f} |")


if __name__ == "__main__":
    main()
