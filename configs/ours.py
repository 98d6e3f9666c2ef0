"""Ours: the paper's local model with a whole-canvas start model (jdraw.start_net).

Command:
  python train.py --config configs/ours.py --workdir runs/ours

The local model (window encoder + LSTM) is the bundled paper checkpoint's,
copied in and left as it is (its loss is not computed, so its weights do not
move); only the new global model trains: a small U-Net down to 13x13 with
coordinate channels and a pooled summary of the canvas (about 1/6 of the
paper global model's time per call, see bench/global_cost.py). The stroke
order is then refined by the learned stroke ranker (configs/ranker.py).

Wall time and result: see the docstring of configs/ranker.py and the README's
"Beyond the paper" table, which list both stages' measured numbers.
"""

import ml_collections

from configs import paper


def get_config() -> ml_collections.ConfigDict:
    c = paper.get_config()
    c.name = "ours"
    c.model.global_net = "unet"
    c.model.start_widths = (8, 16, 32, 64)
    c.model.start_full_res_convs = 0
    c.train.update(
        dict(
            init_from="jdraw/checkpoints/paper",
            train_local=False,
            learning_rate=1e-3,
            global_batch=32,
            global_per_char=4,
            num_steps=1200,
            log_every=20,
            checkpoint_every=100,
        )
    )
    c.eval.update(dict(every=500, val_chars=48))
    return c
