"""Paths through a drawing's ink between two stroke ends (:mod:`jdraw.planner.joins`).

A join links two ends by the shortest path through the ink (:func:`ink_tree`,
:func:`between`); a long one only where it goes back over a line the pen draws
anyway (:func:`own_line`).
"""

from __future__ import annotations

from collections import deque

import numpy as np


def pixel(p) -> tuple[int, int]:
    """The pixel (x, y) nearest point ``p``."""
    return tuple(int(v) for v in np.rint(p))


def ink_tree(ink: np.ndarray, a, moves: int) -> dict:
    """Breadth-first tree of 8-connected ink pixels within ``moves`` moves of ``a``:
    ``{pixel: the pixel before it}``, so each path in it is a shortest one."""
    h, w = ink.shape
    a = pixel(a)
    prev = {a: a}
    todo = deque([(a, 0)])
    while todo:
        c, n = todo.popleft()
        if n == moves:
            continue
        for q in ((c[0] + dx, c[1] + dy) for dx in (-1, 0, 1) for dy in (-1, 0, 1)):
            if q not in prev and 0 <= q[0] < w and 0 <= q[1] < h and ink[q[1], q[0]]:
                prev[q] = c
                todo.append((q, n + 1))
    return prev


def between(prev: dict, a, b) -> np.ndarray | None:
    """The points strictly between ``a`` and ``b`` on the tree ``prev``'s path, if it has ``b``."""
    a, b = pixel(a), pixel(b)
    if b not in prev:
        return None
    out = [b]
    while out[-1] != a:
        out.append(prev[out[-1]])
    return np.asarray(out[-2:0:-1], np.float64).reshape(-1, 2)


OWN = 0.8  # share of a long link's points that must lie on one of its two strokes


def own_line(link, first, second, share: float = OWN) -> bool:
    """Whether ``share`` of the points of ``link`` lie on ``first``'s line or on
    ``second``'s (within a pixel of that stroke's pixels): the pen goes back over
    the line it has just drawn, or over the one it is about to draw."""
    from jdraw.planner.stroke_tokens import path_pixels

    q = np.rint(np.asarray(link, np.float64)).astype(np.int64).reshape(-1, 2)
    if not len(q):
        return True
    for s in (first, second):
        p = path_pixels(s)
        d = np.abs(q[:, None, :] - p[None, :, :]).max(-1).min(-1)
        if (d <= 1).mean() >= share:
            return True
    return False
