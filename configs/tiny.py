"""A tiny config for tests: seconds on a 2-core CPU.

Command:
  python train.py --config configs/tiny.py --workdir /tmp/jdraw-tiny

Result: the loss falls over 30 steps (tests/test_training.py checks it);
the model is far too small and briefly trained to draw well.
"""

import ml_collections

from configs import paper


def get_config() -> ml_collections.ConfigDict:
    c = paper.get_config()
    c.name = "tiny"
    c.model.hidden = 16
    c.train.update(
        dict(
            windows=64,
            strokes=8,
            max_len=96,
            strokes_per_char=2,
            global_batch=2,
            num_steps=30,
            log_every=5,
            checkpoint_every=10,
            learning_rate=3e-3,
        )
    )
    c.eval.update(dict(every=0, val_chars=4))
    return c
