"""Draws cursive words' written strokes (jdraw.data.cursive) in order colours.

  python examples/cursive_words.py [--out docs/cursive_words.png]

Each word's strokes as a writer makes them (EMS Allure, joined where the
glyphs meet, i dots and t/x crosses after the word), coloured from blue (first)
to red (last), a dot at each stroke's start and an arrowhead halfway along it.
"""

import argparse

import cv2
import numpy as np

from jdraw.data import cursive
from jdraw.io import pictures

WORDS = ("hello", "minute", "bridge", "quick", "Anna", "dozen")


def word_panel(word: str, scale: float = 0.15, pad: int = 18) -> np.ndarray:
    """``uint8 [h, w, 3]`` RGB picture of ``word``'s written strokes, ``scale`` px per font unit."""
    strokes = cursive.word_strokes(word)
    pts = np.concatenate(strokes)
    lo, hi = pts.min(0), pts.max(0)
    s = scale
    lines = [(p - lo) * s + pad for p in strokes]
    shape = (
        int(np.ceil((hi[1] - lo[1]) * s)) + 2 * pad,
        int(np.ceil((hi[0] - lo[0]) * s)) + 2 * pad,
    )
    img = pictures.draw_strokes_png(None, lines, shape=shape, scale=1.0, line_width=3)
    for p, c in zip(lines, pictures.order_colours(len(lines))):
        if len(p) > 2:  # an arrow along the middle segment shows the direction
            m = len(p) // 2
            a, b = np.round(p[m - 1]).astype(int), np.round(p[m]).astype(int)
            cv2.arrowedLine(
                img,
                tuple(a),
                tuple(b),
                tuple(int(v) for v in c),
                1,
                cv2.LINE_AA,
                0,
                8 / max(1, np.hypot(*(b - a))),
            )
    label = f"{word}: {len(strokes)} strokes"
    cv2.putText(img, label, (4, 14), cv2.FONT_HERSHEY_SIMPLEX, 0.45, (60, 60, 60), 1, cv2.LINE_AA)
    return img


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default="docs/cursive_words.png")
    a = p.parse_args()
    panels = [word_panel(w) for w in WORDS]
    width = max(x.shape[1] for x in panels[::2]) + max(x.shape[1] for x in panels[1::2])
    rows = []
    for left, right in zip(panels[::2], panels[1::2]):
        h = max(left.shape[0], right.shape[0])
        row = np.full((h, width, 3), 255, np.uint8)
        row[: left.shape[0], : left.shape[1]] = left
        row[: right.shape[0], width - right.shape[1] :] = right
        rows.append(row)
    img = np.vstack(rows)
    cv2.imwrite(a.out, cv2.cvtColor(img, cv2.COLOR_RGB2BGR))
    print(f"wrote {a.out}: " + ", ".join(f"{w} {len(cursive.word_strokes(w))}" for w in WORDS))


if __name__ == "__main__":
    main()
