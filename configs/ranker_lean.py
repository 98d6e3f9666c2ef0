"""The stroke ranker of the lean planner, trained on its own strokes of lines drawn any way.

Command (after configs/lean_start.py, whose bundle traces):
  python train.py --config configs/ranker_lean.py --workdir runs/ranker_lean

As configs/ranker_robust.py with the lean planner (configs/lean.py and
configs/lean_start.py) as the tracer: 600 traced characters in the mix of
drawings of configs/robust.py. The tracer's bundle joins strokes
(planner.join), so the ranker learns to order joined strokes.

Wall time: about 2 min on the 2-core CPU (600 traced characters 62 s, the fit
6 s): 261,147 ordered pairs, 39,125 heading examples.
"""

import ml_collections

from configs import ranker_robust


def get_config() -> ml_collections.ConfigDict:
    c = ranker_robust.get_config()
    c.name = "ranker_lean"
    c.tracer = "runs/lean_start/bundle"
    c.out = "runs/ranker_lean/bundle"
    return c
