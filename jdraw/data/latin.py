"""Latin letters and digits in the order and direction that schools teach them.

A per-glyph table, written for jdraw from the public description of manuscript
("ball and stick") handwriting that US schools teach (Zaner-Bloser's letter
formation: "pull down straight", "circle back", "slide right", "curve
forward"; see docs/latin.md). Each glyph is a list of strokes in writing
order, each stroke a polyline of lines and elliptic arcs in writing direction.

Conventions the table follows, as the model does:

* straight strokes go top to bottom and left to right; a letter's stem comes
  before its bars and bowls (E: stem, then bars top to bottom);
* circles ("circle back": a, c, d, e, g, o, q, C, G, O, 0, 6, 9) start at
  the top right and run counter-clockwise;
* bowls of B, D, P, R and of 2, 3 and 5 "curve forward" (clockwise);
* i and j are dotted, t and f crossed last; 5's top bar is drawn last;
* where the school model goes back up a line it has just drawn (n's "push
  up", b's and p's bowls), a bitmap cannot show it, so the table lifts the
  pen and starts the hump or bowl where it leaves the stem. 2, 3, 6, 8, 9, M,
  N, S and Z are one stroke each.

Units: a glyph's box is ``y`` 0 (cap and ascender line) to 1 (baseline), the
x-height at 0.45 and descenders to 1.4, ``y`` down; ``x`` from 0. Angles of
arcs are degrees with ``y`` down (0 right, 90 bottom, -90 top), so
increasing angle runs clockwise on the page.

:func:`load` gives a :class:`jdraw.data.kanji.KanjiSet` of the glyphs in the
100 x 100 canvas, so every KanjiVG pipeline (demonstrations, lines drawn other
ways, the tracer's training examples, evaluation) takes it as it is.
"""

from __future__ import annotations

import hashlib

import numpy as np

from jdraw.data.kanji import KanjiSet

CANVAS = 100


def _arc(cx, cy, rx, ry, a0, a1, step=6.0) -> np.ndarray:
    n = max(2, int(abs(a1 - a0) / step) + 1)
    a = np.radians(np.linspace(a0, a1, n))
    return np.stack([cx + rx * np.cos(a), cy + ry * np.sin(a)], 1)


def _line(*pts) -> np.ndarray:
    return np.asarray(pts, np.float64)


def _join(*parts) -> np.ndarray:
    """One stroke through ``parts`` in turn (each part starts where the last ended)."""
    return np.concatenate([np.asarray(p, np.float64) for p in parts])


def _dot(x, y) -> np.ndarray:
    return _line((x, y), (x, y + 0.05))


# Lower-case body: the bowl between the x-height (0.45) and the baseline (1).
_BOWL = (0.25, 0.725, 0.25, 0.275)
_TOP = (0.25, 0.5, 0.4, 0.5)  # a capital's round letter


def _o_then(stem_to: float) -> np.ndarray:
    """Circle back from the top right, round to the right, then the stem to ``stem_to``."""
    return _join(_arc(*_BOWL, -30, -360), _line((0.5, 0.725), (0.5, stem_to)))


def _hump(x0: float, w: float = 0.5) -> np.ndarray:
    """n's arch from its stem at ``x0``, over and down to the baseline."""
    return _join(_arc(x0 + w / 2, 0.7, w / 2, 0.22, -165, 0), _line((x0 + w, 0.7), (x0 + w, 1.0)))


GLYPHS: dict[str, list[np.ndarray]] = {
    # ---- capitals
    "A": [_line((0.35, 0), (0, 1)), _line((0.35, 0), (0.7, 1)), _line((0.13, 0.62), (0.57, 0.62))],
    "B": [
        _line((0, 0), (0, 1)),
        _join(
            _line((0, 0), (0.3, 0)),
            _arc(0.3, 0.25, 0.24, 0.25, -90, 90),
            _arc(0.33, 0.75, 0.27, 0.25, -90, 90),
            _line((0.33, 1), (0, 1)),
        ),
    ],
    "C": [_arc(0.4, 0.5, 0.38, 0.5, -40, -320)],
    "D": [
        _line((0, 0), (0, 1)),
        _join(
            _line((0, 0), (0.25, 0)), _arc(0.25, 0.5, 0.42, 0.5, -90, 90), _line((0.25, 1), (0, 1))
        ),
    ],
    "E": [
        _line((0, 0), (0, 1)),
        _line((0, 0), (0.6, 0)),
        _line((0, 0.5), (0.5, 0.5)),
        _line((0, 1), (0.6, 1)),
    ],
    "F": [_line((0, 0), (0, 1)), _line((0, 0), (0.6, 0)), _line((0, 0.5), (0.5, 0.5))],
    "G": [_join(_arc(0.4, 0.5, 0.38, 0.5, -40, -360), _line((0.78, 0.5), (0.45, 0.5)))],
    "H": [_line((0, 0), (0, 1)), _line((0.6, 0), (0.6, 1)), _line((0, 0.5), (0.6, 0.5))],
    "I": [_line((0.25, 0), (0.25, 1)), _line((0, 0), (0.5, 0)), _line((0, 1), (0.5, 1))],
    "J": [_join(_line((0.45, 0), (0.45, 0.75)), _arc(0.225, 0.75, 0.225, 0.25, 0, 180))],
    "K": [_line((0, 0), (0, 1)), _line((0.6, 0), (0.02, 0.55), (0.62, 1))],
    "L": [_line((0, 0), (0, 1), (0.55, 1))],
    "M": [_line((0, 1), (0, 0), (0.35, 0.65), (0.7, 0), (0.7, 1))],
    "N": [_line((0, 1), (0, 0), (0.6, 1), (0.6, 0))],
    "O": [_arc(*_TOP, -90, -450)],
    "P": [
        _line((0, 0), (0, 1)),
        _join(
            _line((0, 0), (0.3, 0)),
            _arc(0.3, 0.27, 0.27, 0.27, -90, 90),
            _line((0.3, 0.54), (0, 0.54)),
        ),
    ],
    "Q": [_arc(*_TOP, -90, -450), _line((0.45, 0.7), (0.85, 1.05))],
    "R": [
        _line((0, 0), (0, 1)),
        _join(
            _line((0, 0), (0.3, 0)),
            _arc(0.3, 0.27, 0.27, 0.27, -90, 90),
            _line((0.3, 0.54), (0.03, 0.54), (0.6, 1)),
        ),
    ],
    "S": [_join(_arc(0.35, 0.25, 0.3, 0.25, -30, -270), _arc(0.35, 0.75, 0.3, 0.25, -90, 150))],
    "T": [_line((0.3, 0), (0.3, 1)), _line((0, 0), (0.6, 0))],
    "U": [
        _join(
            _line((0, 0), (0, 0.7)), _arc(0.3, 0.7, 0.3, 0.3, 180, 0), _line((0.6, 0.7), (0.6, 0))
        )
    ],
    "V": [_line((0, 0), (0.32, 1), (0.64, 0))],
    "W": [_line((0, 0), (0.2, 1), (0.4, 0.3), (0.6, 1), (0.8, 0))],
    "X": [_line((0, 0), (0.6, 1)), _line((0.6, 0), (0, 1))],
    "Y": [_line((0, 0), (0.3, 0.5)), _line((0.6, 0), (0.3, 0.5), (0.3, 1))],
    "Z": [_line((0, 0), (0.6, 0), (0, 1), (0.6, 1))],
    # ---- small letters
    "a": [_o_then(1.0)],
    "b": [_line((0, 0), (0, 1)), _arc(*_BOWL, -160, 160)],
    "c": [_arc(*_BOWL, -40, -320)],
    "d": [_o_then(0.0)],
    "e": [_join(_line((0.02, 0.725), (0.5, 0.725)), _arc(*_BOWL, 0, -320))],
    "f": [
        _join(_arc(0.35, 0.15, 0.15, 0.15, -20, -180), _line((0.2, 0.15), (0.2, 1.0))),
        _line((0.02, 0.45), (0.4, 0.45)),
    ],
    "g": [_join(_o_then(1.25), _arc(0.3, 1.25, 0.2, 0.15, 0, 160))],
    "h": [_line((0, 0), (0, 1)), _hump(0)],
    "i": [_line((0.1, 0.45), (0.1, 1)), _dot(0.1, 0.22)],
    "j": [
        _join(_line((0.3, 0.45), (0.3, 1.25)), _arc(0.15, 1.25, 0.15, 0.15, 0, 150)),
        _dot(0.3, 0.22),
    ],
    "k": [_line((0, 0), (0, 1)), _line((0.45, 0.45), (0.02, 0.75), (0.48, 1))],
    "l": [_line((0, 0), (0, 1))],
    "m": [_line((0, 0.45), (0, 1)), _hump(0, 0.35), _hump(0.35, 0.35)],
    "n": [_line((0, 0.45), (0, 1)), _hump(0)],
    "o": [_arc(*_BOWL, -80, -440)],
    "p": [_line((0, 0.45), (0, 1.4)), _arc(*_BOWL, -160, 160)],
    "q": [_o_then(1.4)],
    "r": [_line((0, 0.45), (0, 1)), _arc(0.22, 0.68, 0.22, 0.2, -165, -40)],
    "s": [_join(_arc(0.25, 0.58, 0.2, 0.13, -30, -270), _arc(0.25, 0.86, 0.22, 0.14, -90, 150))],
    "t": [_line((0.15, 0.15), (0.15, 1)), _line((0, 0.45), (0.32, 0.45))],
    "u": [
        _join(
            _line((0, 0.45), (0, 0.8)),
            _arc(0.23, 0.8, 0.23, 0.2, 180, 0),
            _line((0.46, 0.8), (0.46, 0.45)),
        )
    ],
    "v": [_line((0, 0.45), (0.25, 1), (0.5, 0.45))],
    "w": [_line((0, 0.45), (0.17, 1), (0.35, 0.6), (0.53, 1), (0.7, 0.45))],
    "x": [_line((0, 0.45), (0.45, 1)), _line((0.45, 0.45), (0, 1))],
    "y": [_line((0, 0.45), (0.25, 1)), _line((0.5, 0.45), (0.1, 1.4))],
    "z": [_line((0, 0.45), (0.45, 0.45), (0, 1), (0.45, 1))],
    # ---- digits
    "0": [_arc(0.25, 0.5, 0.25, 0.5, -90, -450)],
    "1": [_line((0.2, 0), (0.2, 1))],
    "2": [_join(_arc(0.25, 0.28, 0.25, 0.26, -170, 20), _line((0.485, 0.37), (0, 1), (0.5, 1)))],
    "3": [_join(_arc(0.22, 0.26, 0.24, 0.24, -160, 90), _arc(0.22, 0.74, 0.26, 0.26, -90, 160))],
    "4": [_line((0.05, 0), (0, 0.65), (0.5, 0.65)), _line((0.38, 0), (0.38, 1))],
    "5": [
        _join(_line((0.05, 0), (0.1, 0.45)), _arc(0.25, 0.7, 0.25, 0.3, -125, 150)),
        _line((0.05, 0), (0.48, 0)),
    ],
    "6": [_join(_arc(0.25, 0.5, 0.25, 0.5, -60, -270), _arc(0.25, 0.75, 0.25, 0.25, 90, -200))],
    "7": [_line((0, 0), (0.5, 0), (0.15, 1))],
    "8": [
        _join(
            _arc(0.25, 0.25, 0.22, 0.25, -30, -270),
            _arc(0.25, 0.75, 0.25, 0.25, -90, 225),
            _line((0.073, 0.573), (0.47, 0.25)),
            _arc(0.25, 0.25, 0.22, 0.25, 0, -30),
        )
    ],
    "9": [_join(_arc(0.25, 0.3, 0.25, 0.3, -30, -360), _line((0.5, 0.3), (0.5, 1.0)))],
}


def _cubics(poly: np.ndarray) -> np.ndarray:
    """``[K, 4, 2]`` cubic control points of a polyline (each segment a straight cubic)."""
    p0, p1 = poly[:-1], poly[1:]
    keep = np.linalg.norm(p1 - p0, axis=1) > 1e-9
    p0, p1 = p0[keep], p1[keep]
    return np.stack([p0, p0 + (p1 - p0) / 3, p0 + 2 * (p1 - p0) / 3, p1], 1)


def to_canvas(strokes: list[np.ndarray], size: float = 80.0) -> list[np.ndarray]:
    """Glyph-unit polylines scaled to fill ``size`` px (the longer side), centred.

    A single glyph is planned as :func:`jdraw.plan_image` plans a small drawing:
    fitted to the canvas, as a KanjiVG character fills it.
    """
    pts = np.concatenate(strokes)
    lo, hi = pts.min(0), pts.max(0)
    s = size / max(1e-6, float((hi - lo).max()))
    centre = (lo + hi) / 2
    return [(p - centre) * s + (CANVAS - 1) / 2 for p in strokes]


def dev_glyphs() -> list[str]:
    """The glyphs held out of every training set: 14 of the 62, by a hash of each."""
    key = lambda g: hashlib.sha256(f"jdraw-latin-{ord(g):04x}".encode()).hexdigest()
    return sorted(sorted(GLYPHS, key=key)[:14])


def names(split: str) -> list[str]:
    """The glyphs of ``train`` or ``dev``."""
    dev = set(dev_glyphs())
    if split == "dev":
        return sorted(dev)
    if split == "train":
        return sorted(set(GLYPHS) - dev)
    raise ValueError(f"unknown Latin split {split!r}; expected 'train' or 'dev'")


def words(split: str = "train", n: int = 2000, seed: int = 0) -> KanjiSet:
    """``n`` printed words of 2-4 glyphs of ``split``, each written glyph by glyph, left to right.

    A word is its glyphs side by side on one baseline (a gap of 0.1-0.4 of the
    cap height between them, lower case sitting on the same baseline as capitals
    and digits), every glyph's strokes in the table's order and direction, and
    the glyphs in reading order: the demonstration that a line of separate
    letters is drawn letter after letter, which no single glyph shows. Fitted
    to the canvas as :func:`load`'s glyphs are (the longer side 80 px). Names
    are ``latin-word-<glyphs' code points>``; codes are the first glyph's.
    """
    chosen = names(split)
    rng = np.random.default_rng([seed, 11])
    out_names, codes, chars = [], [], []
    for _ in range(n):
        text = [chosen[k] for k in rng.integers(len(chosen), size=int(rng.integers(2, 5)))]
        x, strokes = 0.0, []
        for g in text:
            parts = [np.asarray(p, np.float64) for p in GLYPHS[g]]
            lo = min(float(p[:, 0].min()) for p in parts)
            hi = max(float(p[:, 0].max()) for p in parts)
            strokes += [p + (x - lo, 0.0) for p in parts]
            x += hi - lo + float(rng.uniform(0.1, 0.4))
        out_names.append("latin-word-" + "-".join(f"{ord(g):04x}" for g in text))
        codes.append(ord(text[0]))
        chars.append([_cubics(p) for p in to_canvas(strokes)])
    return KanjiSet.from_strokes(out_names, codes, chars)


def load(split: str | None = None) -> KanjiSet:
    """The glyphs (all, or a split's) as a :class:`KanjiSet` in the 100 x 100 canvas."""
    chosen = sorted(GLYPHS) if split is None else names(split)
    chars = [[_cubics(p) for p in to_canvas(GLYPHS[g])] for g in chosen]
    return KanjiSet.from_strokes(
        [f"latin-{ord(g):04x}" for g in chosen], [ord(g) for g in chosen], chars
    )
