"""The reading-direction detector (jdraw.images.reading): right-to-left script or not.

Command:
  python train.py --config configs/reading_direction.py --workdir runs/reading_direction

Needs the fonts of jdraw.data.fonts.DETECTOR_TRAIN and DETECTOR_EVAL:
  apt-get install culmus fonts-kacst fonts-arabeyes fonts-sil-scheherazade \
    fonts-dejavu-core fonts-liberation fonts-kaushanscript fonts-noto-core fonts-noto-cjk \
    fonts-freefont-ttf fonts-sil-ezra fonts-hosny-amiri fonts-dancingscript

Random letters of 15 scripts set in the training fonts (words_per_script
drawings each) and random sketches are cut into line windows; a three-layer
CNN (about 4,700 weights) is fitted on them and written to ``out``, the
package's jdraw/assets/reading, with its provenance and its accuracy on
drawings set in the held-out fonts.

Wall time and result: see jdraw/assets/reading/direction.json ("seconds",
"held_out_accuracy") and docs/reading_direction.md.
"""

import ml_collections


def get_config() -> ml_collections.ConfigDict:
    c = ml_collections.ConfigDict()
    c.name = "reading_direction"
    c.stage = "reading"
    c.seed = 0
    c.out = "jdraw/assets/reading"
    c.words_per_script = 150  # drawings per script
    c.sketches = 200
    c.min_height = 30  # px, ink height of a drawing
    c.max_height = 160
    c.two_words = 0.3  # fraction of drawings with two words
    c.marker = 0.4  # fraction drawn with a thick outline (a marker)
    c.slant = 0.4  # fraction sheared like slanted handwriting
    c.channels = (8, 16, 24)
    c.steps = 3000
    c.batch = 256
    c.learning_rate = 3e-3
    c.eval_words_per_font = 12
    return c


def tiny() -> ml_collections.ConfigDict:
    """A few drawings and steps: what the tests run."""
    c = get_config()
    c.words_per_script = 2
    c.sketches = 2
    c.steps = 3
    c.batch = 16
    c.eval_words_per_font = 1
    return c
