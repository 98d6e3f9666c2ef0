"""Ours, leaner local model: 8- and 16-channel blocks, trained on lines drawn any way.

Command:
  python train.py --config configs/lean.py --workdir runs/lean

A batched local step of the smaller local model (configs/fast_local.py) is
mostly its window encoder's full-resolution blocks (16 channels on 21x21 to
13x13 windows). This one halves the early blocks' channels, blocks
((8, 8), (8, 16), (16, 16), (16, 32)): 2.0 M multiply-adds a window against
4.6 M, the same 23x23 window, 5x5x32 features and 128-wide LSTM. It trains
from scratch on the mix of drawings of configs/robust.py (jdraw's lines 40%,
OpenCV 1-pixel, anti-aliased, 3- and 5-pixel pens 15% each), Adam 1e-3 with
a cosine decay to 1e-4. The start model is trained after it
(configs/lean_start.py); here its loss weight is 0. Planning joins a stroke to
the one that goes on from its end through a junction (``planner.join``,
jdraw.planner.joins), written into the bundle.

Wall time: 3,600 steps (100,199 strokes) in 35 min of training-loop time on
the 2-core CPU (2,105 s; evaluations shared the CPU part of the time), in one
go. Its bundle, runs/lean/bundle, has an untrained start model; the next
stage trains it.
"""

import ml_collections

from configs import robust


def get_config() -> ml_collections.ConfigDict:
    c = robust.get_config()
    c.name = "lean"
    c.model.blocks = ((8, 8), (8, 16), (16, 16), (16, 32))
    c.model.hidden = 128
    c.planner = ml_collections.ConfigDict(dict(join=True))
    c.train.update(
        dict(
            init_from="",
            learning_rate=1e-3,
            final_lr_fraction=0.1,
            num_steps=3600,
            checkpoint_every=100,
        )
    )
    return c
