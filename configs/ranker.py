"""The stroke ranker (jdraw.ranker): learned order and direction of traced strokes.

Command:
  python train.py --config configs/ranker.py --workdir runs/ranker

The tracer (``tracer``: a planner bundle) plans ``chars`` augmented KanjiVG
training characters; each drawn stroke is labelled with the KanjiVG stroke it
matches, and a pairwise order MLP and a heading MLP are fitted to those
labels (RankNet loss). The ranker is written into ``out`` (ranker.npz and
ranker.json beside the planner's params), where ``jdraw.plan`` finds it.

Wall time and result: measured numbers are in results/beyond.md, with the
command that made each.
"""

import ml_collections


def get_config() -> ml_collections.ConfigDict:
    c = ml_collections.ConfigDict()
    c.name = "ranker"
    c.stage = "ranker"
    c.seed = 0
    c.tracer = "runs/ours/bundle"  # whose strokes the ranker learns to order
    c.out = "runs/ranker/bundle"
    c.chars = 300
    c.demo_chars = 2500
    c.chunk = 100
    c.augment = 1.0
    c.steps = 4000
    c.batch = 512
    c.learning_rate = 3e-3
    return c
