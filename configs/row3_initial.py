"""Table I row 3: (b) Initial Extraction: cut a 5x5 patch of each state image, then encode.

Command:
  python train.py --config configs/row3_initial.py --workdir runs/row3_initial
  python eval.py --checkpoint runs/row3_initial --name row3_initial

Same data, budget (strokes fed, global samples) and optimiser as configs/paper.py;
only the model differs. Wall time and result: results/table1.md.
"""

import ml_collections

from configs import paper


def get_config() -> ml_collections.ConfigDict:
    c = paper.get_config()
    c.name = "row3_initial"
    c.model.extraction = "initial"
    return c
