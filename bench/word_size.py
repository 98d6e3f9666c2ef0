"""How a cursive word's size on the planner's canvas goes with how well it is planned.

  python bench/word_size.py [--split val] [--n 40]

Plans the first ``--n`` words of a split as :mod:`jdraw.evaluation.words` draws them
(100-300 px high, a 3-px marker) with ``plan_image`` twice: as large as their lines
allow (``jdraw.tiling.layout.JOINED_CORE`` set past any core: the layout before
2026-12-07, late) and as shipped (joined-up writing no larger than the planner learned
it). For each, the words are grouped by their height on the canvas (the word's height
times the scale ``plan_image`` chose) and each group's mean stroke accuracy and drawn
per written strokes are printed. About 40 s for 40 words on the 2-core CPU.
"""

from __future__ import annotations

import argparse

import numpy as np

from jdraw.data import cursive
from jdraw.evaluation import words as W
from jdraw.tiling import layout
from jdraw.tiling.plan_image import plan_image

EDGES = (0, 50, 70, 100, np.inf)  # canvas px


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--split", default="val", choices=("train", "val", "test"))
    ap.add_argument("--n", type=int, default=40)
    a = ap.parse_args()
    shipped = layout.JOINED_CORE
    for name, core in (("as large as its lines allow", float("inf")), ("as shipped", shipped)):
        layout.JOINED_CORE = core
        rows = []
        for w in cursive.split_words(a.split)[: a.n]:
            h = W.word_height(w)
            img, written = W.render_word(w, h)
            plan = plan_image(img, polarity="dark", progress=False)
            s = W.score_word(img < 128, written, plan.strokes)
            rows.append((h * plan.scale, s["stroke_acc"], s["stroke_ratio"]))
        layout.JOINED_CORE = shipped
        r = np.asarray(rows)
        print(f"\n{name} ({a.split}, {len(r)} words)")
        print("| word height on the canvas | words | stroke acc | drawn / written |")
        print("| --- | ---: | ---: | ---: |")
        for lo, hi in zip(EDGES, EDGES[1:]):
            on = (r[:, 0] >= lo) & (r[:, 0] < hi)
            if on.any():
                span = f"{lo:.0f} px or more" if np.isinf(hi) else f"{lo:.0f}-{hi:.0f} px"
                print(f"| {span} | {on.sum()} | {r[on, 1].mean():.3f} | {r[on, 2].mean():.2f} |")


if __name__ == "__main__":
    main()
