"""Table I row 4: (b) + (a): Initial Extraction and a fully connected layer instead of the LSTM.

Command:
  python train.py --config configs/row4_initial_fc.py --workdir runs/row4_initial_fc
  python eval.py --checkpoint runs/row4_initial_fc --name row4_initial_fc

Same data, budget (strokes fed, global samples) and optimiser as configs/paper.py;
only the model differs. Wall time and result: results/table1.md.
"""

import ml_collections

from configs import paper


def get_config() -> ml_collections.ConfigDict:
    c = paper.get_config()
    c.name = "row4_initial_fc"
    c.model.extraction = "initial"
    c.model.core = "fc"
    return c
