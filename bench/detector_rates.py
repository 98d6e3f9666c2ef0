"""How often reading-direction detectors read each script right to left, at several thresholds.

  PYTHONPATH=. python bench/detector_rates.py DIR [DIR ...] [--per-font 60] [--seed 3]

Each ``DIR`` holds a detector (``direction.json`` and ``direction.npz``). The
trainer sets a detector's threshold on 20 drawings per validation font (seed 2,
``bench/detector_average.py``) so that none of the left-to-right ones reads right
to left. This bench asks how far that holds on more drawings of the same fonts:
``--per-font`` new drawings per validation font (five times as many random
sketches) with another seed, 300 drawings of KanjiVG validation characters
(``bench/detector_kanji.py``'s), and our words set in the validation fonts
(``bench/detector_words.py``'s). For each detector it prints, at its own threshold
and at fixed ones, the fraction of each script read right to left: for the
right-to-left scripts that is what should be high, for the others it is a
mistake. ``--more-faces`` adds drawings of han, kana and Hangul set in CJK faces
of no split (:data:`jdraw.data.cjk_faces.DETECTOR_CHECK`; ``apt-get install
fonts-arphic-bsmi00lp fonts-arphic-gbsn00lp fonts-arphic-gkai00mp fonts-hanazono
fonts-ipaexfont-mincho fonts-baekmuk``). Nothing held out is read. Needs the fonts of
``configs/reading_direction.py``; about 90 s per detector on the 2-core CPU.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from detector_kanji import kanji_drawings
from rtl_words import set_words

import configs.reading_direction as cfg_module
from jdraw.data import cjk_faces
from jdraw.data import fonts as F
from jdraw.images import reading
from jdraw.images.prepare import prepare
from jdraw.train import reading as training
from jdraw.train.reading_data import sample

THRESHOLDS = (1.5, 2.0, 2.5, 3.0, 4.0)
SKETCHES = 5  # times --per-font random sketches (they have no fonts)
KANJI = 300  # drawings of KanjiVG validation characters


def drawings(per_font: int, seed: int, more_faces: bool = False) -> dict:
    """``{set: [images]}``: the validation fonts' drawings, KanjiVG's and our words;
    with ``more_faces``, also ``per_font`` drawings per face of
    :data:`jdraw.data.cjk_faces.DETECTOR_CHECK` (``"han, more faces"``, ...)."""
    cfg = cfg_module.get_config()
    _, val_fonts, _ = training._font_splits(cfg)
    rng = np.random.default_rng(seed)
    out = {}
    for script, names in val_fonts.items():
        n = per_font * (SKETCHES if script == "sketch" else 1)
        out[script] = [sample(script, font, rng, cfg) for font in names for _ in range(n)]
    out["kanjivg"] = list(kanji_drawings(KANJI))
    if more_faces:
        for script, names in cjk_faces.DETECTOR_CHECK.items():
            got = [sample(script, font, rng, cfg) for font in names for _ in range(per_font)]
            out[f"{script}, more faces"] = got
    for s in ("arabic", "hebrew", "latin"):
        got = set_words(s, 24, np.random.default_rng(0), F.DETECTOR_VAL)
        out[f"{s} words"] = [img for *_, img in got]
    return out


def scores(net, images: list) -> np.ndarray:
    """Each image's score (the net's pooling); a drawing too small to read is left out."""
    got = []
    for img in images:
        try:
            got.append(reading.rtl_score(prepare(img), net))
        except ValueError:  # too little ink left to read
            continue
    return np.asarray(got, np.float64)


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("detectors", nargs="+", help="folders of direction.json/.npz")
    p.add_argument("--per-font", type=int, default=60, help="drawings per validation font")
    p.add_argument("--seed", type=int, default=3, help="not the trainer's 2")
    p.add_argument(
        "--more-faces", action="store_true",
        help="also the CJK faces of no split (jdraw.data.cjk_faces.DETECTOR_CHECK)",
    )  # fmt: skip
    a = p.parse_args(argv)
    t0 = time.perf_counter()
    sets = drawings(a.per_font, a.seed, a.more_faces)
    names = list(sets)
    print("drawings: " + ", ".join(f"{s} {len(v)}" for s, v in sets.items()))
    for d in a.detectors:
        net = reading.load(d)
        got = {s: scores(net, v) for s, v in sets.items()}
        print(f"\n{d} (threshold {net.threshold:.2f}): fraction read right to left")
        print("| threshold | " + " | ".join(names) + " |")
        print("| --- " * (1 + len(names)) + "|")
        for th in sorted({*THRESHOLDS, round(net.threshold, 2)}):
            mark = " (its own)" if th == round(net.threshold, 2) else ""
            cells = [f"{np.mean(got[s] > th):.3f}" if len(got[s]) else "-" for s in names]
            print(f"| {th:.2f}{mark} | " + " | ".join(cells) + " |")
    print(f"\n({time.perf_counter() - t0:.0f} s)")


if __name__ == "__main__":
    main()
