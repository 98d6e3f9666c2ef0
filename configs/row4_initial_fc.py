"""Table I row 4: (b) + (a): Initial Extraction and a fully connected layer instead of the LSTM.

Command:
  python train.py --config configs/row4_initial_fc.py --workdir runs/row4_initial_fc
  python eval.py --checkpoint runs/row4_initial_fc --name row4_initial_fc

Same data, budget (strokes fed, global samples) and optimiser as configs/paper.py;
only the model differs.

Wall time: 47 min of training-loop time on the shared 2-core CPU (3,600
steps, 100,077 strokes fed). Result (results/table1.md, eval.py): pixel
accuracy 1.0000 (1.0000) and stroke accuracy 0.9468 (0.9509) on 100 random
train (test) characters, the paper's 0.8666 (0.8809); the whole test
split, 1.0000 / 0.9535.
"""

import ml_collections

from configs import paper


def get_config() -> ml_collections.ConfigDict:
    c = paper.get_config()
    c.name = "row4_initial_fc"
    c.model.extraction = "initial"
    c.model.core = "fc"
    return c
