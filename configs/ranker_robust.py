"""The stroke ranker of the robust planner: trained on its own strokes of lines drawn other ways.

Command (after configs/robust_start.py, whose bundle traces):
  python train.py --config configs/ranker_robust.py --workdir runs/ranker_robust

As configs/ranker.py, but the tracer is the robust planner and the traced
characters are drawn in the mix of configs/robust.py (jdraw's own lines,
OpenCV's, 3- and 5-pixel pens; canonicalised, KanjiVG's strokes laid onto
them), so the ranker learns to order the strokes the planner draws from any
of them. 600 traced characters.

Wall time: about 4 min on the 2-core CPU (600 traced characters 117 s, the
fit 9 s): 261,399 ordered pairs, 39,149 heading examples. Its ranker.npz and
ranker.json, copied beside runs/robust_start/bundle's params, make
jdraw/checkpoints/robust (the default until configs/lean.py). Whole test
split: order over all pairs 0.9035 as traced -> 0.9485 ranked, direction
0.9907 -> 0.9974 (results/beyond_robust.json).
"""

import ml_collections

from configs import ranker, robust


def get_config() -> ml_collections.ConfigDict:
    c = ranker.get_config()
    c.name = "ranker_robust"
    c.tracer = "runs/robust_start/bundle"
    c.out = "runs/ranker_robust/bundle"
    c.chars = 600
    c.styles = robust.get_config().data.styles
    return c
