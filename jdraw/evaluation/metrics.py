"""The paper's metrics (§IV-A) and stroke order/direction agreement."""

from __future__ import annotations

import numpy as np


def pixel_accuracy(target, drawn) -> float:
    """``TP / (T + P - TP)`` of two ``bool [H, W]`` images (1.0 if both empty)."""
    t = np.asarray(target, bool)
    p = np.asarray(drawn, bool)
    tp = np.count_nonzero(t & p)
    denom = np.count_nonzero(t) + np.count_nonzero(p) - tp
    return 1.0 if denom == 0 else tp / denom


def stroke_iou(a, b, tol: int = 0) -> np.ndarray:
    """``[A, B]`` IoU of stroke images ``a [A, H, W]`` and ``b [B, H, W]``.

    With ``tol > 0`` a pixel counts as shared when the other side has ink
    within ``tol`` pixels (Chebyshev); the intersection is the mean of the two
    sides' counts, so two renderings of one line score about 1. ``tol=0`` is
    the exact IoU of the paper. Two empty images score 1.
    """
    a = np.asarray(a, bool)
    b = np.asarray(b, bool)
    af = a.reshape(len(a), -1).astype(np.float64)
    bf = b.reshape(len(b), -1).astype(np.float64)
    if tol:
        ad = np.stack([_dilate(x, tol) for x in a]).reshape(len(a), -1).astype(np.float64)
        bd = np.stack([_dilate(x, tol) for x in b]).reshape(len(b), -1).astype(np.float64)
        inter = (af @ bd.T + ad @ bf.T) / 2
    else:
        inter = af @ bf.T
    union = af.sum(1)[:, None] + bf.sum(1)[None] - inter
    return np.where(union > 0, inter / np.maximum(union, 1e-9), 1.0)


def stroke_accuracy(target_strokes, drawn_strokes, tol: int = 0) -> float:
    """Mean over drawn strokes of the best IoU with any target stroke.

    Args:
      target_strokes: ``bool [S, H, W]`` one image per target stroke.
      drawn_strokes: ``bool [D, H, W]`` one image per drawn stroke.
      tol: pixels of tolerance (:func:`stroke_iou`); 0 is the paper's metric.

    Returns:
      The score in [0, 1]; 1.0 if neither has strokes, 0.0 if only one does.
    """
    t = np.asarray(target_strokes, bool)
    d = np.asarray(drawn_strokes, bool)
    if len(d) == 0 or len(t) == 0:
        return float(len(d) == len(t))
    return float(stroke_iou(d, t, tol).max(1).mean())


def _agreement(m: np.ndarray, target_points, drawn_points, iou: float) -> dict:
    """Order and direction agreement from the ``[S, D]`` target x drawn IoU matrix.

    Each target stroke is matched to the drawn stroke of highest IoU, if at
    least ``iou``. Keys: ``order`` (pairs of matched targets drawn in the
    reference's relative order), ``direction`` (matched strokes whose drawn
    start is nearer the reference start than its end), ``matched``,
    ``order_all`` (over all pairs; an unmatched stroke counts against every
    pair it is in; one stroke: 1.0 if matched) and ``exact`` (as many strokes
    as the reference, all matched to distinct drawn strokes, in order).
    """
    n, n_drawn = m.shape
    if n == 0 or n_drawn == 0:
        nan = float("nan")
        return dict(
            order=nan, direction=nan, matched=0.0, order_all=float(n == n_drawn), exact=n == n_drawn
        )
    best = m.argmax(1)
    ok = m.max(1) >= iou
    idx = np.flatnonzero(ok)
    pairs = [(i, j) for a, i in enumerate(idx) for j in idx[a + 1 :]]
    order = float(np.mean([best[i] < best[j] for i, j in pairs])) if pairs else float("nan")
    dirs = []
    for i in idx if target_points is not None else ():
        tp, dp = np.asarray(target_points[i], float), np.asarray(drawn_points[best[i]], float)
        dirs.append(np.linalg.norm(dp[0] - tp[0]) <= np.linalg.norm(dp[0] - tp[-1]))
    if n == 1:
        order_all = float(ok[0])
    else:
        agree = sum(
            bool(ok[i] and ok[j] and best[i] < best[j]) for i in range(n) for j in range(i + 1, n)
        )
        order_all = agree / (n * (n - 1) / 2)
    return dict(
        order=order,
        direction=float(np.mean(dirs)) if dirs else float("nan"),
        matched=float(ok.mean()),
        order_all=order_all,
        exact=bool(n_drawn == n and ok.all() and np.all(np.diff(best) > 0)),
    )


def order_and_direction(target_strokes, target_points, drawn_strokes, drawn_points, iou=0.5):
    """Agreement of stroke order and direction with a reference.

    Each target stroke is matched to the drawn stroke of highest IoU (if
    above ``iou``). Order agreement is the fraction of pairs of matched target
    strokes drawn in the reference's relative order (Kendall-style); direction
    agreement is the fraction of matched strokes whose drawn start is nearer
    the reference start than the reference end.

    Args:
      target_strokes, drawn_strokes: ``bool [S, H, W]``, ``bool [D, H, W]``.
      target_points, drawn_points: lists of ``[n, 2]`` (x, y) points.

    Returns:
      ``(order, direction, matched fraction)``, NaN where undefined.
    """
    m = stroke_iou(target_strokes, drawn_strokes)
    r = _agreement(m, target_points, drawn_points, iou)
    return r["order"], r["direction"], r["matched"]


def order_all_pairs(target_strokes, drawn_strokes, iou=0.5) -> tuple[float, bool]:
    """Order agreement over all pairs of reference strokes, and exact order.

    Each target stroke is matched as in :func:`order_and_direction`; a pair
    agrees only if both strokes are matched and drawn in the reference's
    relative order, so an unmatched stroke counts against every pair it is in.

    Returns:
      ``(fraction of agreeing pairs, exact)``: ``exact`` is true when the plan
      has as many strokes as the reference, all matched to distinct drawn
      strokes, in the reference's order. With one reference stroke the
      fraction is 1.0 if it is matched.
    """
    r = _agreement(stroke_iou(target_strokes, drawn_strokes), None, None, iou)
    return r["order_all"], r["exact"]


def _dilate(img: np.ndarray, r: int) -> np.ndarray:
    import cv2

    k = np.ones((2 * r + 1, 2 * r + 1), np.uint8)
    return cv2.dilate(np.asarray(img, np.uint8), k).astype(bool)


def tolerant_pixel_accuracy(target, drawn, tol: int = 1) -> float:
    """Pixel accuracy with a tolerance of ``tol`` pixels (Chebyshev).

    A drawn pixel counts as right when ink lies within ``tol`` of it, and an
    ink pixel as covered when a drawn pixel lies within ``tol``:
    ``(right + covered) / (drawn + ink)``. For inputs drawn by another
    rasteriser or with a thick pen, whose centreline the planner draws.
    """
    t = np.asarray(target, bool)
    p = np.asarray(drawn, bool)
    n = np.count_nonzero(t) + np.count_nonzero(p)
    if n == 0:
        return 1.0
    right = np.count_nonzero(p & _dilate(t, tol))
    covered = np.count_nonzero(t & _dilate(p, tol))
    return (right + covered) / n


def score(demos, plan, inputs=None, tol: int = 0) -> dict:
    """Per-character metrics of a plan against demonstrations, averaged.

    Args:
      demos: the reference demonstrations (strokes in KanjiVG's order).
      plan: a :class:`jdraw.Plan` of the same characters.
      inputs: ``bool [B, H, W]`` images the plan was made from (default: the
        demonstrations' own targets). Pixel accuracy is against these.
      tol: 0 for the paper's exact metrics; ``tol`` pixels of tolerance
        (:func:`tolerant_pixel_accuracy`, :func:`stroke_iou`) for
        inputs drawn by another rasteriser or pen.

    Returns:
      pixel_acc, stroke_acc, order_agreement (matched pairs), order_all_pairs,
      exact_order, direction_agreement, stroke_ratio (drawn / true strokes),
      truncated, n.
    """
    from jdraw import geometry
    from jdraw.plans import render

    drawn = render(plan)
    keys = ("pixel", "stroke", "order", "order_all", "exact", "direction", "ratio")
    acc: dict[str, list] = {k: [] for k in keys}
    for b, (d, img, strokes) in enumerate(zip(demos, drawn, plan.strokes)):
        ink = d.target if inputs is None else np.asarray(inputs[b], bool)
        per = (
            np.stack([geometry.render_strokes([s]) for s in strokes])
            if strokes
            else np.zeros((0, *img.shape), bool)
        )
        tgt = d.stroke_images()
        pixel = tolerant_pixel_accuracy if tol else pixel_accuracy
        acc["pixel"].append(pixel(ink, img, tol) if tol else pixel(ink, img))
        m = stroke_iou(per, tgt, tol) if len(per) and len(tgt) else np.zeros((len(per), len(tgt)))
        acc["stroke"].append(
            float(m.max(1).mean()) if len(per) and len(tgt) else float(len(per) == len(tgt))
        )
        r = _agreement(m.T, d.strokes, strokes, 0.5)
        for k in ("order", "direction", "order_all", "exact"):
            acc[k].append(r[k])
        acc["ratio"].append(len(strokes) / max(len(d.strokes), 1))
    mean = lambda v: (
        float(np.nanmean(v)) if np.isfinite(np.asarray(v, float)).any() else float("nan")
    )
    return {
        "pixel_acc": mean(acc["pixel"]),
        "stroke_acc": mean(acc["stroke"]),
        "order_agreement": mean(acc["order"]),
        "order_all_pairs": mean(acc["order_all"]),
        "exact_order": mean(acc["exact"]),
        "direction_agreement": mean(acc["direction"]),
        "stroke_ratio": mean(acc["ratio"]),
        "truncated": float(np.mean(plan.truncated)),
        "n": len(demos),
    }
