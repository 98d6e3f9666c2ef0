"""Synthetic demonstrations: random pen-down curves with loops, cusps, crossings and retraces.

KanjiVG's strokes are nearly straight and meet other strokes at corners and
T-junctions; a cursive writer's line loops, reverses at cusps, crosses itself
at shallow angles and goes back over what it has just drawn. A scribble is a
drawing of one to three such curves, each one continuous pen-down motion, so
the local model learns to follow a line on through its own crossings and
turns, whatever the script. The curves that generate a drawing are its
demonstration; their order and direction carry no meaning, so scribbles train
the tracer (the local model), not the stroke ranker.

Each curve is one of:

* ``loops``: a prolate trochoid (the line of e, l and cursive joins), 1-4 loops;
* ``cusps``: a trochoid at or just below its cusp ratio (the top of r, m's arches);
* ``spline``: a smooth curve through 4-7 random points, which may cross itself;
* ``retrace``: a smooth curve that turns back over its last part and leaves it.

Curves are rotated, sheared and placed at random and kept :data:`MARGIN`
pixels inside the canvas. Nothing bounds a loop's size from below: a small
loop may close up on the canvas, as a small cursive e does.
"""

from __future__ import annotations

import numpy as np

from jdraw.data.cursive import to_cubics
from jdraw.data.kanji import CANVAS, KanjiSet

KINDS = ("loops", "cusps", "spline", "retrace")
MARGIN = 4.0  # canvas pixels kept free around a drawing


def _trochoid(rng: np.random.Generator, cusp: bool) -> np.ndarray:
    """``[n, 2]`` a trochoid ``(a t - b sin t, -c cos t)``; loops where ``b > a``."""
    a = rng.uniform(4.0, 9.0)
    b = a * (rng.uniform(0.85, 1.02) if cusp else rng.uniform(1.4, 2.6))
    c = rng.uniform(0.8, 2.2) * b
    turns = rng.uniform(1.2, 4.2)
    t = np.linspace(0.0, 2 * np.pi * turns, int(120 * turns)) + rng.uniform(0, 2 * np.pi)
    return np.stack([a * t - b * np.sin(t), -c * np.cos(t)], 1)


def _smooth(points: np.ndarray, per: int = 24) -> np.ndarray:
    """``[n, 2]`` a Catmull-Rom curve through ``points`` ``[k, 2]``."""
    p = np.concatenate([points[:1], points, points[-1:]])
    u = np.linspace(0.0, 1.0, per, endpoint=False)[:, None]
    out = []
    for i in range(1, len(p) - 2):
        p0, p1, p2, p3 = p[i - 1], p[i], p[i + 1], p[i + 2]
        out.append(
            0.5
            * (
                2 * p1
                + (p2 - p0) * u
                + (2 * p0 - 5 * p1 + 4 * p2 - p3) * u**2
                + (3 * p1 - p0 - 3 * p2 + p3) * u**3
            )
        )
    out.append(points[-1:])
    return np.concatenate(out)


def _spline(rng: np.random.Generator) -> np.ndarray:
    k = int(rng.integers(4, 8))
    return _smooth(rng.uniform(0.0, 60.0, (k, 2)))


def _retrace(rng: np.random.Generator) -> np.ndarray:
    """Out along a curve, back over its last ``20-70%``, then off in a new direction."""
    line = _smooth(rng.uniform(0.0, 50.0, (int(rng.integers(2, 5)), 2)))
    back = line[::-1][: max(2, int(len(line) * rng.uniform(0.2, 0.7)))]
    end = back[-1]
    away = _smooth(np.stack([end, end + rng.uniform(-30, 30, 2), end + rng.uniform(-40, 40, 2)]))
    return np.concatenate([line, back[1:], away[1:]])


def curve(kind: str, rng: np.random.Generator) -> np.ndarray:
    """``[n, 2]`` float one curve of ``kind`` (:data:`KINDS`), before it is placed."""
    if kind == "loops":
        p = _trochoid(rng, cusp=False)
    elif kind == "cusps":
        p = _trochoid(rng, cusp=True)
    elif kind == "spline":
        p = _spline(rng)
    elif kind == "retrace":
        p = _retrace(rng)
    else:
        raise ValueError(f"unknown scribble kind {kind!r}; expected one of {KINDS}")
    ang = rng.uniform(-np.pi, np.pi) if kind in ("spline", "retrace") else rng.uniform(-0.5, 0.5)
    shear = rng.uniform(-0.4, 0.4)
    rot = np.array([[np.cos(ang), -np.sin(ang)], [np.sin(ang), np.cos(ang)]])
    p = p @ np.array([[1.0, shear], [0.0, 1.0]]).T @ rot.T
    return p if rng.random() < 0.5 else p[::-1]


def drawing(rng: np.random.Generator) -> list[np.ndarray]:
    """One to three curves placed together on the canvas: ``[n, 2]`` polylines, canvas pixels.

    The drawing is scaled to fit inside :data:`MARGIN`, by 0.75-1 of the
    largest such scale; where that would shrink several curves below 0.6,
    the last curves are dropped until it does not (or one is left).
    """
    n = int(rng.choice([1, 2, 3], p=[0.5, 0.35, 0.15]))
    curves = [curve(KINDS[int(rng.integers(len(KINDS)))], rng) for _ in range(n)]
    curves = [c + rng.uniform(0.0, 40.0, 2) for c in curves]
    room = CANVAS - 1 - 2 * MARGIN
    while True:
        pts = np.concatenate(curves)
        lo, hi = pts.min(0), pts.max(0)
        scale = min(1.0, room / max(float(np.max(hi - lo)), 1e-9))
        if scale >= 0.6 or len(curves) == 1:
            break
        curves = curves[:-1]
    scale *= rng.uniform(0.75, 1.0)
    pts = np.concatenate(curves)
    lo, hi = pts.min(0), pts.max(0)
    size = (hi - lo) * scale
    offset = MARGIN + rng.uniform(0.0, 1.0, 2) * np.maximum(room - size, 0.0) - lo * scale
    return [np.clip(c * scale + offset, MARGIN / 2, CANVAS - 1 - MARGIN / 2) for c in curves]


def load(n: int = 3000, seed: int = 0) -> KanjiSet:
    """``n`` scribbles (:func:`drawing`) as a :class:`KanjiSet`, fixed by ``seed``.

    Each polyline segment is a straight cubic; ``keep_turns`` is set, so a
    retrace stays drawn twice in its demonstration.
    """
    rng = np.random.default_rng([seed, 0x5C81])
    chars = []
    for _ in range(n):
        polys = drawing(rng)
        chars.append([to_cubics(_thin(p)) for p in polys])
    names = [f"scribble-{i:05d}" for i in range(n)]
    return KanjiSet.from_strokes(names, np.arange(n), chars, keep_turns=True)


def _thin(p: np.ndarray, step: float = 1.5) -> np.ndarray:
    """Polyline ``p`` with points about ``step`` pixels apart (fewer cubics, same line)."""
    keep, last = [0], p[0]
    for i in range(1, len(p) - 1):
        if np.linalg.norm(p[i] - last) >= step:
            keep.append(i)
            last = p[i]
    keep.append(len(p) - 1)
    return p[keep]
