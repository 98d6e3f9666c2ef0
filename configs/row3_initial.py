"""Table I row 3: (b) Initial Extraction: cut a 5x5 patch of each state image, then encode.

Command:
  python train.py --config configs/row3_initial.py --workdir runs/row3_initial
  python eval.py --checkpoint runs/row3_initial --name row3_initial

Same data, budget (strokes fed, global samples) and optimiser as configs/paper.py;
only the model differs.

Wall time: 94 min of training-loop time on the shared 2-core CPU (3,600
steps, 100,077 strokes fed). Result (results/table1.md, eval.py): pixel
accuracy 1.0000 (1.0000) and stroke accuracy 0.9527 (0.9608) on 100 random
train (test) characters, the paper's 0.8746 (0.8822); the whole test
split, 1.0000 / 0.9669.
"""

import ml_collections

from configs import paper


def get_config() -> ml_collections.ConfigDict:
    c = paper.get_config()
    c.name = "row3_initial"
    c.model.extraction = "initial"
    return c
