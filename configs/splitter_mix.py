"""The stroke splitter trained on every script: KanjiVG, Latin letters and cursive words.

Command (the tracer is the bundled default's local and start models, planned
without a splitter; ``out`` is a bundle folder holding the default's params):
  python train.py --config configs/splitter_mix.py --workdir runs/splitter_mix

As the default's splitter (there 9,000, here the first 5,000 of the same traced
KanjiVG training characters, drawn in
the mix of lines of jdraw.data.variants, ends joined through the ink up to 8
px apart), plus ``extra``: augmented Latin letters and digits in school order
(jdraw.data.latin, train glyphs) and fragments of cursive words
(jdraw.data.cursive, train words), traced the same way. The KanjiVG chunks are
the first 5,000 of those the default's splitter was fitted to (same seeds); the other sets'
draws are salted apart.
"""

import ml_collections

STYLES = {"clean": 0.4, "cv2": 0.15, "aa": 0.15, "px3": 0.15, "px5": 0.15}


def get_config() -> ml_collections.ConfigDict:
    c = ml_collections.ConfigDict()
    c.name = "splitter_mix"
    c.stage = "splitter"
    c.seed = 0
    c.tracer = "jdraw/checkpoints/default"
    c.out = "runs/mix/bundle"
    c.chars = 5000
    c.extra = {"latin": 1500, "cursive": 2000}
    c.chunk = 100
    c.augment = 1.0
    c.styles = dict(STYLES)
    c.patches = False
    c.reach = 8
    c.hidden = 64
    c.steps = 3000
    c.batch = 512
    c.learning_rate = 3e-3
    return c
