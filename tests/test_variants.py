"""Demonstrations laid onto lines drawn other ways (jdraw.data.variants)."""

import numpy as np
import pytest

from jdraw import geometry
from jdraw.data import demos as demo
from jdraw.data import kanji, variants
from jdraw.evaluation import metrics
from jdraw.images import canonical


def _replayed(d: demo.Demo) -> np.ndarray:
    return geometry.render_strokes([np.asarray(s, float) for s in d.strokes])


def test_laid_onto_jdraws_own_lines_the_strokes_are_jdraws(kanji_set):
    i = int(kanji.split_indices(kanji_set, "train")[10])
    ref = demo.sample(kanji_set, i)
    d = variants.on_lines(kanji_set.strokes(i), ref.target)
    assert d is not None and len(d.strokes) == len(ref.strokes)
    for a, b in zip(d.strokes, ref.strokes):
        ia, ib = (geometry.render_strokes([np.asarray(s, float)]) for s in (a, b))
        assert metrics.stroke_iou(ia[None], ib[None], tol=1)[0, 0] > 0.9
        assert np.abs(a[0] - b[0]).max() <= 1 and np.abs(a[-1] - b[-1]).max() <= 1


@pytest.mark.parametrize("style", ["px3", "px5", "cv2"])
def test_a_box_drawn_thick_keeps_kanjivgs_three_strokes(kanji_set, style):
    """口 canonicalised from a thick pen has round corners and no stroke-end ticks;
    laid onto it, the demonstration still has KanjiVG's three strokes, each
    starting and ending where KanjiVG's does."""
    ctrl = kanji_set.strokes(kanji_set.index()["053e3"])
    ink = canonical.canonicalise(variants.draw(ctrl, style))
    d = variants.on_lines(ctrl, ink, reach=3.5 if style == "px5" else 2.5)
    assert d is not None and len(d.strokes) == 3
    for s, c in zip(d.strokes, ctrl):
        curve = kanji.sample_cubics(c)
        assert np.linalg.norm(s[0] - curve[0]) <= 4 and np.linalg.norm(s[-1] - curve[-1]) <= 4
    # The target is the canonical ink (all but a few pixels), and exactly what replay draws.
    assert not (d.target & ~ink).any()
    assert np.count_nonzero(ink & ~d.target) <= 3
    assert np.array_equal(_replayed(d), d.target)
    for s in d.strokes:  # local moves, as the planner takes them
        assert np.abs(np.diff(s, axis=0)).max() <= 2


def test_strokes_that_do_not_explain_the_ink_are_refused(kanji_set):
    ctrl = kanji_set.strokes(kanji_set.index()["053e3"])
    ink = canonical.canonicalise(variants.draw(ctrl, "cv2"))
    ink[5:8, 5:60] = True  # a line no stroke draws
    assert variants.on_lines(ctrl, ink) is None
    assert variants.on_lines(ctrl[:2], canonical.canonicalise(variants.draw(ctrl, "cv2"))) is None


def test_sample_draws_styles_and_falls_back_to_clean(kanji_set):
    i = int(kanji.split_indices(kanji_set, "train")[3])
    clean = variants.sample(kanji_set, i, np.random.default_rng(1), 0.0, {"clean": 1.0})
    assert np.array_equal(clean.target, demo.sample(kanji_set, i).target)
    thick = variants.sample(kanji_set, i, np.random.default_rng(1), 0.0, {"px3": 1.0})
    assert len(thick.strokes) == len(clean.strokes)
    assert not np.array_equal(thick.target, clean.target)
    assert np.array_equal(_replayed(thick), thick.target)
    with pytest.raises(ValueError, match="unknown style"):
        variants.draw(kanji_set.strokes(i), "px4")


def test_training_batches_draw_the_configured_styles(kanji_set):
    from configs import tiny
    from jdraw.train import feed

    pool = kanji.split_indices(kanji_set, "train")[:50]
    clean, other = tiny.get_config(), tiny.get_config()
    clean.data.styles = {"clean": 1.0}
    other.data.styles = {"cv2": 1.0}
    a, _ = feed.make_batch(kanji_set, pool, clean, 3)
    b, n = feed.make_batch(kanji_set, pool, other, 3)
    again, _ = feed.make_batch(kanji_set, pool, other, 3)
    for part in ("local", "global"):  # a pure function of (seed, step)
        for k in b[part]:
            assert np.array_equal(b[part][k], again[part][k]), (part, k)
    # The first character and its augmentation are the same draw in both; its lines are not.
    ta, tb = a["local"]["target"][0], b["local"]["target"][0]
    assert not np.array_equal(ta, tb)
    assert metrics.tolerant_pixel_accuracy(ta, tb, 2) > 0.9
    loc, glo = b["local"], b["global"]
    assert not (loc["visited"][:n] & ~loc["target"][:n]).any()
    for t, s in zip(glo["target"], glo["start"]):  # every start lies on the drawn ink
        assert t.reshape(-1)[s]
