"""The stroke splitter of the lean planner: where a drawn stroke ends, where two are one.

The first splitter, bundled until configs/splitter_reach.py: it joins stroke
ends at most 3 px apart only. Kept in jdraw/checkpoints/splitter_near.

Command (after configs/lean_start.py, whose bundle traces):
  python train.py --config configs/splitter_lean.py --workdir runs/splitter_lean

The tracer plans ``chars`` augmented training characters drawn in the mix of
configs/robust.py (jdraw's own lines, OpenCV's, anti-aliased, 3- and 5-pixel
pens), as for configs/ranker_lean.py. Every sharp corner of a drawn stroke is
a split example, every pair of stroke ends close together on ink a join
example (jdraw.train.splitter); two small MLPs (jdraw.planner.splits.Splitter)
are fitted to them and written into ``out`` (splitter.npz, splitter.json),
where ``jdraw.plan`` finds them.

Wall time: about 9 min on the 2-core CPU (9,000 traced characters 509 s, the
fit 6 s): 27,990 corners (3,956 splits) and 24,683 pairs of ends (2,402 joins).
Copied beside the default's params and ranker (jdraw/checkpoints/default), the
whole test split (python eval.py --name beyond_lean_split --n 1 at d997b29;
now --split jdraw/checkpoints/splitter_near): stroke
accuracy 0.9801 -> 0.9866 and order over all pairs 0.9499 -> 0.9588 on jdraw's
lines; on OpenCV's lines 0.9714 -> 0.9861; on 3-px lines 0.9169 -> 0.9492
(strokes / true 0.944 -> 1.005, order over all pairs 0.7741 -> 0.9122); on
5-px lines 0.8704 -> 0.8951 (results/beyond_lean_split.json against
results/beyond_lean.json).
"""

import ml_collections

from configs import robust


def get_config() -> ml_collections.ConfigDict:
    c = ml_collections.ConfigDict()
    c.name = "splitter_lean"
    c.stage = "splitter"
    c.seed = 0
    c.tracer = "runs/lean_start/bundle"
    c.out = "runs/splitter_lean/bundle"
    c.chars = 9000
    c.chunk = 100
    c.augment = 1.0
    c.styles = robust.get_config().data.styles
    c.patches = False  # the nets see each corner's and join's geometry only
    c.reach = 0  # join ends a few pixels apart only (configs/splitter_reach.py: through the ink)
    c.hidden = 64
    c.steps = 3000
    c.batch = 512
    c.learning_rate = 3e-3
    return c
