"""The bundled stroke splitter: configs/splitter_lean.py, and ends joined through the ink.

Command (after configs/lean_start.py, whose bundle traces):
  python train.py --config configs/splitter_reach.py --workdir runs/splitter_reach

As configs/splitter_lean.py, but two stroke ends up to 8 px apart are also a
join example when a path of at most 8 one-pixel moves through the ink links
them (jdraw.planner.joins.bridge): where a thick line crosses another, the
local model often stops a few pixels short of the crossing and takes the line
up again a few pixels past it. The join draws the crossing again, and a piece
of line that is then drawn twice is dropped (jdraw.planner.splits.drop_covered).

Wall time: about 10 min on the 2-core CPU (9,000 traced characters 582 s, the
fit 4 s): 27,990 corners (3,956 splits) and 47,052 pairs of ends (4,151
joins; 22,369 of the pairs, 1,749 of the joins, through the ink). Copied
beside the default's params and ranker (jdraw/checkpoints/default), the whole
test split (python eval.py --name beyond_lean_reach --n 1) against
configs/splitter_lean.py (results/beyond_lean_split.json): 3-px lines, stroke
accuracy 0.9492 -> 0.9546, strokes / true 1.005 -> 0.995; jdraw's lines,
stroke accuracy 0.9866 -> 0.9870, order over all pairs 0.9588 -> 0.9582;
OpenCV's lines 0.9861 -> 0.9884; 5-px lines 0.8951 -> 0.8999. Part of that is
dropping strokes that others draw over, which today's code does with any splitter:
the first one with it scores 0.9507 on 3-px lines and 0.9866 on OpenCV's
(results/beyond_lean_near.json, --split jdraw/checkpoints/splitter_near).
"""

import ml_collections

from configs import splitter_lean


def get_config() -> ml_collections.ConfigDict:
    c = splitter_lean.get_config()
    c.name = "splitter_reach"
    c.out = "runs/splitter_reach/bundle"
    c.reach = 8  # pixels: ends linked through the ink (jdraw.planner.joins.REACH)
    return c
