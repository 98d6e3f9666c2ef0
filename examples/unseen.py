"""Draws scripts and pictures the model never saw: Latin letters, cursive, line drawings.

  python examples/unseen.py [--checkpoint DIR] [--out docs/unseen.png]

Each input is a 100x100 one-pixel-line image made here (OpenCV's Hershey
fonts, thinned; simple geometric drawings). Prints pixel accuracy and the
number of strokes per input; writes target | strokes-by-order panels.
"""

import argparse

import cv2
import numpy as np
from skimage.morphology import skeletonize

import jdraw
from jdraw.io import figures


def text_image(s: str, font=cv2.FONT_HERSHEY_SIMPLEX, scale=2.2) -> np.ndarray:
    img = np.zeros((100, 100), np.uint8)
    (w, h), _ = cv2.getTextSize(s, font, scale, 1)
    cv2.putText(img, s, ((100 - w) // 2, (100 + h) // 2), font, scale, 255, 1, cv2.LINE_8)
    return skeletonize(img > 0)


def drawing(kind: str) -> np.ndarray:
    img = np.zeros((100, 100), np.uint8)
    if kind == "house":
        cv2.rectangle(img, (25, 45), (75, 85), 255, 1, cv2.LINE_8)
        cv2.line(img, (20, 48), (50, 18), 255, 1, cv2.LINE_8)
        cv2.line(img, (50, 18), (80, 48), 255, 1, cv2.LINE_8)
        cv2.rectangle(img, (44, 62), (56, 85), 255, 1, cv2.LINE_8)
    elif kind == "star":
        pts = [(50 + 38 * np.sin(a), 52 - 38 * np.cos(a)) for a in np.arange(5) * 4 * np.pi / 5]
        for a, b in zip(pts, pts[1:] + pts[:1]):
            cv2.line(img, tuple(map(int, a)), tuple(map(int, b)), 255, 1, cv2.LINE_8)
    elif kind == "spiral":
        t = np.linspace(0, 5 * np.pi, 400)
        p = np.stack([50 + 2.6 * t * np.cos(t), 50 + 2.6 * t * np.sin(t)], 1).astype(np.int32)
        cv2.polylines(img, [p], False, 255, 1, cv2.LINE_8)
    elif kind == "face":
        cv2.circle(img, (50, 50), 38, 255, 1, cv2.LINE_8)
        cv2.circle(img, (36, 40), 5, 255, 1, cv2.LINE_8)
        cv2.circle(img, (64, 40), 5, 255, 1, cv2.LINE_8)
        cv2.ellipse(img, (50, 58), (20, 14), 0, 20, 160, 255, 1, cv2.LINE_8)
    return skeletonize(img > 0)


def inputs():
    yield "A", text_image("A")
    yield "k", text_image("k")
    yield "Rx", text_image("Rx", scale=1.9)
    yield "hi (cursive)", text_image("hi", cv2.FONT_HERSHEY_SCRIPT_SIMPLEX, 2.4)
    yield "8", text_image("8")
    for k in ("house", "star", "spiral", "face"):
        yield k, drawing(k)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--checkpoint", default=None)
    ap.add_argument("--out", default="docs/unseen.png")
    args = ap.parse_args()
    names, imgs = zip(*inputs())
    plan = jdraw.plan(np.stack(imgs), checkpoint=args.checkpoint)
    drawn = jdraw.render(plan)
    tiles = []
    for name, img, strokes, d in zip(names, imgs, plan.strokes, drawn):
        print(f"{name:14s} pixel acc {jdraw.pixel_accuracy(img, d):.4f}  strokes {len(strokes)}")
        pair = np.concatenate(
            [
                figures.target_panel(img, 2),
                np.full((200, 3, 3), 160, np.uint8),
                figures.strokes_panel(strokes, scale=2),
            ],
            1,
        )
        tiles.append(np.pad(pair, ((4, 4), (4, 4), (0, 0)), constant_values=255))
    rows = [np.concatenate(tiles[i : i + 3], 1) for i in range(0, len(tiles) - len(tiles) % 3, 3)]
    figures.save_png(args.out, np.concatenate(rows, 0))
    print("wrote", args.out)


if __name__ == "__main__":
    main()
