"""Dev scores of bundles: the KanjiVG val split, the Latin dev glyphs, cursive val words.

  PYTHONPATH=. python bench/dev_scores.py BUNDLE [BUNDLE ...] [--words 40] [--out FILE]

For choosing between planners without looking at the KanjiVG test split: each
bundle plans the 1,000 KanjiVG val characters (jdraw's lines, ordered by its
ranker), the Latin dev glyphs four times each on jdraw's lines
(:func:`jdraw.evaluation.latin.evaluate_latin`) and the first ``--words`` cursive
val words through ``plan_image`` (:mod:`jdraw.evaluation.words`), and prints stroke
accuracy, order over all pairs, direction and strokes per true stroke (2-3 min a
bundle on the 2-core CPU); the Latin glyphs also with a 1-pixel tolerance, as issue
24's Latin bar is set.
"""

from __future__ import annotations

import argparse
import json
import pathlib

from jdraw.data import kanji
from jdraw.evaluation import evaluate, metrics
from jdraw.evaluation import words as W
from jdraw.evaluation.latin import evaluate_latin
from jdraw.planner import plan as api
from jdraw.planner import ranker

KEYS = ("stroke_acc", "order_all_pairs", "direction_agreement", "stroke_ratio")


def scores(checkpoint, n_words: int = 40) -> dict:
    ks = kanji.load(progress=False)
    idx = kanji.split_indices(ks, "val")
    demos, inputs, plan = evaluate.plan_chars(ks, idx, checkpoint, progress=False)
    plan = ranker.reorder(plan, "ranker", api.load_ranker(checkpoint))
    out = {"kanji_val": metrics.score(demos, plan, inputs)}
    out["latin_dev"] = evaluate_latin(checkpoint, copies=4, styles=("clean",), progress=False)
    if n_words:
        w = W.evaluate_words("val", n_words, checkpoint=checkpoint, progress=False)
        out["words"] = {k: v for k, v in w.items() if k != "words"}
    return out


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("bundles", nargs="+")
    p.add_argument("--words", type=int, default=40, help="cursive val words (0: none)")
    p.add_argument("--out", default=None, help="write every bundle's scores here as JSON")
    a = p.parse_args(argv)
    res = {}
    for b in a.bundles:
        r = res[b] = scores(b, a.words)
        fmt = lambda m: " / ".join(f"{m[k]:.4f}" for k in KEYS)  # noqa: E731
        print(
            f"{b}\n  KanjiVG val (stroke acc / order, all pairs / direction / per true):",
            fmt(r["kanji_val"]),
        )
        print("  Latin dev, jdraw's lines:", fmt(r["latin_dev"]["clean"]))
        print("  ... with a 1-px tolerance (issue 24's bar):", fmt(r["latin_dev"]["clean_1px"]))
        if "words" in r:
            print("  " + W.summary(r["words"]))
    if a.out:
        pathlib.Path(a.out).write_text(json.dumps(res, indent=2) + "\n")


if __name__ == "__main__":
    main()
