"""Table I row 5: (c) the global model alone, looped on itself, trained on raw actions.

Command:
  python train.py --config configs/row5_global_only.py --workdir runs/row5_global_only
  python eval.py --checkpoint runs/row5_global_only --name row5_global_only

Budget: every training sample here is a whole-canvas encoder pass, 16 a step
for the same 3,600 steps as row 1, which matches row 1's compute per step
(512 window passes + 8 canvas passes) within about 10% on this CPU; the
paper's 100,000-stroke budget would be ~450,000 canvas passes here (about
6 hours of this 2-core CPU). strokes_seen counts samples (one raw action of
one stroke each).

Wall time: 103 min of training-loop time on the shared 2-core CPU (57,600
samples). Result (results/table1.md, eval.py): pixel accuracy 0.4509 (0.4443)
and stroke accuracy 0.3903 (0.3607) on 100 random train (test) characters,
the paper's 0.2693 (0.2773) and 0.1565 (0.1680); the whole test split,
0.4584 / 0.3670. Alone, the global model collapses, as in the paper.
"""

import ml_collections

from configs import paper


def get_config() -> ml_collections.ConfigDict:
    c = paper.get_config()
    c.name = "row5_global_only"
    c.model.kind = "global_only"
    c.train.global_batch = 16
    return c
