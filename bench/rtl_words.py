"""Right-to-left words through ``jdraw.plan_image``: where the plan starts and which way it runs.

  python bench/rtl_words.py [--words 8] [--detector-words 12] [--seed 0] [--detector DIR]
      [--checkpoint BUNDLE] [--only hebrew,arabic,latin] [--directions auto,rtl,ltr]
      [--fonts eval|val]

Hebrew and Arabic words of our own (jdraw.data.fonts.WORDS) are set in the
fonts the reading-direction detector never saw (jdraw.data.fonts.DETECTOR_EVAL),
60-200 px high, and planned with the direction read from the image (``auto``),
given as a hint (``rtl``: the planner's part alone) and forced left to right
(``ltr``: the order before this change, save marks after their letter).
Per script and setting it prints:

* ``read rtl``: fraction of words the detector reads right to left;
* ``first right``: fraction whose first stroke starts in the rightmost letter
  (its x within that letter's advance, plus 5% of the height);
* ``rho``: mean Spearman correlation of a stroke's place in the plan with its
  mean x (negative: right to left), over words of 3 or more strokes.

``--fonts val`` sets the words in the detector's validation fonts instead
(jdraw.data.fonts.DETECTOR_VAL), for choosing between planners without looking
at the held-out ones.

Latin words (print and Dancing Script) show that left-to-right text keeps its
positive correlation. A second table gives the detector's accuracy on random
letters of every script set in the held-out fonts, and on random sketches.
``--detector DIR`` measures another detector (a trainer's ``out`` folder)
instead of the bundled one. Needs the fonts (see configs/reading_direction.py
for the apt-get line).
"""

from __future__ import annotations

import argparse
import pathlib
import time

import numpy as np
from scipy.stats import spearmanr

from jdraw.data import fonts as F
from jdraw.tiling.plan_image import plan_image

MARGIN = 8  # px of white around a rendered word (fonts.render_word's default)


def set_words(script: str, words: int, rng: np.random.Generator, fonts: dict | None = None):
    """Yields ``(text, font, height, image)``: ``words`` of our words per font of
    ``script`` (default: the held-out fonts), each set 60-200 px high in its direction."""
    k = 0
    for font in (fonts or F.DETECTOR_EVAL)[script]:
        for _ in range(words):
            text = F.WORDS[script][k % len(F.WORDS[script])]
            k += 1
            if not F.covers(font, text):
                continue
            height = int(rng.integers(60, 201))
            way = "rtl" if script in F.RTL_SCRIPTS else "ltr"
            yield text, font, height, F.render_word(text, font, height, direction=way)


def measure(
    script: str,
    words: int,
    rng: np.random.Generator,
    direction: str | None,
    checkpoint: str | None = None,
    fonts: dict | None = None,
) -> dict:
    first = rho = read = 0.0
    n = n_rho = 0
    rtl = script in F.RTL_SCRIPTS
    for text, font, height, img in set_words(script, words, rng, fonts):
        plan = plan_image(img, progress=False, direction=direction, checkpoint=checkpoint)
        read += plan.direction == "rtl"
        xs = [float(s[:, 0].mean()) for s in plan.strokes]
        if len(xs) >= 3:
            rho += spearmanr(np.arange(len(xs)), xs)[0]
            n_rho += 1
        right = img.shape[1] - 1 - MARGIN
        if rtl:
            w1 = F.first_letter_width(text, font, height)
            first += plan.strokes[0][0, 0] >= right - w1 - 0.05 * height
        else:
            w1 = F.first_letter_width(text, font, height, "ltr")
            first += plan.strokes[0][0, 0] <= MARGIN + w1 + 0.05 * height
        n += 1
    return {"words": n, "read_rtl": read / n, "first": first / n, "rho": rho / max(n_rho, 1)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--words", type=int, default=8, help="words per font")
    ap.add_argument(
        "--detector-words",
        type=int,
        default=12,
        help="random drawings per font (0: no detector table)",
    )
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--detector", help="folder of another direction.json/.npz (default: bundled)")
    ap.add_argument("--checkpoint", help="planner bundle (default: the bundled default)")
    ap.add_argument("--only", default="hebrew,arabic,latin", help="scripts of the first table")
    ap.add_argument("--directions", default="auto,rtl,ltr", help="settings of the first table")
    ap.add_argument("--fonts", default="eval", choices=("eval", "val"), help="fonts of the words")
    args = ap.parse_args()
    from jdraw.images import reading

    if args.detector:
        reading.ASSET = pathlib.Path(args.detector).resolve()  # what plan_image's detect loads
        print(f"detector: {reading.ASSET} ({reading.load().pool}, {reading.load().threshold:.2f})")
    print("| script | direction | words | read rtl | first stroke in first letter | rho |")
    print("| --- | --- | ---: | ---: | ---: | ---: |")
    t0 = time.perf_counter()
    fonts = F.DETECTOR_VAL if args.fonts == "val" else F.DETECTOR_EVAL
    for script in args.only.split(","):
        for direction in [None if d == "auto" else d for d in args.directions.split(",")]:
            rng = np.random.default_rng(args.seed)
            r = measure(script, args.words, rng, direction, args.checkpoint, fonts)
            print(
                f"| {script} | {direction or 'auto'} | {r['words']} | {r['read_rtl']:.2f} | "
                f"{r['first']:.2f} | {r['rho']:+.2f} |",
                flush=True,
            )
    print(f"\n({time.perf_counter() - t0:.0f} s)\n")
    if args.detector_words <= 0:
        return

    import sys

    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))  # configs/
    import configs.reading_direction as cfg_module
    from jdraw.train import reading as training

    cfg = cfg_module.get_config()
    held = {**F.DETECTOR_EVAL, "sketch": [None]}
    acc = training.accuracy(reading.load(), held, args.detector_words, cfg, seed=args.seed + 7)
    print("| script (held-out fonts) | fonts | detector accuracy |")
    print("| --- | --- | ---: |")
    for script, a in acc.items():
        names = ", ".join(n for n in held[script] if n) or "random sketches"
        print(f"| {script} | {names} | {a:.3f} |")


if __name__ == "__main__":
    main()
