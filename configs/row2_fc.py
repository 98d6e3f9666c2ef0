"""Table I row 2: (a) the LSTM cell replaced by a fully connected layer.

Command:
  python train.py --config configs/row2_fc.py --workdir runs/row2_fc
  python eval.py --checkpoint runs/row2_fc --name row2_fc

Same data, budget (strokes fed, global samples) and optimiser as configs/paper.py;
only the model differs.

Wall time: 78 min of training-loop time on the shared 2-core CPU (3,600
steps, 100,077 strokes fed). Result (results/table1.md, eval.py): pixel
accuracy 1.0000 (1.0000) and stroke accuracy 0.9512 (0.9451) on 100 random
train (test) characters, the paper's 0.9564 (0.9532); the whole test
split, 1.0000 / 0.9607.
"""

import ml_collections

from configs import paper


def get_config() -> ml_collections.ConfigDict:
    c = paper.get_config()
    c.name = "row2_fc"
    c.model.core = "fc"
    return c
