"""Right-to-left words: is each mark (a dot, an accent) drawn right after its letter body?

  python bench/rtl_marks.py [--script arabic] [--words 8] [--fonts val|eval] [--checkpoint BUNDLE]

Plans our words (``jdraw.data.fonts.WORDS``) set in the reading-direction detector's
validation fonts (``--fonts val``, the default, for choosing between planners) or its
held-out ones, 60-200 px high as ``bench/rtl_words.py`` draws them (the same words,
heights and seed), with the right-to-left hint. The word's pieces of ink are split
into letter bodies and marks as ``jdraw.tiling.layout.tall_boxes`` splits them, a
mark's body being the tall piece over or under its centre (as
``jdraw.tiling.layout`` orders regions), its letter the stroke of that body that
passes nearest it. Each planned stroke belongs to the piece most of its points lie
on. A mark counts as in place when its first stroke comes after its letter's stroke
with no stroke of another letter body between them. Prints the share in place and the mean
rank correlation of stroke order with x (``rho``, as ``bench/rtl_words.py``).
Needs the fonts (configs/reading_direction.py). About 20 s for 48 words.
"""

from __future__ import annotations

import argparse

import cv2
import numpy as np
from scipy.stats import spearmanr

from jdraw.data import fonts as F
from jdraw.tiling.layout import mark_bodies, piece_of, tall_boxes
from jdraw.tiling.plan_image import plan_image


def bodies_of_marks(ink: np.ndarray) -> tuple[np.ndarray, dict[int, int]]:
    """``(labels, {mark piece: body piece})`` of a ``bool`` image's 8-connected pieces."""
    n, labels, stats, _ = cv2.connectedComponentsWithStats(ink.astype(np.uint8), connectivity=8)
    b = np.array([[x, y, x + w - 1, y + h - 1] for x, y, w, h, _ in stats[1:]], float)
    if not len(b):
        return labels, {}
    found = mark_bodies(b, tall_boxes(b))  # a word: one text line
    return labels, {m + 1: body + 1 for m, body in found.items()}


def in_place(strokes, pieces: list[int], body_of: dict[int, int]) -> tuple[int, int]:
    """``(marks in place, marks drawn)`` of a plan whose ``strokes`` lie on ``pieces``.

    A mark's letter is the stroke of its body that passes nearest the mark's centre;
    the mark is in place when its first stroke comes after that stroke with no stroke
    of another letter body between them.
    """
    good = total = 0
    for mark, body in body_of.items():
        own = [u for u, p in enumerate(pieces) if p == body]
        if mark not in pieces or not own:
            continue
        t = pieces.index(mark)
        c = np.mean(np.concatenate([strokes[u] for u, p in enumerate(pieces) if p == mark]), 0)
        letter = own[int(np.argmin([np.abs(strokes[u] - c).sum(1).min() for u in own]))]
        between = [p for p in pieces[letter + 1 : t] if p not in body_of]
        good += letter < t and not between
        total += 1
    return good, total


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--script", default="arabic", choices=sorted(F.RTL_SCRIPTS))
    ap.add_argument("--words", type=int, default=8, help="words per font")
    ap.add_argument("--fonts", default="val", choices=("val", "eval"))
    ap.add_argument("--checkpoint", default=None, help="planner bundle (default: bundled)")
    a = ap.parse_args()
    table = F.DETECTOR_VAL if a.fonts == "val" else F.DETECTOR_EVAL
    rng = np.random.default_rng(0)  # bench/rtl_words.py's words and heights
    good = total = k = 0
    rhos = []
    for font in table[a.script]:
        for _ in range(a.words):
            text = F.WORDS[a.script][k % len(F.WORDS[a.script])]
            k += 1
            if not F.covers(font, text):
                continue
            img = F.render_word(text, font, int(rng.integers(60, 201)), direction="rtl")
            plan = plan_image(img, progress=False, direction="rtl", checkpoint=a.checkpoint)
            labels, body_of = bodies_of_marks(img < 128)
            g, t = in_place(plan.strokes, [piece_of(s, labels) for s in plan.strokes], body_of)
            good, total = good + g, total + t
            xs = [float(s[:, 0].mean()) for s in plan.strokes]
            if len(xs) >= 3:
                rhos.append(spearmanr(np.arange(len(xs)), xs)[0])
    print(
        f"{a.script}, {a.fonts} fonts, hint rtl: marks right after their body "
        f"{good}/{total} = {good / max(total, 1):.3f}; rho {np.mean(rhos):+.3f}"
    )


if __name__ == "__main__":
    main()
