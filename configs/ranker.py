"""The stroke ranker (jdraw.planner.ranker): learned order and direction of traced strokes.

Command:
  python train.py --config configs/ranker.py --workdir runs/ranker

The tracer (``tracer``: a planner bundle) plans ``chars`` augmented KanjiVG
training characters; each drawn stroke is labelled with the KanjiVG stroke it
matches, and a pairwise order MLP and a heading MLP are fitted to those
labels (RankNet loss). The ranker is written into ``out`` (ranker.npz and
ranker.json beside the planner's params), where ``jdraw.plan`` finds it.

``demo_chars`` more characters add KanjiVG's own strokes (cheap: no planning).

Wall time: about 35 min on the shared 2-core CPU (load average ~10), almost
all of it making examples (300 traced characters took 404 s); the fit, 4,000
steps of 512 pairs, 19 s. Result: 241,680 ordered pairs and 35,829 heading
examples; on 48 validation characters traced by configs/ours.py, order
agreement 0.78 -> 0.84 (matched pairs), 0.80 -> 0.85 (all pairs), exact order
0.52 -> 0.65, direction 0.957 -> 0.980. Test split: results/beyond.md.
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
