"""The cursive-word dev set: words written with a marker, planned by :func:`jdraw.plan_image`.

  python -m jdraw.evaluation.words [--split val] [--n 40] [--checkpoint DIR] [--out FILE.json]

Each word of a split of :mod:`jdraw.data.cursive` is drawn ``word_height(word)``
pixels high (100-300, fixed by a hash of the word) with a 3-pixel anti-aliased
pen (OpenCV ``polylines``, ``LINE_AA``, dark ink on white), planned with
``plan_image``, and scored against the strokes a cursive writer makes
(:func:`jdraw.data.cursive.word_strokes`):

* ``stroke_ratio``: drawn strokes / written strokes, the mean over words, and
  ``stroke_ratio_total``, the sums' ratio;
* ``strokes_per_piece``: drawn strokes per connected piece of ink (8-connected
  components of the drawn image), the mean over words (``written_per_piece``
  is the writer's own figure);
* ``stroke_acc``: :func:`jdraw.evaluation.metrics.stroke_accuracy` with a
  2-pixel tolerance, written and planned strokes rasterised as 1-pixel lines
  at the input's resolution;
* ``order_all_pairs`` and ``direction``: as :func:`jdraw.evaluation.metrics.score`
  computes them from the same tolerant stroke IoU (each written stroke matched
  to the planned stroke of highest IoU, at least 0.5);
* ``untraced_ratio``: the writer's strokes cut wherever they go back over
  :data:`RETRACE_MIN` pixels or more of their own line (:func:`untraced_pieces`),
  per written stroke. A plan that never draws that much of a line twice needs at
  least that many strokes; the planner goes over drawn ink for at most 8 moves
  in a row (``jdraw.planner.loop.Limits``, up to 16 pixels).

Acceptance (issue 24): stroke_ratio <= 1.15, strokes_per_piece <= 1.5, stroke_acc >= 0.85.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import pathlib
import time

import cv2
import numpy as np

from jdraw import geometry
from jdraw.data import cursive
from jdraw.evaluation import metrics

PEN = 3  # pixels: OpenCV thickness of the anti-aliased marker
PAD = 12  # pixels of paper around the ink
TOL = 2  # pixels of tolerance in the stroke IoU
MIN_HEIGHT, MAX_HEIGHT = 100, 300
RETRACE_MIN = 16  # pixels of a line drawn again that count as a retrace
RETRACE_TOL = 1.5  # pixels: a point this near an earlier part of its stroke is drawn again
RETRACE_GAP = 8  # pixels along the stroke before a point that it is not compared with


def word_height(word: str) -> int:
    """Ink height in pixels for ``word``: 100-300, fixed by a hash of the word."""
    h = int(hashlib.sha256(f"jdraw-cursive-height-{word}".encode()).hexdigest(), 16)
    return MIN_HEIGHT + h % (MAX_HEIGHT - MIN_HEIGHT + 1)


def render_word(word: str, height: int) -> tuple[np.ndarray, list[np.ndarray]]:
    """``word`` written ``height`` pixels high (top of the ink to its bottom).

    Returns:
      ``(image uint8 [H, W]`` dark ink on white, ``written``: list of ``[n, 2]``
      float (x, y) strokes in the image's pixels, in writing order).
    """
    strokes = cursive.word_strokes(word)
    pts = np.concatenate(strokes)
    lo, hi = pts.min(0), pts.max(0)
    s = height / max(float(hi[1] - lo[1]), 1e-9)
    written = [(p - lo) * s + PAD for p in strokes]
    w = int(np.ceil((hi[0] - lo[0]) * s)) + 2 * PAD + 1
    img = np.full((height + 2 * PAD + 1, w), 255, np.uint8)
    shift = 4
    for p in written:
        q = np.round(p * (1 << shift)).astype(np.int32).reshape(-1, 1, 2)
        cv2.polylines(img, [q], False, 0, PEN, cv2.LINE_AA, shift)
    return img, written


def pieces(ink: np.ndarray) -> int:
    """Connected pieces (8-connected components) of ``bool [H, W]`` ink."""
    n, _ = cv2.connectedComponents(np.asarray(ink, np.uint8), connectivity=8)
    return int(n) - 1


def retraced(stroke: np.ndarray, tol: float = RETRACE_TOL, gap: int = RETRACE_GAP) -> np.ndarray:
    """``bool [n]``, ``stroke`` resampled every pixel: whether each point is on its earlier line.

    A point is on the earlier line when a point of the stroke at least ``gap``
    pixels before it (along the stroke) lies within ``tol`` pixels.
    """
    p = np.asarray(stroke, float)
    d = np.r_[0.0, np.cumsum(np.hypot(*np.diff(p, axis=0).T))]
    t = np.arange(0.0, d[-1] + 1e-9, 1.0)
    q = np.stack([np.interp(t, d, p[:, 0]), np.interp(t, d, p[:, 1])], 1)
    i, j = np.tril_indices(len(q), -(gap + 1))  # j <= i - gap - 1
    near = np.hypot(*(q[i] - q[j]).T) < tol
    out = np.zeros(len(q), bool)
    out[i[near]] = True
    return out


def untraced_pieces(stroke: np.ndarray, min_run: int = RETRACE_MIN) -> int:
    """Pieces of ``stroke`` left when each stretch drawn again (``min_run`` px+) is cut out."""
    again = retraced(stroke)
    edges = np.flatnonzero(np.diff(np.r_[0, again.astype(np.int8), 0]))
    cut = np.zeros(len(again), bool)
    for a, b in zip(edges[::2], edges[1::2]):
        if b - a >= min_run:
            cut[a:b] = True
    keep = ~cut
    return int(keep[0] + np.sum(keep[1:] & ~keep[:-1]))


def stroke_images(strokes, shape: tuple[int, int]) -> np.ndarray:
    """``bool [S, H, W]``: each ``[n, 2]`` (x, y) stroke as a 1-pixel line."""
    if not len(strokes):
        return np.zeros((0, *shape), bool)
    return np.stack([geometry.render_strokes([p], shape) for p in strokes])


def score_word(ink: np.ndarray, written, drawn, tol: int = TOL) -> dict:
    """Scores of one word: planned strokes ``drawn`` against the writer's ``written``.

    Args:
      ink: ``bool [H, W]`` the drawn word (for its connected pieces).
      written, drawn: lists of ``[n, 2]`` (x, y) strokes in ``ink``'s pixels, in order.
      tol: pixels of tolerance in the stroke IoU.
    """
    shape = np.shape(ink)
    t_img, d_img = stroke_images(written, shape), stroke_images(drawn, shape)
    n_pieces = pieces(ink)
    out = {
        "written": len(written),
        "drawn": len(drawn),
        "pieces": n_pieces,
        "stroke_ratio": len(drawn) / max(len(written), 1),
        "strokes_per_piece": len(drawn) / max(n_pieces, 1),
        "written_per_piece": len(written) / max(n_pieces, 1),
        "untraced_ratio": sum(untraced_pieces(p) for p in written) / max(len(written), 1),
        "stroke_acc": metrics.stroke_accuracy(t_img, d_img, tol),
    }
    if len(t_img) and len(d_img):
        m = metrics.stroke_iou(d_img, t_img, tol)  # [D, S]
        r = metrics._agreement(m.T, written, drawn, 0.5)
        out["order_all_pairs"], out["direction"] = r["order_all"], r["direction"]
    else:
        out["order_all_pairs"], out["direction"] = float(len(t_img) == len(d_img)), float("nan")
    return out


def evaluate_words(
    split: str = "val",
    n: int | None = 40,
    *,
    checkpoint=None,
    split_strokes: bool | None = None,
    progress: bool = True,
    retrace: bool = True,
    height: int | None = None,
) -> dict:
    """Plans the first ``n`` words of ``split`` (all if ``None``) and scores them.

    Args:
      checkpoint: passed to :func:`jdraw.plan_image` (``None``: the bundled default).
      split_strokes: ``plan_image``'s ``split=`` (the learned splitter; ``None``: as
        the checkpoint says).
      retrace: ``plan_image``'s ``retrace=`` (joins back over the line in joined-up
        writing).
      height: every word this many pixels high (``None``: :func:`word_height`'s 100-300).

    Returns:
      the means over words (module docstring), ``n``, ``seconds`` and ``words``:
      each word's height and scores.
    """
    from tqdm.auto import tqdm

    from jdraw.tiling.plan_image import plan_image

    words = cursive.split_words(split)[:n]
    per = []
    t0 = time.time()
    for w in tqdm(words, desc=f"cursive words ({split})", unit="word", disable=not progress):
        h = word_height(w) if height is None else int(height)
        img, written = render_word(w, h)
        plan = plan_image(
            img,
            checkpoint=checkpoint,
            polarity="dark",
            progress=False,
            split=split_strokes,
            retrace=retrace,
        )
        per.append({"word": w, "height": h, **score_word(img < 128, written, plan.strokes)})
    mean = lambda k: float(np.nanmean([p[k] for p in per])) if per else float("nan")  # noqa: E731
    return {
        "split": split,
        "n": len(per),
        "checkpoint": str(checkpoint) if checkpoint is not None else "bundled default",
        "retrace": retrace,
        "height": "100-300 by word" if height is None else int(height),
        "stroke_ratio": mean("stroke_ratio"),
        "stroke_ratio_total": sum(p["drawn"] for p in per) / max(sum(p["written"] for p in per), 1),
        "strokes_per_piece": mean("strokes_per_piece"),
        "written_per_piece": mean("written_per_piece"),
        "stroke_acc": mean("stroke_acc"),
        "order_all_pairs": mean("order_all_pairs"),
        "direction": mean("direction"),
        "untraced_ratio": mean("untraced_ratio"),
        "seconds": time.time() - t0,
        "words": per,
    }


def add_to_results(path, res: dict, key: str = "cursive_words") -> None:
    """Puts ``res`` under ``key`` in the JSON results file ``path`` (made if absent)."""
    path = pathlib.Path(path)
    data = json.loads(path.read_text()) if path.exists() else {}
    data[key] = res
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(data, indent=2) + "\n")


def summary(res: dict) -> str:
    return (
        f"cursive words ({res['split']}, n={res['n']}): drawn/written strokes "
        f"{res['stroke_ratio']:.3f} (total {res['stroke_ratio_total']:.3f}), strokes per piece "
        f"{res['strokes_per_piece']:.2f} (written {res['written_per_piece']:.2f}), stroke acc "
        f"{res['stroke_acc']:.4f} (tol {TOL} px), order all pairs {res['order_all_pairs']:.4f}, "
        f"direction {res['direction']:.4f}; the writer's strokes cut at their retraces "
        f"({RETRACE_MIN} px or more): {res['untraced_ratio']:.3f} per written stroke, "
        f"{res['seconds']:.0f} s"
    )


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--split", default="val", choices=("train", "val", "test"))
    p.add_argument("--n", type=int, default=40, help="first N words of the split (0: all)")
    p.add_argument("--checkpoint", default=None, help="bundle folder (default: bundled)")
    p.add_argument("--out", default=None, help="write the results here as JSON")
    p.add_argument(
        "--no-retrace",
        action="store_true",
        help="plan_image(retrace=False): no joins back over the line in joined-up writing",
    )
    p.add_argument(
        "--height", type=int, default=None, help="every word this many px high (default: 100-300)"
    )
    a = p.parse_args(argv)
    res = evaluate_words(
        a.split, a.n or None, checkpoint=a.checkpoint, retrace=not a.no_retrace, height=a.height
    )
    print(summary(res))
    if a.out:
        pathlib.Path(a.out).write_text(json.dumps(res, indent=2) + "\n")


if __name__ == "__main__":
    main()
