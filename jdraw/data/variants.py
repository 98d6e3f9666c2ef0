"""Demonstrations on lines drawn other ways: another rasteriser, a thicker pen.

The planner sees canonical lines (:func:`jdraw.images.canonical.canonicalise`),
and canonical lines made from OpenCV's polylines or a 3-5 pixel pen are not
jdraw's own: corners are round where jdraw leaves the tick of one stroke
overshooting the one it meets, and junctions sit a pixel off. A model trained
only on jdraw's lines reads the ticks as "a stroke ends here" and, without
them, draws a box as one stroke. :func:`sample` draws a character in a random
style, canonicalises it, and lays each KanjiVG stroke onto the canonical
pixels (:func:`on_lines`), so the demonstration's order and stroke ends are
KanjiVG's while its ink is what the planner will see.
"""

from __future__ import annotations

from collections import deque

import cv2
import numpy as np

from jdraw.data import demos as D
from jdraw.data import kanji

CANVAS = D.CANVAS

# Style -> (OpenCV thickness, line type). "px3"/"px5" are 3- and 5-pixel-wide lines
# (OpenCV's thickness 2 draws 3 pixels across, 3 draws 5); "aa" is thresholded at half.
STYLES = {
    "cv2": (1, cv2.LINE_8),
    "aa": (1, cv2.LINE_AA),
    "px3": (2, cv2.LINE_8),
    "px5": (3, cv2.LINE_8),
}


def draw(ctrl: list[np.ndarray], style: str, step: float = 1.5) -> np.ndarray:
    """``bool [100, 100]``: strokes ``ctrl`` (cubics) drawn by OpenCV in ``style``.

    Polylines through points ``step`` pixels apart along the curves, as
    :func:`jdraw.evaluation.evaluate.rasterise` draws the test split.
    """
    if style not in STYLES:
        raise ValueError(f"unknown style {style!r}; expected one of {sorted(STYLES)}")
    thickness, line = STYLES[style]
    img = np.zeros((CANVAS, CANVAS), np.uint8)
    for c in ctrl:
        pts = np.rint(kanji.sample_cubics(c, step=step)).astype(np.int32)
        cv2.polylines(img, [pts.reshape(-1, 1, 2)], False, 255, thickness, line)
    return img >= 128


def _bfs(a: tuple, b: tuple, allowed: set) -> list[tuple] | None:
    """Shortest 8-connected pixel path from ``a`` to ``b`` through ``allowed``."""
    prev = {a: None}
    todo = deque([a])
    while todo:
        p = todo.popleft()
        if p == b:
            out = []
            while p is not None:
                out.append(p)
                p = prev[p]
            return out[::-1]
        for dy in (-1, 0, 1):
            for dx in (-1, 0, 1):
                q = (p[0] + dy, p[1] + dx)
                if q in allowed and q not in prev:
                    prev[q] = p
                    todo.append(q)
    return None


def _stroke_path(curve: np.ndarray, ink: np.ndarray, reach: float, every: float):
    """``[n, 2]`` int (x, y) path on ``ink`` that follows ``curve``, or None.

    The path keeps within ``reach`` pixels of the curve and passes, in
    order, the ink pixel nearest to a point of the curve every ``every``
    pixels of its length, so a loop or a stroke crossing itself is followed
    round, not cut short. Between two such points it may use the ink within
    ``reach`` of that part of the curve, so a stroke that goes back over its
    own line (a cursive landing, a retrace) finds its way back too.
    """
    ys, xs = np.nonzero(ink)
    pix = np.stack([xs, ys], 1).astype(np.float64)
    d = np.linalg.norm(pix[:, None, :] - curve[None, :, :], axis=2)  # [pixels, samples]
    near = d.min(1) <= reach
    if not near.any():
        return None
    pix, d = pix[near], d[near]
    along = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(curve, axis=0), axis=1))])
    n_way = max(1, int(np.ceil(along[-1] / every)))
    marks = np.linspace(0.0, along[-1], n_way + 1)
    way = []
    for w, m in enumerate(marks):
        k = int(np.argmin(np.abs(along - m)))
        j = int(np.argmin(d[:, k]))
        # A thick line's centreline stops short of the pen's cap: ends may lie further off.
        if d[j, k] > (2 * reach if w in (0, n_way) else reach):
            return None
        way.append(j)
    path: list[tuple] = [(int(pix[way[0], 1]), int(pix[way[0], 0]))]
    for i in range(n_way):
        lo, hi = marks[i] - every / 2, marks[i + 1] + every / 2
        part = (along >= lo) & (along <= hi)
        ok = d[:, part].min(1) <= reach
        allowed = {(int(y), int(x)) for x, y in pix[ok]}
        a = path[-1]
        b = (int(pix[way[i + 1], 1]), int(pix[way[i + 1], 0]))
        allowed |= {a, b}
        seg = _bfs(a, b, allowed)
        if seg is None:
            return None
        path.extend(seg[1:])
    yx = np.asarray(path, np.int64)
    return yx[:, ::-1]


def on_lines(
    ctrl: list[np.ndarray],
    ink: np.ndarray,
    reach: float = 2.5,
    spare: float = 0.04,
    keep_turns: bool = False,
):
    """The demonstration of strokes ``ctrl`` laid onto 1-pixel lines ``ink``, or None.

    Each stroke becomes a path on ``ink`` within ``reach`` pixels of its
    curve (:func:`_stroke_path`), cut into local moves as
    :func:`jdraw.data.demos.from_control_points` cuts its own. None when a
    stroke finds no such path or more than a ``spare`` fraction (and 3) of
    the ink pixels lie on no stroke's path (a line the strokes do not
    explain). The target is the union of the paths. ``keep_turns``: as
    :func:`jdraw.data.demos.clean_path`.
    """
    strokes, target = [], np.zeros(ink.shape, bool)
    for c in ctrl:
        curve = kanji.sample_cubics(c, step=0.5)
        p = _stroke_path(curve, ink, reach, every=8.0)
        if p is None:
            return None
        path = D.clean_path(p, keep_turns)
        strokes.append(D.decompose(path))
        target[path[:, 1], path[:, 0]] = True
    if np.count_nonzero(ink & ~target) > max(3, spare * np.count_nonzero(ink)):
        return None
    return D.Demo(strokes=strokes, target=target)


def weights(styles) -> dict[str, float] | None:
    """A config's ``styles`` (any mapping, or nothing) as ``{style: probability}`` or ``None``."""
    return {str(k): float(v) for k, v in styles.items()} if styles else None


def sample(ks: kanji.KanjiSet, i: int, rng: np.random.Generator, strength: float, styles) -> D.Demo:
    """Demonstration of character ``i``, augmented, in a style drawn from ``styles``.

    Args:
      styles: ``{style: probability}``; ``"clean"`` is jdraw's own rasteriser,
        the rest are :data:`STYLES`, canonicalised. A drawing whose strokes do
        not lay onto its canonical lines (:func:`on_lines`) falls back to clean.
        Strokes that go back over their line keep the way back when the set
        says so (``ks.keep_turns``).
    """
    from jdraw.images import canonical

    names = list(styles)
    p = np.asarray([styles[k] for k in names], float)
    style = names[int(rng.choice(len(names), p=p / p.sum()))]
    ctrl = ks.strokes(i)
    turns = bool(ks.keep_turns)
    if strength > 0:
        a, t = kanji.random_affine(rng, np.concatenate(ctrl), strength)
        ctrl = [c @ a.T + t for c in ctrl]
    if style == "clean":
        return D.from_control_points(ctrl, keep_turns=turns)
    drawn = draw(ctrl, style, step=float(rng.uniform(1.0, 3.0)))
    ink = canonical.canonicalise(drawn)
    d = on_lines(ctrl, ink, reach=3.5 if style == "px5" else 2.5, keep_turns=turns)
    if d is None:
        return D.from_control_points(ctrl, keep_turns=turns)
    d.drawn = drawn
    return d
