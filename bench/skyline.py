"""A long line drawing that ``plan_image`` takes for joined-up writing: what shrinking it costs.

  python bench/skyline.py [--seeds 5] [--png FILE]

Draws ``--seeds`` skylines (a ridge of 60 straight pieces 1,660 px long over eight
houses, one roof touching the ridge now and then, and a sun; a 4-px anti-aliased pen)
and plans each with ``plan_image`` three ways:

* ``as large as its lines allow``: ``jdraw.tiling.layout.JOINED_CORE`` set past any
  core, so the drawing is laid out as before 2026-12-07 (late);
* ``shrunk to the core, no floor``: ``SEPARATE`` set to 0, so the drawing is drawn as
  small as its ridge's core asks;
* ``default``: as shipped (shrunk, but its separate lines kept ``SEPARATE`` px apart).

It prints the scale, tiles, strokes per true stroke, the share of the drawn ink within
3 px of a planned stroke (recall) and of the planned lines within 3 px of the ink
(precision), means over the skylines. ``--png`` draws the first skyline's three plans.
"""

from __future__ import annotations

import argparse

import cv2
import numpy as np

from jdraw.evaluation import words
from jdraw.tiling import layout
from jdraw.tiling.plan_image import plan_image

TOL = 3  # px: a planned line this close to the ink covers it
PEN = 4


def skyline(seed: int) -> tuple[np.ndarray, list[np.ndarray]]:
    """``(image uint8 [420, 1700], strokes)``: dark ink on white, and its lines."""
    rng = np.random.default_rng(seed)
    x = np.linspace(20, 1680, 60)
    strokes = [np.stack([x, 250 + rng.uniform(-150, 60, 60)], 1)]
    for k in range(8):
        x0, y0 = 60 + 200 * k, 330
        box = [[x0, y0], [x0 + 60, y0], [x0 + 60, y0 + 60], [x0, y0 + 60], [x0, y0]]
        strokes += [
            np.array(box, float),
            np.array([[x0 - 5, y0], [x0 + 30, y0 - 30], [x0 + 65, y0]], float),
        ]
    t = np.linspace(0, 2 * np.pi, 50)
    strokes.append(np.stack([1500 + 40 * np.cos(t), 60 + 40 * np.sin(t)], 1))
    img = np.full((420, 1700), 255, np.uint8)
    for p in strokes:
        cv2.polylines(img, [np.round(p).astype(np.int32)], False, 0, PEN, cv2.LINE_AA)
    return img, strokes


def near(mask: np.ndarray) -> np.ndarray:
    k = np.ones((2 * TOL + 1, 2 * TOL + 1), np.uint8)
    return cv2.dilate(mask.astype(np.uint8), k) > 0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--png", default=None)
    a = ap.parse_args()
    ways = {
        "as large as its lines allow": dict(JOINED_CORE=float("inf")),
        "shrunk to the core, no floor": dict(SEPARATE=0.0),
        "default": {},
    }
    shipped = {k: getattr(layout, k) for k in ("JOINED_CORE", "SEPARATE")}
    print("| layout | scale | tiles | strokes / true | recall | precision |")
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    pictures = []
    for name, patch in ways.items():
        for k, v in {**shipped, **patch}.items():
            setattr(layout, k, v)
        rows = []
        for seed in range(a.seeds):
            img, true = skyline(seed)
            plan = plan_image(img, polarity="dark", progress=False)
            ink = words.stroke_images(true, img.shape).any(0)
            drawn = words.stroke_images(plan.strokes, img.shape).any(0)
            rows.append(
                (
                    plan.scale,
                    len(plan.tiles),
                    len(plan.strokes) / len(true),
                    (ink & near(drawn)).sum() / ink.sum(),
                    (drawn & near(ink)).sum() / max(drawn.sum(), 1),
                )
            )
            if seed == 0 and a.png:
                c = cv2.cvtColor(img, cv2.COLOR_GRAY2BGR) // 3 + 170
                for i, p in enumerate(plan.strokes):
                    hue = np.uint8([[[int(120 * i / max(len(plan.strokes) - 1, 1)), 255, 220]]])
                    col = tuple(int(v) for v in cv2.cvtColor(hue, cv2.COLOR_HSV2BGR)[0, 0])
                    cv2.polylines(c, [np.round(p).astype(np.int32)], False, col, 2, cv2.LINE_AA)
                cv2.putText(c, name, (10, 30), cv2.FONT_HERSHEY_SIMPLEX, 0.9, (0, 0, 0), 2)
                pictures.append(c)
        m = np.mean(rows, axis=0)
        print(
            f"| {name} | {m[0]:.3f} | {m[1]:.1f} | {m[2]:.2f} | {m[3]:.3f} | {m[4]:.3f} |",
            flush=True,
        )
    for k, v in shipped.items():
        setattr(layout, k, v)
    if pictures:
        cv2.imwrite(a.png, np.concatenate(pictures, 0))
        print(f"wrote {a.png}")


if __name__ == "__main__":
    main()
