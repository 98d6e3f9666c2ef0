"""KanjiVG validation characters read by reading-direction detectors: how many read right to left.

  PYTHONPATH=. python bench/detector_kanji.py DIR [DIR ...] [--drawings 200] [--seed 7]

Each ``DIR`` holds a detector (``direction.json`` and ``direction.npz``). Each
drawing is one to three characters of the KanjiVG validation split side by
side, 0.8-3 times the canvas size, drawn with an anti-aliased pen 1-7 px wide;
every detector reads it (mean window logit against its own threshold). A kanji
read right to left would have its strokes ordered backwards, so the count
should be 0. No fonts needed; about 40 s for two detectors on the 2-core CPU.
"""

from __future__ import annotations

import argparse

import cv2
import numpy as np

from jdraw.data import kanji
from jdraw.images import reading
from jdraw.images.prepare import prepare


def draw(ks: kanji.KanjiSet, chars, scale: float, pen: int) -> np.ndarray:
    """``uint8 [H, W]``: characters ``chars`` of ``ks`` side by side, dark on white."""
    img = np.full((int(110 * scale), int((100 * len(chars) + 10) * scale)), 255, np.uint8)
    for j, i in enumerate(chars):
        for st in ks.strokes(i):
            pts = (kanji.sample_cubics(st) + (5 + 100 * j, 5)) * scale
            q = np.round(pts * 16).astype(np.int32).reshape(-1, 1, 2)
            cv2.polylines(img, [q], False, 0, pen, cv2.LINE_AA, 4)
    return img


def kanji_drawings(n: int, seed: int = 7):
    """Yields ``n`` drawings (``uint8 [H, W]``) of one to three KanjiVG validation
    characters side by side, 0.8-3 times the canvas size, pens 1-7 px wide."""
    ks = kanji.load(progress=False)
    idx = kanji.split_indices(ks, "val")
    rng = np.random.default_rng(seed)
    for _ in range(n):
        chars = rng.choice(idx, int(rng.integers(1, 4)))
        yield draw(ks, chars, float(rng.uniform(0.8, 3.0)), int(rng.integers(1, 8)))


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("detectors", nargs="+", help="folders of direction.json/.npz")
    p.add_argument("--drawings", type=int, default=200)
    p.add_argument("--seed", type=int, default=7)
    a = p.parse_args(argv)
    nets = [reading.load(d) for d in a.detectors]
    rtl = np.zeros(len(nets), int)
    for img in kanji_drawings(a.drawings, a.seed):
        prep = prepare(img)
        for j, net in enumerate(nets):
            rtl[j] += reading.detect(prep, net) == "rtl"
    for d, n in zip(a.detectors, rtl):
        print(f"{d}: {n} of {a.drawings} KanjiVG validation drawings read right to left")


if __name__ == "__main__":
    main()
