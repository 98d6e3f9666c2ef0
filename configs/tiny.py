"""A tiny config for tests: seconds on a 2-core CPU.

Command:
  python train.py --config configs/tiny.py --workdir /tmp/jdraw-tiny

Wall time: 58 s for the command (27 s of training-loop time, the rest loading
KanjiVG, compiling and validating) on the 2-core CPU at load average ~3.
Result: the loss falls from 9.4 (step 5) to 5.0 (step 30) with 103 strokes fed;
validation on 4 characters: pixel accuracy 1.0, stroke accuracy 0.21 (far too
small and briefly trained to draw well). Trained 40 steps on 4 unaugmented
characters it plans them at stroke accuracy 0.65, untrained 0.04
(tests/test_learning.py).
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
