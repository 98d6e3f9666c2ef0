"""The stroke ranker of the robust planner: trained on its own strokes of lines drawn other ways.

Command (after configs/robust_start.py, whose bundle traces):
  python train.py --config configs/ranker_robust.py --workdir runs/ranker_robust

As configs/ranker.py, but the tracer is the robust planner and the traced
characters are drawn in the mix of configs/robust.py (jdraw's own lines,
OpenCV's, 3- and 5-pixel pens; canonicalised, KanjiVG's strokes laid onto
them), so the ranker learns to order the strokes the planner draws from any
of them. 600 traced characters.

Status: see the docstring's result once the run is done.
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
