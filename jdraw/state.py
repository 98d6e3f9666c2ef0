"""The drawing state: one builder for training examples and for planning.

The model never sees ground truth: every image below is a function of the
target bitmap and of what the pen has done so far.

Local state (paper §III-A), channels last:
  0. ``X_env``: pixels already visited by the pen;
  1. ``X_con``: target pixels in the same 8-connected component of the target
     as the pen;
  2. ``X_dif``: target pixels not yet visited.

Global state (§III-B): ``X_loc`` (the pen, one-hot; all zero before the first
stroke), ``X_env``, ``X_last`` (pixels visited since the last global move) and
``X_dif``.
"""

from __future__ import annotations

import cv2
import jax
import jax.numpy as jnp
import numpy as np

from jdraw.geometry import MOVES, STAY, midpoint

LOCAL_CHANNELS = 3
GLOBAL_CHANNELS = 4


def component_labels(target: np.ndarray) -> np.ndarray:
    """8-connected component labels ``int32 [H, W]`` of ``target`` (0 = background)."""
    n, labels = cv2.connectedComponents(np.asarray(target, np.uint8), connectivity=8)
    del n
    return labels.astype(np.int32)


def apply_move(visited: jax.Array, pen: jax.Array, d: jax.Array, on=True):
    """Moves the pen down by ``d``; returns ``(visited, new_pen, n_new)``.

    Args:
      visited: ``bool [H, W]``.
      pen: ``int32 [2]`` (x, y).
      d: ``int32 [2]`` with ``|d| <= 2``.
      on: ``bool []``; when false nothing moves (``visited`` and ``pen`` come
        back as they were, ``n_new`` is 0).
    """
    mid = midpoint(pen, d)
    end = pen + d
    # Both pixels are read, then written in one update (when ``end == mid``
    # the two writes agree), so a batch of slots can update in place.
    xs, ys = jnp.stack([mid[0], end[0]]), jnp.stack([mid[1], end[1]])
    was = visited[ys, xs]
    n_new = (~was[0]).astype(jnp.int32) + (~was[1] & jnp.any(end != mid)).astype(jnp.int32)
    visited = visited.at[ys, xs].set(was | on)
    return visited, jnp.where(on, end, pen), jnp.where(on, n_new, 0)


def _local_channels(target, labels, visited, pen_label):
    con = target & (labels == pen_label)
    return jnp.stack([visited, con, target & ~visited], -1).astype(jnp.float32)


def local_state(target, labels, visited, pen) -> jax.Array:
    """Full local state ``float32 [H, W, 3]`` (env, con, dif)."""
    return _local_channels(target, labels, visited, labels[pen[1], pen[0]])


def _window_index(pen: jax.Array, size: int, shape):
    """Rows and columns (clipped onto the image) and ``inside`` of a window at ``pen``."""
    h = size // 2
    r = pen[1] - h + jnp.arange(size)
    c = pen[0] - h + jnp.arange(size)
    inside = ((r >= 0) & (r < shape[0]))[:, None] & ((c >= 0) & (c < shape[1]))[None, :]
    return jnp.clip(r, 0, shape[0] - 1)[:, None], jnp.clip(c, 0, shape[1] - 1)[None, :], inside


def _crop(img: jax.Array, pen: jax.Array, size: int, fill=0) -> jax.Array:
    """``[size, size]`` crop centred at ``pen``, zero (``fill``) outside the image.

    Read pixel by pixel, so a batch of slots never copies whole images.
    """
    r, c, inside = _window_index(pen, size, img.shape)
    return jnp.where(inside, img[r, c], jnp.asarray(fill, img.dtype))


def local_window(target, labels, visited, pen, size: int):
    """Local state on a ``size x size`` window centred on the pen.

    Equals ``local_state`` cropped at ``pen`` with zeros outside the image.

    Returns:
      ``(window float32 [size, size, 3], inside bool [size, size])``, where
      ``inside`` marks window pixels that lie on the canvas.
    """
    pen_label = labels[pen[1], pen[0]]
    t = _crop(target, pen, size)
    lab = _crop(labels, pen, size)
    v = _crop(visited, pen, size)
    inside = _window_index(pen, size, target.shape)[2]
    return _local_channels(t, lab, v, pen_label), inside


def global_state(target, visited, last, pen, has_pen) -> jax.Array:
    """Global state ``float32 [H, W, 4]`` (loc, env, last, dif)."""
    loc = jnp.zeros(target.shape, bool).at[pen[1], pen[0]].set(has_pen)
    return jnp.stack([loc, visited, last, target & ~visited], -1).astype(jnp.float32)


def allowed_moves(target: jax.Array, pen: jax.Array) -> jax.Array:
    """``bool [25]``: moves that keep the pen, and the pixel it skips, on ink.

    The stay move is never allowed: a pen-down step must go somewhere.
    """
    d = jnp.asarray(MOVES, jnp.int32)
    end = pen[None] + d
    mid = midpoint(pen[None], d)
    h, w = target.shape
    inb = (end[:, 0] >= 0) & (end[:, 0] < w) & (end[:, 1] >= 0) & (end[:, 1] < h)
    endc = jnp.clip(end, 0, jnp.array([w - 1, h - 1]))
    midc = jnp.clip(mid, 0, jnp.array([w - 1, h - 1]))
    ok = inb & target[endc[:, 1], endc[:, 0]] & target[midc[:, 1], midc[:, 0]]
    return ok.at[STAY].set(False)


def allowed_starts(target, visited, only_unvisited) -> jax.Array:
    """``bool [H, W]``: where a stroke may start.

    Unvisited ink, or visited ink touching unvisited ink (strokes often start
    on an earlier one). ``only_unvisited`` drops the latter, used after a
    stroke that added nothing so that planning always progresses.
    """
    dif = target & ~visited
    near = jax.lax.reduce_window(dif, False, jax.lax.bitwise_or, (3, 3), (1, 1), "SAME")
    return jnp.where(only_unvisited, dif, target & near)
