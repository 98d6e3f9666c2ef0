"""Makes the README gallery: example inputs, planned strokes, and the numbers.

    python examples/make_gallery.py            # ~1 min on a 2-core CPU
    python examples/make_gallery.py --sweep    # + sizes x polarities table, ~3 min

Writes the inputs to ``examples/images/`` (photo-like: thick anti-aliased
strokes, uneven light, noise; one is chalk on a board) and, for each, the
planned strokes coloured by drawing order (blue first, red last, a dot at
each start) to ``docs/gallery/``, plus an SVG of the word. Every input is
drawn from known centrelines, so the script prints how close the planned
strokes lie to them (precision / recall within 4 input pixels), with the
tile count, stroke count and wall time.

Planning uses :func:`jdraw.plan` (the bundled checkpoint, or seeded random
weights when none is bundled: stroke order and splitting then mean little,
coverage and geometry still hold).
"""

from __future__ import annotations

import argparse
import pathlib
import sys
import time

import cv2
import numpy as np

from jdraw.images.load import load_image
from jdraw.io import pictures
from jdraw.io.outputs import write_text
from jdraw.io.svg import to_svg
from jdraw.tiling import plan_image as tiling

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the photo-like inputs are the tests' (tests/synthetic.py)
from tests.synthetic import centreline_scores, photo_like, text_centrelines  # noqa: E402


def sketch_centrelines() -> tuple[list[np.ndarray], tuple[int, int]]:
    """A house under a sun, with a path: lines and circles."""
    t = np.linspace(0, 2 * np.pi, 120)
    lines = [
        np.array([[80, 330], [80, 200], [200, 110], [320, 200], [320, 330], [80, 330]], float),
        np.array([[170, 330], [170, 260], [230, 260], [230, 330]], float),  # door
        np.array([[105, 215], [150, 215], [150, 250], [105, 250], [105, 215]], float),  # window
        np.stack([470 + 45 * np.cos(t), 90 + 45 * np.sin(t)], 1),  # sun
        np.stack(
            [
                200 + 40 * np.sin(np.linspace(0, 3, 60)) * np.linspace(0, 1, 60),
                np.linspace(335, 390, 60),
            ],
            1,
        ),  # path
    ]
    for k in range(8):  # rays
        a = k * np.pi / 4
        lines.append(
            np.array(
                [
                    [470 + 60 * np.cos(a), 90 + 60 * np.sin(a)],
                    [470 + 85 * np.cos(a), 90 + 85 * np.sin(a)],
                ]
            )
        )
    return lines, (400, 580)


EXAMPLES = {
    # name: (centrelines and shape, stroke width px, light ink)
    "hello": (lambda: text_centrelines("hello", 5.0), 10, False),
    "sketch": (sketch_centrelines, 7, True),
    "sentence": (lambda: text_centrelines("The quick brown fox jumps", 2.2), 4, False),
}


SWEEP = [  # (text, font scale, stroke width px): the same hand from small to large
    ("hello world", 2.0, 4),
    ("minimum", 6.0, 13),
    ("jumps over", 10.0, 20),
]


def sweep(planner=None) -> None:
    """Precision / recall within 4 px on photo-like handwriting of several sizes."""
    print("\n| text | input px | stroke width px | ink | tiles | strokes | precision | recall |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    scores = []
    for text, font_scale, width in SWEEP:
        lines, shape = text_centrelines(text, font_scale)
        for light in (False, True):
            photo = photo_like(lines, shape, width=width, light_ink=light, gradient=0.6, noise=0.08)
            result = tiling.plan_image(photo, planner=planner, progress=False)
            p, r = centreline_scores(result.strokes, lines, 4.0)
            scores.append((p, r))
            h, w = shape
            ink = "light" if light else "dark"
            print(
                f"| {text} | {w}x{h} | {width} | {ink} | {len(result.tiles)} | "
                f"{len(result.strokes)} | {p:.3f} | {r:.3f} |"
            )
    s = np.array(scores)
    print(f"\nmin precision {s[:, 0].min():.3f}, min recall {s[:, 1].min():.3f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--only", nargs="*", choices=sorted(EXAMPLES), help="examples to make")
    ap.add_argument("--sweep", action="store_true", help="also measure sizes x polarities")
    args = ap.parse_args()
    img_dir, out_dir = ROOT / "examples" / "images", ROOT / "docs" / "gallery"
    img_dir.mkdir(parents=True, exist_ok=True)
    out_dir.mkdir(parents=True, exist_ok=True)
    print("| example | input px | stroke width px | tiles | strokes | precision | recall | time |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for name in args.only or EXAMPLES:
        make, width, light = EXAMPLES[name]
        lines, shape = make()
        photo = photo_like(lines, shape, width=width, light_ink=light, gradient=0.5, noise=0.06)
        path = img_dir / f"{name}.jpg"
        cv2.imwrite(str(path), photo, [cv2.IMWRITE_JPEG_QUALITY, 80])
        t0 = time.perf_counter()
        result = tiling.plan_image(load_image(path), progress=True)
        dt = time.perf_counter() - t0
        precision, recall = centreline_scores(result.strokes, lines, 4.0)
        scale = min(1.5, 700 / shape[1])
        pictures.draw_strokes_png(
            result.prepared.ink, result.strokes, out_dir / f"{name}.png", scale=scale
        )
        if name == "hello":
            svg = to_svg(result.strokes, shape, width_mm=120, stroke_width=3)
            write_text(svg, out_dir / f"{name}.svg")
        h, w = shape
        print(
            f"| {name} | {w}x{h} | {width} | {len(result.tiles)} | {len(result.strokes)} | "
            f"{precision:.3f} | {recall:.3f} | {dt:.1f} s |"
        )
    if args.sweep:
        sweep()


if __name__ == "__main__":
    main()
