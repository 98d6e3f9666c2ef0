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

Status (session 5): not used anywhere yet. The run was still going when the
session ended; the same command resumes it. Wall time: 2,400 steps in about
40 min on the 2-core CPU (about 0.75 s a step alone, 2 s beside a CI run).
Interim result at step 2,400, exported with jdraw.export and given the
default's ranker (ranker.npz, ranker.json copied in):

  python eval.py --checkpoint BUNDLE --name fl_2400 --n 1 --variants=

whole test split (1,000 characters), ranker order: stroke accuracy 0.9730
(default 0.9747), pixel 0.9999, order over all pairs 0.9297 (default
0.9332), matched pairs 0.9606, exact order 0.323, direction 0.9949. At step
1,200, on 100 random test characters, stroke accuracy was 0.9590.

  python bench/global_cost.py --chars 32 --ours BUNDLE

(the training run paused): `jdraw.plan` at batch 1, 21.10 characters/s
against the paper's model's 10.00 in the same run, 2.11x; global step 0.200
of the paper's by time, 0.082 by FLOPs.
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
            global_batch=1,
            global_per_char=1,
            global_weight=0.0,
            num_steps=3600,
            checkpoint_every=200,
        )
    )
    return c
