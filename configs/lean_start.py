"""Ours, leaner start model: the whole-canvas U-Net from 50x50 (space to depth).

Command (after configs/lean.py, whose local model it copies in):
  python train.py --config configs/lean_start.py --workdir runs/lean_start

The start model of configs/ours.py spends most of its CPU time in its
full-resolution layers (8 channels over 100x100 pixels). This one folds each
2x2 block of the state into channels first and runs at 50, 25 and 13 pixels
(16, 32, 64 channels), then gives each pixel its own logit (four per block,
plus a linear term of the pixel's own channels); see
jdraw.model.start_net. It trains from scratch on the mix of drawings of
configs/robust.py, 32 stroke starts a step (4 from each sampled character),
Adam 1e-3 with a cosine decay to 1e-4. The local model (configs/lean.py) does
not move.

Wall time: 1,500 steps (48,000 stroke starts) in 5 min of training-loop time
on the 2-core CPU (298 s), against 46 min for the 1,200 steps of
configs/ours.py's full-resolution start model on a shared CPU. Its bundle,
with configs/ranker_lean.py's ranker.npz and ranker.json copied in, is
jdraw/checkpoints/lean.
"""

import ml_collections

from configs import lean


def get_config() -> ml_collections.ConfigDict:
    c = lean.get_config()
    c.name = "lean_start"
    c.model.start_widths = (16, 32, 64)
    c.model.start_half_res = True
    c.train.update(
        dict(
            init_from="runs/lean/bundle",
            train_local=False,
            learning_rate=1e-3,
            final_lr_fraction=0.1,
            global_batch=32,
            global_per_char=4,
            global_weight=1.0,
            num_steps=1500,
            log_every=20,
            checkpoint_every=100,
        )
    )
    return c
