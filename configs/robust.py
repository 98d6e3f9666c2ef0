"""Ours, robust: the fast local model fine-tuned on lines drawn other ways.

Command:
  python train.py --config configs/robust.py --workdir runs/robust

Starts from jdraw/checkpoints/fast_local (configs/fast_local.py: the bundled
start model beside a 32-channel, 128-wide local model) and trains the local
model on, besides jdraw's own lines (40%), the same characters drawn by
OpenCV (1-pixel polylines, anti-aliased lines thresholded) and with 3- and
5-pixel pens (15% each), canonicalised as `jdraw.plan` canonicalises its input
and with KanjiVG's strokes laid onto the canonical lines
(jdraw.data.variants). A model trained only on jdraw's lines reads the
one-pixel tick where one stroke overshoots the one it meets as "a stroke ends
here"; canonical lines from a thick pen have round corners instead, and it
draws a box as one stroke. The start model is left as it is.

Status: see the docstring's result once the run is done.
"""

import ml_collections

from configs import fast_local


def get_config() -> ml_collections.ConfigDict:
    c = fast_local.get_config()
    c.name = "robust"
    c.data.styles = dict(clean=0.4, cv2=0.15, aa=0.15, px3=0.15, px5=0.15)
    c.train.update(
        dict(
            init_from="jdraw/checkpoints/fast_local",
            learning_rate=5e-4,
            num_steps=2400,
            checkpoint_every=100,
        )
    )
    return c
