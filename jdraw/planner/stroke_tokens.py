"""Strokes as tokens of geometry, the stroke ranker's inputs (:mod:`jdraw.planner.ranker`).

A stroke's features: start, end, centre, box, heading and length, in the
character's box; a pair's relations: how two strokes touch, cross or hold
one another. Computed with numpy on the host from a plan's (or a
demonstration's) strokes.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from jdraw import geometry

STROKE_FEATURES = 20
PAIR_FEATURES = 3 * STROKE_FEATURES + 9


def path_pixels(points) -> np.ndarray:
    """``int64 [m, 2]`` 8-connected pixel path of a stroke's points (the one line rule)."""
    return geometry.polyline_pixels(np.rint(np.asarray(points, float)).astype(np.int64))


def stroke_masks(strokes, shape=(geometry.CANVAS, geometry.CANVAS)) -> np.ndarray:
    """``bool [S, H, W]`` one image per stroke (as :func:`jdraw.geometry.render_strokes`)."""
    out = np.zeros((len(strokes), *shape), bool)
    for k, s in enumerate(strokes):
        p = path_pixels(s)
        out[k, p[:, 1], p[:, 0]] = True
    return out


def stroke_features(path: np.ndarray, box: np.ndarray) -> np.ndarray:
    """``float32 [STROKE_FEATURES]`` of one stroke.

    Args:
      path: ``[m, 2]`` (x, y) pixel path in drawing order.
      box: ``[4]`` the character's ink box (x0, y0, x1, y1).
    """
    p = np.asarray(path, np.float64)
    s, e = p[0], p[-1]
    c = p.mean(0)
    lo, hi = p.min(0), p.max(0)
    n = len(p)
    k = min(3, n - 1)
    head = p[k] - p[0]
    tail = p[-1] - p[-1 - k]
    unit = lambda v: v / max(np.linalg.norm(v), 1e-6)
    size = np.maximum(box[2:] - box[:2], 1.0)
    rel = lambda q: (q - box[:2]) / size
    f = np.concatenate(
        [
            s / 100,
            e / 100,
            c / 100,
            lo / 100,
            hi / 100,
            unit(e - s),
            unit(head),
            unit(tail),
            [n / 100],
            rel(s),
            [np.linalg.norm(e - s) / max(n, 1)],
        ]
    )
    return f.astype(np.float32)


@dataclasses.dataclass
class Tokens:
    """A character's strokes as tokens.

    Attributes:
      paths: ``S`` pixel paths ``[m_i, 2]`` in their drawn direction.
      feats: ``float32 [S, STROKE_FEATURES]``.
      rfeats: ``float32 [S, STROKE_FEATURES]``, the same strokes reversed.
      rel: ``float32 [S, S, 9]`` relations of stroke pairs.
    """

    paths: list[np.ndarray]
    feats: np.ndarray
    rfeats: np.ndarray
    rel: np.ndarray


def _relations(paths: list[np.ndarray]) -> np.ndarray:
    """``float32 [S, S, 9]``: how stroke ``i`` relates to stroke ``j``."""
    n = len(paths)
    allp = np.concatenate(paths)
    h, w = int(allp[:, 1].max()) + 2, int(allp[:, 0].max()) + 2
    masks = np.zeros((n, h, w), bool)
    for k, p in enumerate(paths):
        masks[k, p[:, 1], p[:, 0]] = True
    near = masks.copy()  # 3x3 dilation
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            near[:, max(dy, 0) : h + min(dy, 0), max(dx, 0) : w + min(dx, 0)] |= masks[
                :, max(-dy, 0) : h + min(-dy, 0), max(-dx, 0) : w + min(-dx, 0)
            ]
    inner = masks.copy()
    for k, p in enumerate(paths):
        inner[k, p[0, 1], p[0, 0]] = inner[k, p[-1, 1], p[-1, 0]] = False
    m = masks.reshape(n, -1).astype(np.float32)
    touch = (m @ near.reshape(n, -1).T.astype(np.float32)) > 0
    cross = (inner.reshape(n, -1).astype(np.float32) @ m.T) > 0
    s = np.array([p[0] for p in paths])
    e = np.array([p[-1] for p in paths])
    s_on = near[:, s[:, 1], s[:, 0]].T  # [i, j]: i's start near j
    e_on = near[:, e[:, 1], e[:, 0]].T
    lo = np.array([p.min(0) for p in paths], float)
    hi = np.array([p.max(0) for p in paths], float)
    ov = np.maximum(0, np.minimum(hi[:, None], hi[None]) - np.maximum(lo[:, None], lo[None]) + 1)
    span = np.maximum(1, np.minimum((hi - lo)[:, None], (hi - lo)[None]) + 1)
    holds = np.all(lo[:, None] <= lo[None], -1) & np.all(hi[:, None] >= hi[None], -1)
    rel = np.stack(
        [
            touch,
            s_on,
            e_on,
            s_on.T,
            e_on.T,
            cross,
            ov[..., 0] / span[..., 0],
            ov[..., 1] / span[..., 1],
            holds,
        ],
        -1,
    ).astype(np.float32)
    rel[np.arange(n), np.arange(n)] = 0
    return rel


def tokens(strokes) -> Tokens:
    """Tokens of strokes given as lists of ``[n, 2]`` points (a plan's or a demo's)."""
    paths = [path_pixels(s) for s in strokes]
    if not paths:
        z = np.zeros((0, STROKE_FEATURES), np.float32)
        return Tokens([], z, z, np.zeros((0, 0, 9), np.float32))
    allp = np.concatenate(paths)
    box = np.concatenate([allp.min(0), allp.max(0)]).astype(np.float64)
    feats = np.stack([stroke_features(p, box) for p in paths])
    rfeats = np.stack([stroke_features(p[::-1], box) for p in paths])
    return Tokens(paths, feats, rfeats, _relations(paths))


def flipped(tk: Tokens, flip) -> Tokens:
    """The tokens of the same strokes with ``flip[i]`` ones drawn backwards.

    Equals :func:`tokens` of the reversed paths without recomputing it: a
    stroke's features and its reversed features trade places, and its
    "starts on" / "ends on" relations swap; the rest does not depend on
    direction.
    """
    f = np.asarray(flip, bool)
    rel = tk.rel.copy()
    rel[f, :, 1], rel[f, :, 2] = tk.rel[f, :, 2], tk.rel[f, :, 1]
    rel[:, f, 3], rel[:, f, 4] = tk.rel[:, f, 4], tk.rel[:, f, 3]
    return Tokens(
        [p[::-1] if fl else p for p, fl in zip(tk.paths, f)],
        np.where(f[:, None], tk.rfeats, tk.feats),
        np.where(f[:, None], tk.feats, tk.rfeats),
        rel,
    )


def pair_inputs(feats: np.ndarray, rel: np.ndarray, i, j) -> np.ndarray:
    """``float32 [K, PAIR_FEATURES]`` for index arrays ``i``, ``j`` of stroke pairs."""
    a, b = feats[i], feats[j]
    return np.concatenate([a, b, a - b, rel[i, j]], -1).astype(np.float32)


CONTEXT_FEATURES = 12


def _turning(path: np.ndarray, eps: float = 1.5) -> float:
    """Total absolute turning (radians) of a pixel path, simplified first.

    Douglas-Peucker to ``eps`` pixels (OpenCV) takes the pixel stairs out, so
    a straight line turns 0 and a circle about 2 pi.
    """
    import cv2

    q = cv2.approxPolyDP(np.asarray(path, np.int32).reshape(-1, 1, 2), eps, False)[:, 0]
    d = np.diff(q.astype(np.float64), axis=0)
    if len(d) < 2:
        return 0.0
    a = np.arctan2(d[:, 1], d[:, 0])
    t = np.diff(a)
    return float(np.abs((t + np.pi) % (2 * np.pi) - np.pi).sum())


def context(tk: Tokens) -> np.ndarray:
    """``float32 [CONTEXT_FEATURES]``: what kind of drawing the strokes make, as a whole.

    Read from the strokes alone and the same whichever way each is drawn: how
    many there are, the ink's box, their lengths, how much they turn, how many
    close on themselves, how straight they are, how often they cross and touch.
    A ranker given this beside each stroke and pair can learn that a drawing of
    few curved strokes follows other rules than one of many straight ones (the
    script is in the image, not in a flag).
    """
    paths = tk.paths
    n = len(paths)
    if n == 0:
        return np.zeros(CONTEXT_FEATURES, np.float32)
    allp = np.concatenate(paths)
    size = allp.max(0) - allp.min(0) + 1
    length = np.array([len(p) for p in paths], np.float64)
    turn = np.array([_turning(p) for p in paths]) / (2 * np.pi)
    chord = np.array([np.linalg.norm(p[-1] - p[0]) for p in paths])
    closed = (chord <= 3) & (length >= 12)
    straight = chord / np.maximum(length - 1, 1)
    off = ~np.eye(n, dtype=bool)
    pair_mean = lambda k: float(tk.rel[..., k][off].mean()) if n > 1 else 0.0
    f = [
        np.log1p(n) / 3,
        size[0] / 100,
        size[1] / 100,
        length.mean() / 100,
        length.max() / 100,
        turn.mean(),
        turn.max(),
        closed.mean(),
        straight.mean(),
        straight.min(),
        pair_mean(5),  # crosses
        pair_mean(0),  # touches
    ]
    return np.asarray(f, np.float32)
