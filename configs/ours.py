"""Ours: the paper's local model with a whole-canvas start model (jdraw.model.start_net).

Command:
  python train.py --config configs/ours.py --workdir runs/ours
  python train.py --config configs/ranker.py --workdir runs/ranker   # then the ranker

The local model (window encoder + LSTM) is the paper checkpoint's
(jdraw/checkpoints/paper), copied in and left as it is (its loss is not
computed, so its weights do not move); only the new global model trains: a
small U-Net down to 13x13 with coordinate channels and a pooled summary of the
canvas, 32 stroke starts a step (4 from each sampled character), Adam 1e-3.
When planning, it starts strokes only where strokes can begin (free ends,
junctions, beside drawn ink) whenever such a pixel is allowed.

Wall time: 1,200 steps (38,400 stroke starts) in 46 min of training-loop time
on the 2-core CPU, shared with four other jobs throughout (load average
~10-12); the run was meant for 2,500 steps and stopped at 1,200 for time.
Result (48 validation characters, as traced): stroke accuracy 0.970, order
agreement 0.78 (matched pairs), direction 0.957; the paper checkpoint on the
same characters: 0.971, 0.58, 0.961. With the ranker, and on the test split:
results/beyond.md (README, "Beyond the paper").
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
