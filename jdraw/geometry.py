"""Pixel geometry shared by demonstrations, the planner and the renderer.

Coordinates are ``(x, y)`` with ``x`` the column and ``y`` the row, so a point
``p`` lands on ``image[p[1], p[0]]``. Every place that turns a pen motion into
pixels (the demonstration builder, the planner's state machine inside ``jit``
and :func:`render_strokes`) uses the one line rule below, which is what makes
the pipeline lossless.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np

CANVAS = 100  # side of the square canvas the models see, in pixels

# Local pen moves: index k <-> (dx, dy) = (k % 5 - 2, k // 5 - 2); index 12 is (0, 0).
MOVES = np.stack(np.meshgrid(np.arange(-2, 3), np.arange(-2, 3)), -1).reshape(25, 2)
STAY = 12


def move_index(d):
    """Index ``[...]`` of moves ``d`` ``[..., 2]`` (dx, dy) in ``MOVES``; numpy or jnp."""
    if not isinstance(d, jax.Array):
        d = np.asarray(d)
    return (d[..., 1] + 2) * 5 + (d[..., 0] + 2)


def _div_round_half_toward_zero(m, n):
    """``m / n`` rounded half toward zero, exactly, for integers ``m`` and ``n > 0``.

    The one line rule: the k-th of ``n`` steps from ``a`` along ``d`` lands on
    ``a + round(k * d / n)``. Works on numpy and (inside ``jit``) jnp arrays.
    """
    xp = jnp if isinstance(m, jax.Array) or isinstance(n, jax.Array) else np
    return xp.sign(m) * ((2 * xp.abs(m) + n - 1) // (2 * n))


def midpoint(pen: jax.Array, d: jax.Array) -> jax.Array:
    """The pixel a local move ``d`` (``|d| <= 2``) skips (step 1 of 2 of the line rule)."""
    return pen + _div_round_half_toward_zero(d, 2)


def paint_segment(img: jax.Array, a: jax.Array, b: jax.Array) -> jax.Array:
    """``img`` with the pixels of :func:`segment_pixels` ``(a, b)`` set, inside ``jit``.

    ``img`` is ``bool [H, W]``; ``a`` and ``b`` lie on it.
    """
    d = b - a
    n = jnp.max(jnp.abs(d))
    k = jnp.arange(max(img.shape) + 1)[:, None]
    p = a[None] + _div_round_half_toward_zero(k * d[None], jnp.maximum(n, 1))
    p = jnp.where((k <= n), p, a[None])
    return img.at[p[:, 1], p[:, 0]].set(True)


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

    Each segment is :func:`segment_pixels`, all of them computed at once.
    Returns ``[m, 2]`` int64, consecutive duplicates removed.
    """
    pts = np.asarray(points, np.int64).reshape(-1, 2)
    if len(pts) < 2:
        return pts
    a, d = pts[:-1], np.diff(pts, axis=0)
    n = np.abs(d).max(1)  # pixels each segment steps (0: none)
    seg = np.repeat(np.arange(len(d)), n)
    k = np.arange(len(seg)) - np.repeat(np.cumsum(n) - n, n) + 1  # 1 .. n of its segment
    steps = a[seg] + _div_round_half_toward_zero(k[:, None] * d[seg], n[seg, None])
    path = np.concatenate([pts[:1], steps])
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
