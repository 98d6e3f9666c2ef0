"""The stroke ranker of the lean planner with its splitter, trained on the strokes it draws.

Command (after configs/lean_start.py and configs/splitter_lean.py):
  mkdir -p runs/lean_split && cp -r runs/lean_start/bundle runs/lean_split/ &&
    cp runs/splitter_lean/bundle/splitter.* runs/lean_split/bundle/
  python train.py --config configs/ranker_split.py --workdir runs/ranker_split

As configs/ranker_lean.py, but the tracer cuts and joins its strokes with the
learned splitter (jdraw.planner.splits) before they are labelled, as
``jdraw.plan`` does with the bundled default, so the ranker learns to order
the strokes it will be given.

Wall time: about 3 min on the 2-core CPU. Result (not bundled): on 96
validation characters (seed 1) planned by the default with its splitter, order
over all pairs 0.9624 -> 0.9642 on jdraw's lines, 0.9568 -> 0.9582 on OpenCV's,
0.9093 -> 0.9072 on 3-px lines, and exact order lower on every drawing
(0.396 -> 0.375 on jdraw's lines): no better than the default's ranker
(configs/ranker_lean.py), which stays.
"""

import ml_collections

from configs import ranker_lean


def get_config() -> ml_collections.ConfigDict:
    c = ranker_lean.get_config()
    c.name = "ranker_split"
    c.tracer = "runs/lean_split/bundle"
    c.out = "runs/ranker_split/bundle"
    return c
