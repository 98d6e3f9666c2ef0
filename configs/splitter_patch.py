"""The stroke splitter that also looks at the ink around each corner and join.

Command (after configs/lean_start.py, whose bundle traces):
  python train.py --config configs/splitter_patch.py --workdir runs/splitter_patch

As configs/splitter_lean.py, but each corner's and each join's features also
hold three 11x11 patches around it (jdraw.planner.splits.all_corners,
all_pairs): the ink as drawn before it was canonicalised (a thick pen's outline
is square where two strokes meet with an overshoot and round where one turns),
the stroke's own pixels and the other strokes' pixels; more characters, since
the nets have more inputs.

Wall time: about 9 min on the 2-core CPU (9,000 traced characters 509 s, the
fit 6 s). Result (not bundled): on 96 validation characters,
``PYTHONPATH=. python bench/canonical_variants.py --n 96 --split val
--styles clean,cv2,thick2,thick3 --splitter runs/splitter_patch/bundle``
against the same without ``--splitter`` (the default's, geometry only, fitted
to the same examples): stroke accuracy 0.9858 / 0.9873 / 0.9515 / 0.8887 on
jdraw's, OpenCV's, 3-px and 5-px lines against 0.9862 / 0.9851 / 0.9534 /
0.8887; order over all pairs 0.9610 / 0.9554 / 0.9246 / 0.7938 against
0.9626 / 0.9577 / 0.9187 / 0.7850. The fit reaches 100% on its training
examples within 1,500 steps (fewer steps did no better on validation): the
patches let it learn the examples, not more of the rule.
"""

import ml_collections

from configs import splitter_lean


def get_config() -> ml_collections.ConfigDict:
    c = splitter_lean.get_config()
    c.name = "splitter_patch"
    c.out = "runs/splitter_patch/bundle"
    c.chars = 9000
    c.patches = True
    return c
