"""Latin letters and digits scored against the order and direction schools teach.

The dev glyphs of :mod:`jdraw.data.latin` (never trained on) are drawn
``copies`` times each with a fixed random shift, scale and shear, in every
style of ``styles`` (jdraw's own lines, OpenCV's, 3-pixel lines), planned by
``jdraw.plan`` and scored as the KanjiVG test split is
(:func:`jdraw.evaluation.metrics.score`), with a 1-pixel tolerance for the
lines drawn other ways.
"""

from __future__ import annotations

import numpy as np

from jdraw.data import demos as D
from jdraw.data import kanji, latin, variants
from jdraw.evaluation import metrics
from jdraw.evaluation.batched import plan_batched
from jdraw.planner import plan as api
from jdraw.planner import ranker

STYLES = ("clean", "cv2", "px3")


def drawings(ks: kanji.KanjiSet, copies: int, style: str, seed: int = 0, strength: float = 0.5):
    """``(demos, inputs bool [N, 100, 100])``: each glyph ``copies`` times, drawn in ``style``."""
    rng = np.random.default_rng([seed, 7])
    demos, inputs = [], []
    for i in range(len(ks)):
        for _ in range(copies):
            ctrl = ks.strokes(i)
            a, t = kanji.random_affine(rng, np.concatenate(ctrl), strength)
            ctrl = [c @ a.T + t for c in ctrl]
            d = D.from_control_points(ctrl)
            demos.append(d)
            inputs.append(d.target if style == "clean" else variants.draw(ctrl, style))
    return demos, np.stack(inputs)


def evaluate_latin(
    checkpoint=None,
    *,
    glyphs: str = "dev",
    copies: int = 4,
    styles=STYLES,
    batch: int = 32,
    progress: bool = True,
    **plan_kw,
) -> dict:
    """Scores ``checkpoint`` on the Latin ``glyphs`` split; ``{style: metrics}`` in its order.

    ``plan_kw`` goes to ``jdraw.plan`` (its ``split=`` is the learned splitter's switch).
    Jdraw's own lines (``"clean"``) are scored exactly, as the paper scores, and the
    same plans again with a 1-pixel tolerance (``"clean_1px"``: issue 24's Latin bar);
    the other styles with the tolerance.
    """
    ks = latin.load(glyphs)
    rk = api.load_ranker(checkpoint)
    order = "ranker" if rk is not None else "model"
    out = {"glyphs": "".join(chr(int(c)) for c in ks.codes), "copies": copies}
    for style in styles:
        demos, inputs = drawings(ks, copies, style)
        plan = plan_batched(
            inputs, checkpoint, batch=batch, progress=progress, desc=f"latin {style}", **plan_kw
        )
        plan = ranker.reorder(plan, order, rk)
        out[style] = metrics.score(demos, plan, inputs, tol=0 if style == "clean" else 1)
        if style == "clean":
            out["clean_1px"] = metrics.score(demos, plan, inputs, tol=1)
    return out
