"""The stroke ranker trained on every script: KanjiVG, Latin letters and cursive words.

Command (after configs/splitter_mix.py, whose bundle traces):
  python train.py --config configs/ranker_mix.py --workdir runs/ranker_mix

600 traced and 2,500 demonstrated KanjiVG training characters (as the default's ranker) and ``extra``
augmented Latin letters in school order and cursive word fragments, drawn in
the mix of lines of jdraw.data.variants, planned by the bundle with its
splitter (``tracer_split``), so the ranker learns to order and turn the
strokes the planner finally draws.
"""

import ml_collections

STYLES = {"clean": 0.4, "cv2": 0.15, "aa": 0.15, "px3": 0.15, "px5": 0.15}


def get_config() -> ml_collections.ConfigDict:
    c = ml_collections.ConfigDict()
    c.name = "ranker_mix"
    c.stage = "ranker"
    c.seed = 0
    c.tracer = "runs/mix/bundle"
    c.tracer_split = True
    c.out = "runs/mix/bundle"
    c.chars = 600
    c.demo_chars = 2500
    c.extra = {"latin": 400, "cursive": 400}
    c.chunk = 100
    c.augment = 1.0
    c.styles = dict(STYLES)
    c.steps = 4000
    c.batch = 512
    c.learning_rate = 3e-3
    return c
