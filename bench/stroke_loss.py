"""Where the cursive words' stroke accuracy goes: planned strokes that merge, and pieces.

  python bench/stroke_loss.py [--split val] [--n 40] [--checkpoint BUNDLE]

Plans the first ``--n`` words of a split as :mod:`jdraw.evaluation.words` draws them
(100-300 px high, a 3-px marker) with ``plan_image``. The dev set's stroke accuracy is
a mean over each word's *planned* strokes of their best IoU with a written stroke
(:func:`jdraw.evaluation.metrics.stroke_accuracy`, 2-px tolerance), then over words, so
``1 - accuracy`` is a sum of each planned stroke's ``(1 - IoU) / strokes / words``.
This splits that sum by what the planned stroke is against the written stroke it
matches best:

* ``piece``: it draws under ``COVER`` of that written stroke (the writer's stroke drawn
  in pieces, or a few pixels left as a stroke of their own);
* ``merge``: it draws that stroke, but under ``COVER`` of its own pixels lie on it (it
  runs on into another: a t's cross drawn with the word's line);
* ``both``: neither; ``near``: both over ``COVER`` (the IoU's shortfall is the
  tolerance, a tail or a hook).

It also lists the planned strokes of IoU under ``WORST``. About 20 s for 40 words on the
2-core CPU.
"""

from __future__ import annotations

import argparse

from jdraw.data import cursive
from jdraw.evaluation import metrics
from jdraw.evaluation import words as W
from jdraw.tiling.plan_image import plan_image

COVER = 0.85  # share of a stroke's pixels within the tolerance of the other one
WORST = 0.3  # IoU under which a planned stroke is listed


def kind(own: float, theirs: float) -> str:
    """``own``: the planned stroke's share on the written one; ``theirs``: the written
    stroke's share that the planned one draws (module docstring)."""
    if own >= COVER and theirs >= COVER:
        return "near"
    if own < COVER and theirs < COVER:
        return "both"
    return "merge" if own < COVER else "piece"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--split", default="val", choices=("train", "val", "test"))
    ap.add_argument("--n", type=int, default=40)
    ap.add_argument("--checkpoint", default=None)
    a = ap.parse_args()
    tol = W.TOL
    loss = {"piece": 0.0, "merge": 0.0, "both": 0.0, "near": 0.0}
    count = dict.fromkeys(loss, 0)
    worst, words = [], cursive.split_words(a.split)[: a.n]
    for w in words:
        img, written = W.render_word(w, W.word_height(w))
        plan = plan_image(img, checkpoint=a.checkpoint, polarity="dark", progress=False)
        t, d = W.stroke_images(written, img.shape), W.stroke_images(plan.strokes, img.shape)
        if not len(d) or not len(t):
            continue
        iou = metrics.stroke_iou(d, t, tol)  # [D, S]
        t_near = [metrics._dilate(x, tol) for x in t]
        d_near = [metrics._dilate(x, tol) for x in d]
        for k in range(len(d)):
            b = int(iou[k].argmax())
            own = (d[k] & t_near[b]).sum() / max(d[k].sum(), 1)
            theirs = (t[b] & d_near[k]).sum() / max(t[b].sum(), 1)
            c = kind(own, theirs)
            loss[c] += (1.0 - iou[k, b]) / len(d) / len(words)
            count[c] += 1
            if iou[k, b] < WORST:
                worst.append((w, k, len(d), float(iou[k, b]), c))
    print(f"1 - stroke accuracy ({a.split}, {len(words)} words) by planned stroke:")
    print("| planned stroke | n | share of 1 - accuracy |")
    print("| --- | ---: | ---: |")
    for c in loss:
        print(f"| {c} | {count[c]} | {loss[c]:.4f} |")
    print(f"| all | {sum(count.values())} | {sum(loss.values()):.4f} |")
    print(f"planned strokes of IoU under {WORST}:")
    for w, k, n, v, c in worst:
        print(f"  {w}: stroke {k + 1} of {n}, IoU {v:.2f} ({c})")


if __name__ == "__main__":
    main()
