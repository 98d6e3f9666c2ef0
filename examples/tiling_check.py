"""Does a line that runs over many tiles come out as one motion?

    python examples/tiling_check.py                 # 6 random waves + a spiral, seed 7
    python examples/tiling_check.py --seed 11 --waves 10

Draws photo-like single lines (random length, height, number of humps, phase,
stroke width and ink polarity; and an Archimedean spiral) too big for one
canvas, plans them with :func:`jdraw.tiling.plan_image.plan_image` (the bundled
checkpoint) and prints, per image: tiles, strokes (1 is the goal), joins
across tile borders, unjoined border ends, pen lifts inside tiles removed,
precision / recall within 4 px of the true centreline, and pen-down length
over the true length (above 1 means the pen retraced).
"""

from __future__ import annotations

import argparse
import pathlib
import sys

import numpy as np

from jdraw.tiling import plan_image as tiling

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from tests.synthetic import centreline_scores, photo_like  # noqa: E402  (tests/synthetic.py)


def lines(seed: int, waves: int):
    """``(name, centrelines, shape, width, light_ink)`` test images."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, 1.0, 1000)
    for k in range(waves):
        length, amp = rng.uniform(500, 1400), rng.uniform(40, 150)
        periods, phase = rng.uniform(1.5, 5), rng.uniform(0, 6)
        y = amp + 40 + amp * np.sin(2 * np.pi * periods * t + phase)
        line = np.stack([40 + length * t, y], 1)
        shape = (int(2 * amp + 80), int(length + 80))
        yield f"wave {k}", [line], shape, rng.uniform(4, 12), bool(k % 2)
    a = np.linspace(0, 6 * np.pi, 1500)
    spiral = np.stack([400 + 12 * a * np.cos(a), 400 + 12 * a * np.sin(a)], 1)
    yield "spiral", [spiral], (800, 800), 6.0, False


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--waves", type=int, default=6)
    args = ap.parse_args()
    print("| image | px | tiles | strokes | border joins | breaks | lifts removed | P / R | len |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for name, ref, shape, width, light in lines(args.seed, args.waves):
        img = photo_like(ref, shape, width=width, light_ink=light, gradient=0.6, noise=0.08)
        r = tiling.plan_image(img, progress=False)
        p, rc = centreline_scores(r.strokes, ref, 4.0)
        true_len = sum(np.hypot(*np.diff(s, axis=0).T).sum() for s in ref)
        print(
            f"| {name} | {shape[1]}x{shape[0]} | {len(r.tiles)} | {len(r.strokes)} | "
            f"{r.border_joins} | {r.border_breaks} | {r.lift_joins} | {p:.3f} / {rc:.3f} | "
            f"{r.pen_down_length() / true_len:.3f} |",
            flush=True,
        )


if __name__ == "__main__":
    main()
