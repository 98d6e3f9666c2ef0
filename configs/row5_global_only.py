"""Table I row 5: (c) the global model alone, looped on itself, trained on raw actions.

Command:
  python train.py --config configs/row5_global_only.py --workdir runs/row5_global_only
  python eval.py --checkpoint runs/row5_global_only --name row5_global_only

Budget: every training sample here is a whole-canvas encoder pass, 16 a step
for the same 3,600 steps as row 1, which matches row 1's compute per step
(512 window passes + 8 canvas passes) within about 10% on this CPU; the
paper's 100,000-stroke budget would be ~450,000 canvas passes here (about
6 hours of this 2-core CPU). strokes_seen counts samples (one raw action of
one stroke each). Wall time and result: results/table1.md.
"""

import ml_collections

from configs import paper


def get_config() -> ml_collections.ConfigDict:
    c = paper.get_config()
    c.name = "row5_global_only"
    c.model.kind = "global_only"
    c.train.global_batch = 16
    return c
