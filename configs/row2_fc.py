"""Table I row 2: (a) the LSTM cell replaced by a fully connected layer.

Command:
  python train.py --config configs/row2_fc.py --workdir runs/row2_fc
  python eval.py --checkpoint runs/row2_fc --name row2_fc

Same data, budget (strokes fed, global samples) and optimiser as configs/paper.py;
only the model differs. Wall time and result: results/table1.md.
"""

import ml_collections

from configs import paper


def get_config() -> ml_collections.ConfigDict:
    c = paper.get_config()
    c.name = "row2_fc"
    c.model.core = "fc"
    return c
