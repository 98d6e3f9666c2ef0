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
(copied in from jdraw/checkpoints/ours, the bundled default until
configs/robust.py; its loss weight is 0, so it does
not move).

Wall time: 3,600 steps in about 60 min of training-loop time on the 2-core
CPU (about 0.75 s a step alone; the run was stopped and resumed three times
and shared the CPU with evaluations part of the time). Bundled as
jdraw/checkpoints/fast_local (jdraw.export of the run, with the default's
ranker.npz and ranker.json copied in); configs/robust.py starts from it.

  python eval.py --checkpoint jdraw/checkpoints/fast_local --name beyond_fast_local \
      --n 1 --variants=cv2,px3,thick3

whole test split, ranker order: stroke accuracy 0.9739 (the paper's local
model with the same start model and ranker: 0.9747), order over all pairs
0.9265 (0.9332), matched pairs 0.9588, exact order 0.316, direction 0.9952,
pixel 0.9999; OpenCV 1-pixel lines 0.9583 stroke accuracy, 3-pixel lines
0.8765, 5-pixel lines 0.8146 (results/beyond_fast_local.json).
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
            init_from="jdraw/checkpoints/ours",
            train_local=True,
            global_batch=1,
            global_per_char=1,
            global_weight=0.0,
            num_steps=3600,
            checkpoint_every=200,
        )
    )
    return c
