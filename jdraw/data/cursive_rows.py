"""Rows of short cursive words, each finished, dotted and crossed before the next.

A cursive fragment (:func:`jdraw.data.cursive.fragments`) is one word's letters:
its dots and crosses come after its whole body, so a net that learns from
fragments alone learns "the marks come last". In a line of several words a
writer dots and crosses each word before starting the next; the same holds for
any script whose marks belong to a joined piece (Arabic's dots are drawn with
their piece, before the next one). A row here is 2-3 pieces of 1-3 letters from
different words of a split, side by side on one baseline, each piece written
as :func:`jdraw.data.cursive.word_strokes` writes it (body, then its marks),
the pieces left to right. At least one piece before the last has a mark, so
every row shows a mark drawn before ink to its right.
"""

from __future__ import annotations

import zlib

import numpy as np

from jdraw.data import cursive
from jdraw.data.kanji import KanjiSet

X_HEIGHT = 355.0  # font units: EMS Allure's o spans y 435-790 (y down)
GAP = (0.5, 1.0)  # the gap between two pieces, in x-heights


def _marked(piece: str) -> bool:
    return any(ch in cursive.MARKS for ch in piece)


def rows(split: str, n: int = 400, seed: int = 0, min_scale: float = cursive.MIN_SCALE) -> KanjiSet:
    """``n`` rows of cursive pieces of the words of ``split`` (module docstring).

    Each row fits the canvas as :func:`jdraw.data.cursive.fragments` do, at
    ``min_scale`` canvas pixels per font unit or more; rows that do not are drawn
    again.

    Returns:
      a :class:`jdraw.data.kanji.KanjiSet` (``keep_turns``, as the fragments), names
      like ``"it|on"``, strokes in writing order, control points in canvas pixels.
    """
    words = cursive.split_words(split)
    rng = np.random.default_rng([seed, zlib.crc32(f"rows-{split}".encode())])
    names, codes, chars = [], [], []
    tries = 0
    while len(names) < n:
        tries += 1
        if tries > 50 * n:
            raise ValueError(f"only {len(names)} of {n} rows of the {split!r} words fit")
        pieces = []
        for _ in range(int(rng.integers(2, 4))):
            w = words[int(rng.integers(len(words)))]
            k = int(rng.integers(1, min(3, len(w)) + 1))
            s = int(rng.integers(len(w) - k + 1))
            pieces.append(w[s : s + k])
        if not any(_marked(p) for p in pieces[:-1]):
            continue
        x, strokes = 0.0, []
        for p in pieces:
            part = cursive.word_strokes(p)
            lo = min(float(q[:, 0].min()) for q in part)
            hi = max(float(q[:, 0].max()) for q in part)
            strokes += [q + (x - lo, 0.0) for q in part]
            x += hi - lo + float(rng.uniform(*GAP)) * X_HEIGHT
        scale, offset = cursive.fit(strokes)
        if scale < min_scale:
            continue
        chars.append([cursive.to_cubics(q * scale + offset) for q in strokes if len(q) > 1])
        names.append("|".join(pieces))
        codes.append(len(codes))
    return KanjiSet.from_strokes(names, codes, chars, keep_turns=True)
