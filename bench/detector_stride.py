"""The reading-direction detector read with its windows closer together.

  PYTHONPATH=. python bench/detector_stride.py [--strides 16,8,4] [--detector DIR] [--out FILE]

A short word gives the detector one to three windows (``jdraw.images.reading.STRIDE``
px apart along the line), and its score is their mean logit, which depends on where
the windows happen to fall on the letters. Windows closer together average over more
placements of the same ink. For each stride, the bench scores the drawings the
trainer makes (:func:`jdraw.train.reading.scores`' fonts: 20 per validation font with
seed 2, 12 per held-out font with seed 1, as ``bench/detector_average.py``), sets the
threshold as the trainer does (the highest score of a left-to-right validation
drawing, never below 0), and prints the right-to-left validation drawings read right
to left and each script's held-out accuracy at that threshold. Needs the fonts of
``configs/reading_direction.py``.
"""

from __future__ import annotations

import argparse
import json
import pathlib
import sys
import time

import numpy as np

import configs.reading_direction as cfg_module
from jdraw.images import reading
from jdraw.train import reading as training

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from detector_average import drawing_scores, print_rows, score_row  # noqa: E402


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--strides", default="16,8,4")
    p.add_argument("--detector", default=None, help="folder of direction.json/.npz")
    p.add_argument("--out", default=None, help="write the table here as JSON")
    a = p.parse_args(argv)
    t0 = time.perf_counter()
    net = reading.load(a.detector)
    cfg = cfg_module.get_config()
    _, val_fonts, held = training._font_splits(cfg)
    rows = {}
    for stride in (int(s) for s in a.strides.split(",")):
        reading.STRIDE = stride
        val = drawing_scores([net], val_fonts, cfg.val_words_per_font, 2, cfg)
        hel = drawing_scores([net], held, cfg.eval_words_per_font, 1, cfg)
        rows[stride] = row = score_row(val, hel, np.ones(1))
        shown = {k: round(x, 3) for k, x in row.items()}
        print(f"stride {stride}: {json.dumps(shown)}", flush=True)
    print_rows(rows, "stride", list(hel))
    print(f"\n({time.perf_counter() - t0:.0f} s)")
    if a.out:
        pathlib.Path(a.out).write_text(json.dumps(rows, indent=1) + "\n")


if __name__ == "__main__":
    main()
