"""Row 1 of Table I: the paper's model (Fig. 2), trained on KanjiVG.

Command:
  python train.py --config configs/paper.py --workdir runs/paper

  python eval.py --checkpoint jdraw/checkpoints/paper --name paper   # Table I row 1

Wall time: 74 min of training-loop time (76 min with validation) on the 2-core
CPU, shared with other jobs for most of the run; the same command resumes
from the last Orbax checkpoint. Result (results/table1.md, eval.py): pixel
accuracy 1.0000 (1.0000) and stroke accuracy 0.9679 (0.9684) on 100 random
train (test) characters, the paper's 0.9630 (0.9646); the whole test split,
1.0000 / 0.9718. 100,077 strokes fed. Validation stroke accuracy (48
characters): 0.83 (step 500), 0.90 (1,000), 0.93 (2,000), 0.95 (3,000), 0.96
(3,600). The bundle is jdraw/checkpoints/paper.

Budget: the paper fed 100,000 stroke samples to each model in Table I. A step
packs whole strokes into 512 encoder windows (about 28 strokes; the KanjiVG
strokes average 17 local steps), so 3,600 steps feed about 100,000 strokes;
the run logs the exact count (strokes_seen). Each step also trains the
global model on 8 stroke starts.
"""

import ml_collections


def get_config() -> ml_collections.ConfigDict:
    c = ml_collections.ConfigDict()
    c.name = "paper"
    c.seed = 0
    c.model = ml_collections.ConfigDict(
        dict(hidden=256, core="lstm", extraction="late", kind="two_scale")
    )
    c.data = ml_collections.ConfigDict(dict(augment=1.0))
    c.train = ml_collections.ConfigDict(
        dict(
            learning_rate=1e-4,  # Adam, as the paper
            windows=512,  # encoder windows (local steps) per batch
            strokes=64,  # stroke slots per batch (LSTM rows)
            max_len=96,  # local steps per stroke (longest KanjiVG stroke: 88)
            strokes_per_char=4,
            global_batch=8,
            global_weight=1.0,
            num_steps=3600,
            log_every=20,
            checkpoint_every=200,
        )
    )
    c.eval = ml_collections.ConfigDict(dict(every=500, val_chars=48))
    return c
