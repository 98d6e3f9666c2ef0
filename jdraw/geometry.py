"""Pixel geometry shared by demonstrations, the planner and the renderer.

Coordinates are ``(x, y)`` with ``x`` the column and ``y`` the row, so a point
``p`` lands on ``image[p[1], p[0]]``. Every place that turns a pen motion into
pixels (the demonstration builder, the planner's state machine inside ``jit``
and :func:`render_strokes`) uses the one line rule below, which is what makes
the pipeline lossless.
"""

from __future__ import annotations

import numpy as np

CANVAS = 100


def _div_round_half_toward_zero(m: np.ndarray, n: int) -> np.ndarray:
    """``m / n`` rounded half toward zero, exactly, for integers ``m`` and ``n > 0``."""
    return np.sign(m) * ((2 * np.abs(m) + n - 1) // (2 * n))


def segment_pixels(a, b) -> np.ndarray:
    """Pixels inked by a pen-down move from ``a`` to ``b``, both included.

    ``n = max(|dx|, |dy|)`` pixels are stepped, each rounded half toward zero,
    so the path is 8-connected. For the local moves (``|dx|, |dy| <= 2``) the
    only intermediate pixel is ``a + sign(d) * (|d| // 2)``, the rule that
    :func:`jdraw.state.apply_move` uses inside ``jit``.

    Args:
      a: ``[2]`` int (x, y) start pixel.
      b: ``[2]`` int (x, y) end pixel.

    Returns:
      ``[n + 1, 2]`` int64 pixels from ``a`` to ``b``.
    """
    a = np.asarray(a, np.int64)
    b = np.asarray(b, np.int64)
    d = b - a
    n = int(np.max(np.abs(d)))
    if n == 0:
        return a[None]
    k = np.arange(n + 1)[:, None]
    return a[None] + _div_round_half_toward_zero(k * d[None], n)


def polyline_pixels(points) -> np.ndarray:
    """8-connected pixel path through integer ``points`` ``[n, 2]`` (x, y).

    Returns ``[m, 2]`` int64, consecutive duplicates removed.
    """
    pts = np.asarray(points, np.int64).reshape(-1, 2)
    if len(pts) == 0:
        return pts
    out = [pts[:1]]
    for a, b in zip(pts[:-1], pts[1:]):
        out.append(segment_pixels(a, b)[1:])
    path = np.concatenate(out)
    keep = np.ones(len(path), bool)
    keep[1:] = np.any(path[1:] != path[:-1], axis=1)
    return path[keep]


def render_strokes(strokes, shape: tuple[int, int] = (CANVAS, CANVAS)) -> np.ndarray:
    """Rasterise strokes drawn with the pen down.

    Args:
      strokes: sequence of ``[n, 2]`` (x, y) point arrays; floats are rounded
        to the nearest pixel centre.
      shape: ``(H, W)`` of the output.

    Returns:
      ``bool [H, W]``; pixels outside the frame are dropped.
    """
    img = np.zeros(shape, bool)
    for s in strokes:
        s = np.asarray(s, np.float64).reshape(-1, 2)
        if len(s) == 0:
            continue
        path = polyline_pixels(np.floor(s + 0.5))
        ok = (
            (path[:, 0] >= 0)
            & (path[:, 0] < shape[1])
            & (path[:, 1] >= 0)
            & (path[:, 1] < shape[0])
        )
        img[path[ok, 1], path[ok, 0]] = True
    return img
