"""Reading-direction detectors scored alone and averaged, on the same drawings.

  PYTHONPATH=. python bench/detector_average.py DIR [DIR ...] [--out FILE]

Each ``DIR`` holds a detector (``direction.json`` and ``direction.npz``: the
package's ``jdraw/assets/reading`` or a trainer's ``out``). Every detector scores
the same drawings, those the trainer makes (:func:`jdraw.train.reading.scores`):
20 per validation font with seed 2 and 12 per held-out font with seed 1, each a
drawing's ink-weighted mean window logit. For each detector alone and for the mean
of all of them, the threshold is set as the trainer sets it (the highest score of
a left-to-right validation drawing, never below 0), and the bench prints the
right-to-left validation drawings read right to left and each script's held-out
accuracy. Needs the fonts of ``configs/reading_direction.py``.
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

import configs.reading_direction as cfg_module
from jdraw.data import fonts as F
from jdraw.images import reading
from jdraw.images.prepare import prepare
from jdraw.train import reading as training
from jdraw.train.reading_data import sample


def drawing_scores(nets, fonts_by_script: dict, per_font: int, seed: int, cfg) -> dict:
    """``{script: [drawings, nets]}`` ink-weighted mean window logits of the same drawings."""
    rng = np.random.default_rng(seed)
    out = {}
    for script, names in fonts_by_script.items():
        got = []
        for font in names:
            for _ in range(per_font):
                img = sample(script, font, rng, cfg)
                try:
                    x, ink = reading.drawing_windows(prepare(img), nets[0].width, nets[0].span)
                except ValueError:  # too little ink left to read
                    continue
                got.append(
                    [reading.pool_scores(reading.window_logits(n, x), ink, "logit") for n in nets]
                )
        out[script] = np.array(got, np.float64).reshape(-1, len(nets))
    return out


def score_row(val: dict, hel: dict, w: np.ndarray) -> dict:
    """The threshold set as the trainer sets it on ``val`` scores weighted by ``w``, the
    right-to-left validation drawings above it, and each held-out script's accuracy."""
    v = {s: list(m @ w) for s, m in val.items()}
    cut = training.choose_threshold(v, 0.0)
    row = {"threshold": cut, "val_rtl_recall": training._recall(v, cut)}
    for s, m in hel.items():
        row[s] = float(np.mean((m @ w > cut) == (s in F.RTL_SCRIPTS))) if len(m) else 0.0
    return row


def print_rows(rows: dict, first: str, scripts: list) -> None:
    """``rows`` (:func:`score_row`) as a markdown table, ``first`` naming its first column."""
    print(f"| {first} | threshold | val: rtl read rtl | " + " | ".join(scripts) + " |")
    print("| --- " * (3 + len(scripts)) + "|")
    for name, row in rows.items():
        cells = [f"{row[s]:.3f}" for s in scripts]
        print(f"| {name} | {row['threshold']:.2f} | {row['val_rtl_recall']:.3f} | "
              + " | ".join(cells) + " |")  # fmt: skip


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("detectors", nargs="+", help="folders of direction.json/.npz")
    p.add_argument("--out", default=None, help="write the table here as JSON")
    a = p.parse_args(argv)
    t0 = time.perf_counter()
    nets = [reading.load(d) for d in a.detectors]
    if len({(n.width, n.span) for n in nets}) > 1:
        raise SystemExit("the detectors read different windows (width or span); average like ones")
    cfg = cfg_module.get_config()
    _, val_fonts, held = training._font_splits(cfg)
    val = drawing_scores(nets, val_fonts, cfg.val_words_per_font, 2, cfg)
    hel = drawing_scores(nets, held, cfg.eval_words_per_font, 1, cfg)
    weights = {d: np.eye(len(nets))[i] for i, d in enumerate(a.detectors)}
    if len(nets) > 1:
        weights["mean of all"] = np.full(len(nets), 1.0 / len(nets))
    rows = {name: score_row(val, hel, w) for name, w in weights.items()}
    print_rows(rows, "detector", list(hel))
    print(f"\n({time.perf_counter() - t0:.0f} s)")
    if a.out:
        with open(a.out, "w") as f:
            json.dump({"detectors": a.detectors, "rows": rows}, f, indent=1)


if __name__ == "__main__":
    main()
