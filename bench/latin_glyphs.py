"""The Latin dev glyphs scored one by one: which glyph the planner gets wrong, and how.

  python bench/latin_glyphs.py [--checkpoint BUNDLE] [--style clean|cv2|px3] [--copies 4]

Draws each glyph of :mod:`jdraw.data.latin`'s dev split ``--copies`` times as
``eval.py --latin`` does (:func:`jdraw.evaluation.latin.drawings`, the same random
shift, scale and shear), plans them with ``jdraw.plan`` and the checkpoint's ranker,
and prints the split's scores with a 1-pixel tolerance (issue 24's Latin bar), then one
line per glyph: for each drawing, stroke accuracy / direction / order over all pairs,
and drawn:true strokes. About 15 s on the 2-core CPU.
"""

from __future__ import annotations

import argparse

from jdraw.data import latin
from jdraw.evaluation import latin as latin_eval
from jdraw.evaluation import metrics
from jdraw.evaluation.batched import plan_batched
from jdraw.planner import plan as api
from jdraw.planner import ranker
from jdraw.plans import Plan


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--checkpoint", default=None, help="bundle folder (default: bundled)")
    ap.add_argument("--style", default="clean", choices=latin_eval.STYLES)
    ap.add_argument("--copies", type=int, default=4)
    args = ap.parse_args()

    ks = latin.load("dev")
    demos, inputs = latin_eval.drawings(ks, args.copies, args.style)
    rk = api.load_ranker(args.checkpoint)
    plan = plan_batched(inputs, args.checkpoint, batch=32, progress=False)
    plan = ranker.reorder(plan, "ranker" if rk is not None else "model", rk)
    m = metrics.score(demos, plan, inputs, tol=1)
    print(
        f"{args.style}, 1 px: stroke {m['stroke_acc']:.4f}  order, all pairs "
        f"{m['order_all_pairs']:.4f}  direction {m['direction_agreement']:.4f}  "
        f"strokes/true {m['stroke_ratio']:.3f}  (n={len(demos)})"
    )
    print("glyph  per drawing: stroke acc / direction / order, all pairs  drawn:true strokes")
    for g, code in enumerate(ks.codes):
        cells = []
        for i in range(g * args.copies, (g + 1) * args.copies):
            one = Plan(
                [plan.strokes[i]],
                plan.actions[i : i + 1],
                plan.lengths[i : i + 1],
                plan.truncated[i : i + 1],
            )
            s = metrics.score([demos[i]], one, inputs[i : i + 1], tol=1)
            cells.append(
                f"{s['stroke_acc']:.2f}/{s['direction_agreement']:.2f}/"
                f"{s['order_all_pairs']:.2f} {len(plan.strokes[i])}:{len(demos[i].strokes)}"
            )
        print(f"{chr(int(code))}      " + " | ".join(cells))


if __name__ == "__main__":
    main()
