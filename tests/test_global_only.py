"""Ablation (c): the looped global model's segment rasteriser, raw actions, and what it learns."""

import jax.numpy as jnp
import numpy as np

from jdraw import geometry
from jdraw.data import demos as demo
from jdraw.train import global_only


def test_paint_segment_matches_the_line_rule():
    rng = np.random.default_rng(0)
    for _ in range(50):
        a, b = rng.integers(0, 100, (2, 2))
        img = np.asarray(
            geometry.paint_segment(jnp.zeros((100, 100), bool), jnp.asarray(a), jnp.asarray(b))
        )
        ref = np.zeros((100, 100), bool)
        p = geometry.segment_pixels(a, b)
        ref[p[:, 1], p[:, 0]] = True
        np.testing.assert_array_equal(img, ref)


def test_raw_actions_start_each_stroke_pen_up(kanji_set):
    d = demo.sample(kanji_set, 3)
    acts = global_only.raw_actions(d, np.random.default_rng(0))
    starts = [a for a in acts if a[1] == 0]
    assert len(starts) == len(d.strokes)
    for p, _, s in starts:
        np.testing.assert_array_equal(p, d.strokes[s][0])
    # Each stroke ends at its last pen position.
    for s, st in enumerate(d.strokes):
        last = [a for a in acts if a[2] == s][-1]
        np.testing.assert_array_equal(last[0], st[-1])


def test_global_only_trains_and_plans(tmp_path):
    import jdraw
    from configs import tiny
    from jdraw.train import loop as training

    cfg = tiny.get_config()
    cfg.model.kind = "global_only"
    cfg.train.num_steps = 3
    r = training.train(cfg, tmp_path, progress=False)
    assert r["done"] and np.isfinite(r["loss"])
    img = np.zeros((100, 100), bool)
    img[30, 20:60] = True
    p = jdraw.plan(img, checkpoint=tmp_path / "bundle", max_steps=40)
    assert p.lengths[0] <= 40
    drawn = jdraw.render(p)[0]
    assert not (drawn & ~img).any()  # pen-down moves stay between ink pixels on a line
