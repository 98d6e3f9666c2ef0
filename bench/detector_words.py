"""Our words in the validation fonts read by reading-direction detectors, alone and averaged.

  PYTHONPATH=. python bench/detector_words.py DIR [DIR ...] [--words 24]

Each ``DIR`` holds a detector (``direction.json`` and ``direction.npz``). The
Hebrew, Arabic and Latin words of :data:`jdraw.data.fonts.WORDS` are set in the
validation fonts (:data:`jdraw.data.fonts.DETECTOR_VAL`), ``--words`` per font,
60-200 px high, as ``bench/rtl_words.py --fonts val`` sets them (its
``set_words``), and scored by every detector (ink-weighted mean window logit).
Each detector alone and the mean of all of them read a word right to left above
the threshold that the trainer's rule sets on its validation drawings
(``bench/detector_average.py``'s rows). Prints the fraction of each script's
words read right to left (for Latin, lower is better). Needs the fonts of
``configs/reading_direction.py``; about 25 s for two detectors on the 2-core CPU.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from detector_average import drawing_scores, score_row
from rtl_words import set_words

import configs.reading_direction as cfg_module
from jdraw.data import fonts as F
from jdraw.images import reading
from jdraw.images.prepare import prepare
from jdraw.train import reading as training


def word_scores(nets, script: str, per_font: int, seed: int = 0) -> np.ndarray:
    """``[words, nets]`` scores of ``script``'s words set in its validation fonts."""
    got = []
    for _, _, _, img in set_words(script, per_font, np.random.default_rng(seed), F.DETECTOR_VAL):
        x, ink = reading.drawing_windows(prepare(img), nets[0].width, nets[0].span)
        z = [reading.window_logits(n, x) for n in nets]
        got.append([reading.pool_scores(v, ink, "logit") for v in z])
    return np.array(got, np.float64).reshape(-1, len(nets))


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("detectors", nargs="+", help="folders of direction.json/.npz")
    p.add_argument("--words", type=int, default=24, help="words per validation font")
    a = p.parse_args(argv)
    t0 = time.perf_counter()
    nets = [reading.load(d) for d in a.detectors]
    cfg = cfg_module.get_config()
    _, val_fonts, _ = training._font_splits(cfg)
    val = drawing_scores(nets, val_fonts, cfg.val_words_per_font, 2, cfg)
    weights = {d: np.eye(len(nets))[i] for i, d in enumerate(a.detectors)}
    if len(nets) > 1:
        weights["mean of all"] = np.full(len(nets), 1.0 / len(nets))
    cuts = {name: score_row(val, {}, w)["threshold"] for name, w in weights.items()}
    words = {s: word_scores(nets, s, a.words) for s in ("arabic", "hebrew", "latin")}
    heads = " | ".join(f"{s} ({len(m)})" for s, m in words.items())
    print(f"| detector | threshold | {heads} |")
    print("| --- " * (2 + len(words)) + "|")
    for name, w in weights.items():
        cells = [f"{float(np.mean(m @ w > cuts[name])):.3f}" for m in words.values()]
        print(f"| {name} | {cuts[name]:.2f} | " + " | ".join(cells) + " |")
    print(f"\n({time.perf_counter() - t0:.0f} s)")


if __name__ == "__main__":
    main()
