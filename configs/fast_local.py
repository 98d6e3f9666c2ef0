"""Ours, faster: a smaller local model beside the whole-canvas start model.

Command:
  python train.py --config configs/fast_local.py --workdir runs/fast_local

The paper's local model costs about 0.47 ms a step at batch 1 on the 2-core
CPU (bench/plan_speed.py), half in the window encoder and half in the
LSTM's 1600 x 1024 input projection, and a character takes about 123 steps:
that, not the global step, now bounds planning one character at a time. This
config trains a local model with a narrower last block (32 channels, so 5x5x32
features) and a 128-wide LSTM, from scratch, on the paper's budget (3,600
steps, about 100,000 strokes). The start model is the bundled default's
(copied in from jdraw/checkpoints/default; its loss weight is 0, so it does
not move).

Status: started in session 5 to be evaluated against the default (stroke
accuracy on the test split must not fall) before it is used anywhere; no
result yet.
"""

import ml_collections

from configs import ours


def get_config() -> ml_collections.ConfigDict:
    c = ours.get_config()
    c.name = "fast_local"
    c.model.hidden = 128
    c.model.blocks = ((16, 16), (16, 16), (16, 32), (32, 32))
    c.train.update(
        dict(
            init_from="jdraw/checkpoints/default",
            train_local=True,
            learning_rate=1e-3,
            global_batch=1,
            global_per_char=1,
            global_weight=0.0,
            num_steps=3600,
            log_every=20,
            checkpoint_every=200,
        )
    )
    return c
