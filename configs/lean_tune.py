"""Ours, lean, fine-tuned: the lean local model on more thick lines, in today's canonical form.

Command (after configs/lean_start.py):
  python train.py --config configs/lean_tune.py --workdir runs/lean_tune

configs/lean.py trained before thick lines were redrawn straight through
junctions (jdraw.images.canonical), so its thick-line demonstrations had the
old junction shapes. This run fine-tunes its local model on demonstrations
in today's canonical form, with thick pens drawn more often (jdraw's lines
30%, OpenCV 1-pixel and anti-aliased 10% each, 3-pixel pen 30%, 5-pixel pen
20%), Adam 3e-4 with a cosine decay to 3e-5 over 1,200 steps. The start
model (configs/lean_start.py) does not move.

Wall time: 1,200 steps in 10 min of training-loop time on the 2-core CPU.
Result (96 random validation characters, stroke accuracy with a
1-pixel tolerance on other drawings):

  PYTHONPATH=. python bench/canonical_variants.py --checkpoint runs/lean_tune/bundle \
      --n 96 --split val --styles clean,cv2,thick2,thick3

jdraw's own lines 0.9804, OpenCV 1-pixel 0.9701, 3-pixel pen (thick2) 0.9197,
5-pixel pen (thick3) 0.8714; the bundled default (lean) on the same
characters: 0.9812, 0.9698, 0.9155, 0.8667. Not bundled: half a point on
thick pens, far from 0.95 on 3-pixel lines, for a little on jdraw's lines.
"""

import ml_collections

from configs import lean_start


def get_config() -> ml_collections.ConfigDict:
    c = lean_start.get_config()
    c.name = "lean_tune"
    c.data.styles = dict(clean=0.3, cv2=0.1, aa=0.1, px3=0.3, px5=0.2)
    c.train.update(
        dict(
            init_from="runs/lean_start/bundle",
            train_local=True,
            learning_rate=3e-4,
            final_lr_fraction=0.1,
            global_batch=1,
            global_per_char=1,
            global_weight=0.0,
            num_steps=1200,
            checkpoint_every=100,
        )
    )
    return c
