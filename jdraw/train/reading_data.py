"""Drawings the reading-direction detector learns from, and the distortions of its batches.

:func:`sample` sets random letters of a script in a font (or joined-up
English, :func:`cursive_sample`), :func:`sketch` draws a random line sketch;
:func:`stretch` and :func:`augment` vary the windows cut from them
(:mod:`jdraw.train.reading` fits on them).
"""

from __future__ import annotations

import cv2
import numpy as np

from jdraw.data import fonts as F


def sketch(rng: np.random.Generator) -> np.ndarray:
    """``uint8 [H, W]`` a random line drawing (lines, circles, boxes, zigzags), dark on white."""
    h, w = (int(v) for v in rng.integers(120, 360, 2))
    img = np.full((h, w), 255, np.uint8)
    t = int(rng.integers(1, 7))
    for _ in range(int(rng.integers(2, 9))):
        kind = int(rng.integers(0, 4))
        p = (rng.random(2) * (w, h)).astype(int)
        if kind == 0:
            q = (rng.random(2) * (w, h)).astype(int)
            cv2.line(img, tuple(map(int, p)), tuple(map(int, q)), 0, t, cv2.LINE_AA)
        elif kind == 1:
            r = int(rng.integers(8, max(9, min(h, w) // 3)))
            cv2.circle(img, tuple(map(int, p)), r, 0, t, cv2.LINE_AA)
        elif kind == 2:
            q = (rng.random(2) * (w, h)).astype(int)
            cv2.rectangle(img, tuple(map(int, p)), tuple(map(int, q)), 0, t, cv2.LINE_AA)
        else:
            pts = (rng.random((int(rng.integers(3, 8)), 2)) * (w, h)).astype(np.int32)
            cv2.polylines(img, [pts], bool(rng.random() < 0.3), 0, t, cv2.LINE_AA)
    return img


def _slant(img: np.ndarray, shear: float) -> np.ndarray:
    """``img`` sheared horizontally (a handwriting slant), white fill."""
    h, w = img.shape
    m = np.array([[1.0, -shear, max(0.0, shear) * h], [0.0, 1.0, 0.0]])
    return cv2.warpAffine(
        img, m, (w + int(abs(shear) * h) + 1, h), borderValue=255, flags=cv2.INTER_LINEAR
    )


def cursive_sample(split: str, rng: np.random.Generator, cfg) -> np.ndarray:
    """Joined-up English (EMS Allure, :mod:`jdraw.data.cursive`): ``uint8 [H, W]``.

    One or two words of ``split``'s word list, written with a pen 1 px to a
    fifteenth of the height thick, sometimes slanted. Cursive Latin runs its
    letters together along a baseline as Arabic does; without it the detector
    read some joined script fonts right to left.
    """
    from jdraw.data import cursive

    words = cursive.split_words(split)
    n = 1 + int(rng.random() < cfg.two_words)
    text = [words[int(k)] for k in rng.integers(0, len(words), n)]
    strokes, x = [], 0.0
    for word in text:  # font units, y down; a space of 300 units between words
        got = cursive.word_strokes(word)
        lo = min(float(p[:, 0].min()) for p in got)
        strokes += [p + (x - lo, 0.0) for p in got]
        x = max(float(p[:, 0].max()) for p in strokes) + 300.0
    return _pen_drawing(strokes, rng, cfg, 15)


def _pen_drawing(strokes, rng: np.random.Generator, cfg, thinnest: int) -> np.ndarray:
    """``uint8 [H, W]``: ``strokes`` (x, y down) scaled to a random height, drawn with a
    pen 1 px to ``1 / thinnest`` of it thick (anti-aliased), sometimes slanted."""
    pts = np.concatenate(strokes)
    lo, hi = pts.min(0), pts.max(0)
    height = int(rng.integers(cfg.min_height, cfg.max_height + 1))
    k = height / max(float(hi[1] - lo[1]), 1e-9)
    pen = int(rng.integers(1, max(2, height // thinnest) + 1))
    pad = 8 + pen
    img = np.full((height + 2 * pad + 1, int(np.ceil((hi[0] - lo[0]) * k)) + 2 * pad + 1), 255)
    img = img.astype(np.uint8)
    for p in strokes:
        q = np.round(((p - lo) * k + pad) * 16).astype(np.int32).reshape(-1, 1, 2)
        cv2.polylines(img, [q], False, 0, pen, cv2.LINE_AA, 4)
    if rng.random() < cfg.slant:
        img = _slant(img, float(rng.uniform(-0.35, 0.35)))
    return img


def _wobble(p: np.ndarray, rng: np.random.Generator, amount: float) -> np.ndarray:
    """Polyline ``p [n, 2]`` resampled and bent by a smooth random wander of about ``amount``."""
    seg = np.hypot(*np.diff(p, axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    t = np.linspace(0.0, s[-1], max(2, int(s[-1] / 0.02) + 1))
    q = np.stack([np.interp(t, s, p[:, 0]), np.interp(t, s, p[:, 1])], 1)
    for _ in range(2):  # two slow waves along the stroke, each a random phase and heading
        f, ph = rng.uniform(0.5, 2.0), rng.uniform(0, 2 * np.pi, 2)
        q += amount * np.sin(2 * np.pi * f * t[:, None] + ph) * rng.normal(size=2) / 2
    return q


def print_sample(rng: np.random.Generator, cfg) -> np.ndarray:
    """Hand-printed Latin letters: ``uint8 [H, W]``, left to right.

    Random strings (mostly small letters) of the school glyphs that the planner
    trains on (:func:`jdraw.data.latin.names` ``("train")``), each glyph a little
    off in size and height, every stroke bent by a slow wander as a hand bends it,
    written with a pen 1 px to a twelfth of the height thick, sometimes slanted.
    Printed handwriting (DKG handwriting, a hand-drawn note) has the separate,
    uneven letters that fonts of Hebrew letters have; without it the detector
    read some of it right to left.
    """
    from jdraw.data import latin

    glyphs = latin.names("train")
    small = [g for g in glyphs if g.islower()]
    strokes, x = [], 0.0
    for _ in range(1 + int(rng.random() < cfg.two_words)):
        pool = small if rng.random() < 0.7 else glyphs
        for g in (pool[int(k)] for k in rng.integers(0, len(pool), int(rng.integers(3, 9)))):
            k, dy = rng.uniform(0.85, 1.15), rng.uniform(-0.04, 0.04)
            parts = [np.asarray(p, np.float64) * k + (0.0, dy + 1.0 - k) for p in latin.GLYPHS[g]]
            lo = min(float(p[:, 0].min()) for p in parts)
            hi = max(float(p[:, 0].max()) for p in parts)
            strokes += [_wobble(p + (x - lo, 0.0), rng, rng.uniform(0.0, 0.04)) for p in parts]
            x += hi - lo + float(rng.uniform(0.08, 0.35))
        x += 0.6  # a space between words
    # a dot (two equal points) is drawn as a short line, as the pen leaves it
    strokes = [p + ((0.0, 0.0), (0.0, 1e-3)) if _is_dot(p) else p for p in strokes]
    return _pen_drawing(strokes, rng, cfg, 12)


def _is_dot(p: np.ndarray) -> bool:
    return len(p) == 2 and bool(np.allclose(p[0], p[1]))


def sample(script: str, font: str, rng: np.random.Generator, cfg) -> np.ndarray:
    """One random training drawing of ``script`` set in ``font``: ``uint8 [H, W]``.

    ``script="cursive"``: :func:`cursive_sample`, ``font`` naming the word split;
    ``script="print"``: :func:`print_sample`; ``script="sketch"``: :func:`sketch`
    (``font`` unused by both).
    """
    if script == "sketch":
        return sketch(rng)
    if script == "print":
        return print_sample(rng, cfg)
    if script == "cursive":
        return cursive_sample(font, rng, cfg)
    words = [
        F.random_word(script, rng, font=font) for _ in range(1 + int(rng.random() < cfg.two_words))
    ]
    height = int(rng.integers(cfg.min_height, cfg.max_height + 1))
    pen = float(rng.uniform(0.01, 0.04)) if rng.random() < cfg.marker else 0.0
    direction = "rtl" if script in F.RTL_SCRIPTS else "ltr"
    img = F.render_word(" ".join(words), font, height, pen=pen, direction=direction)
    if rng.random() < cfg.slant:
        img = _slant(img, float(rng.uniform(-0.35, 0.35)))
    return img


def stretch(line: np.ndarray, factor: float) -> np.ndarray:
    """A line image (:func:`reading.line_images`) stretched ``factor`` times along x.

    Fonts and hands differ in how wide their letters are for their height; the
    detector should not learn a script from that alone.
    """
    h, w = line.shape
    out = cv2.resize(line, (max(int(round(w * factor)), 1), h), interpolation=cv2.INTER_AREA)
    return out


BEND_GRID = (3, 5)  # rows, columns of the random displacements that bend() smooths


def bend(v: np.ndarray, rng: np.random.Generator, sigma: float) -> np.ndarray:
    """A window ``v [H, W]`` bent by a smooth random displacement field.

    Displacements of ``sigma`` px (a normal's spread) on a coarse
    :data:`BEND_GRID` are interpolated over the window (bicubic), so neighbouring
    pixels move together: strokes stay lines, their curves and proportions change.
    """
    h, w = v.shape
    d = rng.normal(0.0, sigma, (2, *BEND_GRID)).astype(np.float32)
    dx = cv2.resize(d[0], (w, h), interpolation=cv2.INTER_CUBIC)
    dy = cv2.resize(d[1], (w, h), interpolation=cv2.INTER_CUBIC)
    mx, my = np.meshgrid(np.arange(w, dtype=np.float32), np.arange(h, dtype=np.float32))
    return cv2.remap(v, mx + dx, my + dy, cv2.INTER_LINEAR, borderValue=0.0)


def augment(
    xb: np.ndarray, rng: np.random.Generator, strength: float = 1.0, elastic: float = 0.0
) -> np.ndarray:
    """Windows ``xb [B, H, W]`` in [0, 1], each distorted as another font or hand might draw it.

    Per window: the ink thickened by a pixel across or along the line (half of
    them), the line's height off by up to 2 px; with ``strength`` > 0 also
    scaled in height by up to ``1 +- 0.15 * strength``, its baseline tilted
    (a vertical shear up to ``0.12 * strength``) and its letters slanted (a
    horizontal shear up to ``0.3 * strength``), all about the window's centre.
    With ``elastic`` > 0, half of the windows are also bent by a smooth random
    field (:func:`bend`, ``elastic`` px), as letters differ from font to font and
    hand to hand; with 0, no random number is drawn for it.
    """
    out = np.empty_like(xb)
    b, h, w = xb.shape
    for i in range(b):
        v = xb[i]
        if strength > 0:
            sy = 1.0 + strength * 0.15 * rng.uniform(-1, 1)
            tilt = strength * 0.12 * rng.uniform(-1, 1)
            slant = strength * 0.3 * rng.uniform(-1, 1)
            a = np.array([[1.0, slant], [tilt, sy]])
            c = np.array([w / 2.0, h / 2.0])
            m = np.concatenate([a, (c - a @ c)[:, None]], axis=1)
            v = cv2.warpAffine(v, m, (w, h), flags=cv2.INTER_LINEAR, borderValue=0.0)
        if elastic > 0 and rng.random() < 0.5:
            v = bend(v, rng, elastic)
        r = rng.random()
        if r < 0.25:
            v = np.maximum(v, np.roll(v, 1, axis=0))
        elif r < 0.5:
            v = np.maximum(v, np.roll(v, 1, axis=1))
        out[i] = np.roll(v, int(rng.integers(-2, 3)), axis=0)  # the line's height is not exact
    return out
