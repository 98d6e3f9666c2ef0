"""Cursive fragments on the canvas, stage by stage: where the planner adds strokes.

  python bench/cursive_fragments.py [--checkpoint DIR ...] [--n 64] [--styles clean,px3]

Draws ``--n`` fragments of the cursive val words (:func:`jdraw.data.cursive.fragments`,
2-5 letters fitted to the 100 x 100 canvas, a fixed random choice) in each style
(``clean``: jdraw's own 1-pixel lines; the others as :func:`jdraw.data.variants.draw`
draws them and ``jdraw.plan`` canonicalises them), plans them with each checkpoint
three ways, each ordered by the checkpoint's ranker:

* ``trace``: as traced (``join=False, split=False``);
* ``join``: strokes joined through junctions (``split=False``);
* ``full``: the checkpoint's whole stack (its learned splitter too).

and prints drawn / written strokes, stroke accuracy, order over all pairs and
direction (:func:`jdraw.evaluation.metrics.score`, a 1-pixel tolerance on the
styles other than ``clean``). The writer's strokes go back over their own line
where the font's letters land on the next one (:mod:`jdraw.data.cursive`).
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from jdraw.data import cursive, variants
from jdraw.data import demos as D
from jdraw.evaluation import metrics
from jdraw.evaluation.batched import plan_batched
from jdraw.planner import plan as api
from jdraw.planner import ranker

STAGES = {
    "trace": dict(join=False, split=False),
    "join": dict(join=True, split=False),
    "full": {},
}


def drawings(n: int, style: str, seed: int = 0):
    """``(demos, inputs bool [n, 100, 100])``: ``n`` val fragments drawn in ``style``."""
    ks = cursive.fragments("val")
    idx = np.random.default_rng(seed).choice(len(ks), min(n, len(ks)), replace=False)
    demos, inputs = [], []
    for i in idx:
        ctrl = ks.strokes(int(i))
        d = D.from_control_points(ctrl, keep_turns=True)
        demos.append(d)
        inputs.append(d.target if style == "clean" else variants.draw(ctrl, style))
    return demos, np.stack(inputs)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--checkpoint", nargs="*", default=["default"], help="bundles or 'default'")
    p.add_argument("--n", type=int, default=64)
    p.add_argument("--styles", default="clean,px3")
    a = p.parse_args(argv)
    cols = "checkpoint | style | stage | drawn / written | stroke acc | order, all pairs | dir."
    print(f"| {cols} |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for style in a.styles.split(","):
        demos, inputs = drawings(a.n, style)
        for name in a.checkpoint:
            ck = None if name == "default" else name
            rk = api.load_ranker(ck)
            for stage, kw in STAGES.items():
                t0 = time.time()
                plan = plan_batched(inputs, ck, batch=32, progress=False, **kw)
                plan = ranker.reorder(plan, "ranker" if rk is not None else "model", rk)
                s = metrics.score(demos, plan, inputs, tol=0 if style == "clean" else 1)
                print(
                    f"| {name} | {style} | {stage} | {s['stroke_ratio']:.3f} | "
                    f"{s['stroke_acc']:.3f} | {s['order_all_pairs']:.3f} | "
                    f"{s['direction_agreement']:.3f} |  <!-- {time.time() - t0:.0f} s -->",
                    flush=True,
                )


if __name__ == "__main__":
    main()
