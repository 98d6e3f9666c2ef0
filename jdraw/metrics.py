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


def _iou_matrix(drawn: np.ndarray, target: np.ndarray) -> np.ndarray:
    """``[D, S]`` IoU between stroke images ``drawn [D, H, W]`` and ``target [S, H, W]``."""
    d = drawn.reshape(len(drawn), -1).astype(np.float64)
    t = target.reshape(len(target), -1).astype(np.float64)
    inter = d @ t.T
    union = d.sum(1)[:, None] + t.sum(1)[None] - inter
    return np.where(union > 0, inter / np.maximum(union, 1), 1.0)


def stroke_accuracy(target_strokes, drawn_strokes) -> float:
    """Mean over drawn strokes of the best IoU with any target stroke.

    Args:
      target_strokes: ``bool [S, H, W]`` one image per target stroke.
      drawn_strokes: ``bool [D, H, W]`` one image per drawn stroke.

    Returns:
      The score in [0, 1]; 1.0 if neither has strokes, 0.0 if only one does.
    """
    t = np.asarray(target_strokes, bool)
    d = np.asarray(drawn_strokes, bool)
    if len(d) == 0 or len(t) == 0:
        return float(len(d) == len(t))
    return float(_iou_matrix(d, t).max(1).mean())


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
    t = np.asarray(target_strokes, bool)
    d = np.asarray(drawn_strokes, bool)
    if len(t) == 0 or len(d) == 0:
        return float("nan"), float("nan"), 0.0
    m = _iou_matrix(t, d)
    best = m.argmax(1)
    ok = m.max(1) >= iou
    idx = np.flatnonzero(ok)
    pairs = [(i, j) for a, i in enumerate(idx) for j in idx[a + 1 :]]
    order = np.mean([best[i] < best[j] for i, j in pairs]) if pairs else float("nan")
    dirs = []
    for i in idx:
        tp, dp = np.asarray(target_points[i], float), np.asarray(drawn_points[best[i]], float)
        dirs.append(np.linalg.norm(dp[0] - tp[0]) <= np.linalg.norm(dp[0] - tp[-1]))
    direction = float(np.mean(dirs)) if dirs else float("nan")
    return float(order), direction, float(ok.mean())
