"""Ours, robust, second stage: the start model fine-tuned on lines drawn other ways.

Command (after configs/robust.py, whose bundle it starts from):
  python train.py --config configs/robust_start.py --workdir runs/robust_start

The local model of configs/robust.py learned to end strokes at round
corners; the start model (configs/ours.py) has seen only jdraw's own lines.
This stage trains the start model alone (the local model's loss is not
computed) on the same mix of drawings, canonicalised, with KanjiVG's strokes
laid onto them (jdraw.data.variants): 32 stroke starts a step, 4 from each
character, Adam 2e-4.

Wall time: 300 steps (9,600 stroke starts) in 2 min 15 s of training-loop
time on the 2-core CPU. Validation (48 characters, as traced): order over all
pairs 0.826 -> 0.886, stroke accuracy 0.966, direction 0.988. The bundle
(runs/robust_start/bundle) with the ranker of configs/ranker_robust.py is
jdraw/checkpoints/robust (the default until configs/lean.py).
"""

import ml_collections

from configs import robust


def get_config() -> ml_collections.ConfigDict:
    c = robust.get_config()
    c.name = "robust_start"
    c.train.update(
        dict(
            init_from="runs/robust/bundle",
            train_local=False,
            learning_rate=2e-4,
            global_batch=32,
            global_per_char=4,
            global_weight=1.0,
            num_steps=300,
            log_every=20,
            checkpoint_every=100,
        )
    )
    return c
