"""The learned stroke splitter and joiner (jdraw.planner.splits, jdraw.train.splitter)."""

import numpy as np
import pytest
from flax import nnx

from jdraw import geometry
from jdraw.planner import corners as corner_geometry
from jdraw.planner import joins, splits
from jdraw.planner.stroke_tokens import CONTEXT_FEATURES
from jdraw.plans import Plan
from jdraw.train import splitter as splitter_train


def _line(x0, y0, x1, y1):
    n = max(abs(x1 - x0), abs(y1 - y0))
    t = np.arange(n + 1)[:, None] / n
    return np.rint(np.array([x0, y0]) + t * np.array([x1 - x0, y1 - y0]))


def _ell():
    """Down the left side, then along the bottom: one polyline with one right angle."""
    return np.concatenate([_line(20, 20, 20, 60), _line(20, 60, 70, 60)[1:]])


def _splitter(split_bias: float, join_bias: float) -> splits.Splitter:
    """A splitter whose nets say the same for every input (zero weights, a set bias)."""
    sp = splits.Splitter(hidden=8, patches=False, rngs=nnx.Rngs(0))
    for net, bias in ((sp.split_net, split_bias), (sp.join_net, join_bias)):
        for layer in (net.l1, net.l2, net.out):
            layer.kernel[...] = layer.kernel[...] * 0
        net.out.bias[...] = net.out.bias[...] * 0 + bias
    return sp


def test_corners_finds_a_right_angle_and_no_corner_on_lines_and_arcs():
    ell = _ell()
    (k,) = corner_geometry.corners(ell)
    assert tuple(ell[k]) == (20, 60)
    assert len(corner_geometry.corners(_line(10, 10, 90, 40))) == 0
    t = np.linspace(0, np.pi / 2, 60)  # a quarter circle of radius 40: turns gently
    arc = np.stack([50 + 40 * np.cos(t), 50 + 40 * np.sin(t)], 1)
    assert len(corner_geometry.corners(arc)) == 0
    # Within MIN_ARM pixels of an end a hook is not a corner.
    hook = np.concatenate([_line(20, 20, 20, 60), _line(20, 60, 22, 60)[1:]])
    assert len(corner_geometry.corners(hook)) == 0


def test_corner_labels_split_where_two_reference_strokes_meet_only():
    ell = _ell()
    ks = corner_geometry.corners(ell)
    two = [_line(20, 20, 20, 60), _line(20, 60, 70, 60)]  # like 口's side and bottom
    one = [ell]  # one stroke that turns, like 山's second
    assert corner_geometry.corner_labels(ell, ks, two).tolist() == [True]
    assert corner_geometry.corner_labels(ell, ks, one).tolist() == [False]


def test_split_and_join_keep_every_pixel_and_join_reverses_as_needed():
    ell = _ell()
    parts = corner_geometry.split_at(ell, corner_geometry.corners(ell))
    assert len(parts) == 2 and tuple(parts[0][-1]) == tuple(parts[1][0]) == (20, 60)
    np.testing.assert_array_equal(geometry.render_strokes(parts), geometry.render_strokes([ell]))
    a, b, c = _line(10, 50, 30, 50), _line(52, 50, 31, 50), _line(53, 50, 80, 50)
    (one,) = joins.join_pairs([a, b, c], [(0, True, 1, True), (1, False, 2, False)])
    assert tuple(one[0]) == (10, 50) and tuple(one[-1]) == (80, 50)
    assert np.abs(np.diff(one, axis=0)).max() <= 2
    np.testing.assert_array_equal(
        geometry.render_strokes([one]), geometry.render_strokes([a, b, c])
    )
    # A pair that would close a ring of strokes, or reuse an end, is skipped.
    ring = joins.join_pairs([a, b], [(0, True, 1, True), (0, False, 1, False), (0, True, 1, False)])
    assert len(ring) == 1


def test_end_pairs_need_near_ends_on_ink():
    a, b = _line(10, 50, 30, 50), _line(33, 50, 60, 50)
    assert joins.end_pairs([a, b]) == [(0, True, 1, False)]
    assert joins.end_pairs([a, _line(34, 50, 60, 50)]) == []  # 4 px apart
    ink = geometry.render_strokes([a, b])
    assert joins.end_pairs([a, b], ink) == []  # the gap between them is not ink
    ink[50, 31:33] = True
    assert joins.end_pairs([a, b], ink) == [(0, True, 1, False)]
    _, x = splits.all_pairs([a, b])
    assert x.shape == (1, splits.JOIN_FEATURES)


def test_ends_either_side_of_a_crossing_join_through_the_ink():
    """A line stopped short of a crossing and taken up past it joins over the crossing."""
    a, b, c = _line(10, 50, 46, 50), _line(54, 50, 90, 50), _line(50, 20, 50, 80)
    ink = geometry.render_strokes([a, b, c])
    assert joins.end_pairs([a, b, c], ink) == []  # the pixels between are not ink
    ink[50, 46:55] = True
    assert joins.end_pairs([a, b, c]) == []  # 8 px apart: only through the ink
    assert joins.end_pairs([a, b, c], ink) == [(0, True, 1, False)]
    assert joins.end_pairs([a, b, c], ink, reach=7) == []
    pairs, x = splits.all_pairs([a, b, c], ink, patches=False)
    assert x[0, -2:].tolist() == [1.0, 1.0]  # far, 8 moves
    one, cross = joins.join_pairs([a, b, c], pairs, ink)
    assert tuple(one[0]) == (10, 50) and tuple(one[-1]) == (90, 50)
    assert np.abs(np.diff(one, axis=0)).max() == 1  # along the ink, pixel by pixel
    np.testing.assert_array_equal(geometry.render_strokes([one, cross]), ink)
    _, x = splits.all_corners([_ell(), a])
    assert x.shape == (1, splits.CORNER_FEATURES)


def test_a_stroke_that_stops_at_a_dead_end_joins_back_along_its_own_line():
    """A writer goes down a curved stem and back up it; the tracer lifts at the tip and
    starts again where the line turned back. With reach, the join retraces the curve."""
    t = np.linspace(0.0, np.pi / 2, 60)
    arc = np.stack([30 + 30 * np.cos(t), 20 + 30 * np.sin(t)], 1)  # (60, 20) to (30, 50)
    a = np.rint(arc)  # down the stem to its tip at (30, 50)
    j = int(np.argmax(np.hypot(*(a - a[-1]).T) < 22))  # where the line turns back
    b = a[j] + np.arange(21)[:, None] * [1.0, 1.0]  # and leaves it, outwards
    ink = geometry.render_strokes([a, b])
    assert joins.end_pairs([a, b], ink) == []  # too far for the default reach
    links = dict(joins.end_links([a, b], ink, reach=32))  # the stem's top is a candidate too
    link = links[(0, True, 1, False)]
    assert len(link) >= 15  # about 22 px back up the curve
    np.testing.assert_array_equal(link, joins.bridge(a[-1], b[0], ink, reach=32))
    assert ink[link[:, 1].astype(int), link[:, 0].astype(int)].all()  # back along the drawn line
    (one,) = joins.join_pairs([a, b], [(0, True, 1, False)], ink, reach=32)
    q = np.rint(one).astype(int)
    assert ink[q[:, 1], q[:, 0]].all() and np.abs(np.diff(one, axis=0)).max() <= 2
    assert tuple(one[0]) == tuple(a[0]) and tuple(one[-1]) == tuple(b[-1])
    (straight,) = joins.join_pairs([a, b], [(0, True, 1, False)], ink)  # reach 8: a straight link
    q = np.rint(straight).astype(int)
    assert not ink[q[:, 1], q[:, 0]].all()


def test_near_ends_on_either_side_of_a_cusp_are_linked_round_its_tip():
    """The two sides of a narrow hump are 2 px apart below its tip, with paper between:
    a straight link would leave the ink, so they are linked through the ink, round the
    tip, and the pair is a join candidate (it was none before 2026-12-07)."""
    left = np.array([(49.0, y) for y in range(80, 40, -1)] + [(50.0, 40.0)])  # up to the tip
    right = np.array([(50.0, 40.0)] + [(51.0, y) for y in range(41, 81)])  # and down again
    ink = geometry.render_strokes([left, right])
    up, down = left[:37], right[4:]  # the tracer lifted at (49, 44) and began at (51, 44)
    a, b = up[-1], down[0]
    assert np.abs(a - b).max() <= joins.GAP and not ink[44, 50]  # paper between them
    link = joins.bridge(a, b, ink)
    assert link is not None and len(link) == 7  # 8 moves round the tip
    assert ink[link[:, 1].astype(int), link[:, 0].astype(int)].all()
    assert link[:, 1].min() == 40
    assert (0, True, 1, False) in dict(joins.end_links([up, down], ink))
    (one,) = joins.join_pairs([up, down], [(0, True, 1, False)], ink)
    q = np.rint(one).astype(int)
    assert ink[q[:, 1], q[:, 0]].all() and np.abs(np.diff(one, axis=0)).max() <= 1
    # Without a path through the ink within reach they stay apart.
    apart = geometry.render_strokes([up, down])
    assert joins.bridge(a, b, apart) is None and joins.end_links([up, down], apart) == []


def test_long_links_go_back_over_their_own_line_only(tmp_path):
    """Beyond ``reach``, two ends are linked (up to ``retrace`` moves) only when the
    path through the ink goes back over one of the two strokes' own line."""
    stem = _line(20, 90, 20, 50)  # up a stem to its tip
    leave = _line(21, 71, 45, 95)  # and away from its middle
    ink = geometry.render_strokes([stem, leave])
    pair = (0, True, 1, False)
    assert joins.end_links([stem, leave], ink, reach=16) == []
    link = dict(joins.end_links([stem, leave], ink, reach=16, retrace=40))[pair]
    assert len(link) >= 19 and joins.own_line(link, stem, leave)
    assert (ink[link[:, 1].astype(int), link[:, 0].astype(int)]).all()
    # Ends as far apart through the ink, but over a third stroke's line: no link.
    bar, post = _line(20, 50, 60, 50), _line(60, 51, 60, 90)
    ink = geometry.render_strokes([stem, post, bar])
    assert pair in dict(joins.end_links([stem, post, bar], ink, reach=48))
    assert pair not in dict(joins.end_links([stem, post, bar], ink, reach=16, retrace=48))
    # A splitter joins with its retrace, which it keeps through a bundle folder.
    sp = _splitter(-5.0, 5.0)  # joins every candidate
    sp.reach, sp.retrace = 16, 40
    splits.save(sp, tmp_path)
    back = splits.load(tmp_path)
    assert (back.reach, back.retrace) == (16, 40)
    ink = geometry.render_strokes([stem, leave])
    (one,) = splits.join_many(back, [[stem, leave]], [ink])[0]
    assert len(one) > len(stem) + len(leave)  # part of the stem drawn twice
    assert {(20, 50), (20, 90)} <= {tuple(q) for q in one} and tuple(one[-1]) == (45, 95)
    sp.retrace = 0
    assert len(splits.join_many(sp, [[stem, leave]], [ink])[0]) == 2
    # Asked for per call (jdraw.plan's retrace=, plan_image's joined-up writing), the
    # same join as the splitter's own; asked for 0, none.
    asked = splits.join_many(sp, [[stem, leave]], [ink], retrace=40)[0]
    assert len(asked) == 1 and np.array_equal(asked[0], one)
    assert len(splits.join_many(back, [[stem, leave]], [ink], retrace=0)[0]) == 2


def test_edit_plan_follows_the_nets_and_inks_the_same_pixels():
    ell, far = _ell(), _line(60, 10, 90, 10)
    a, b = _line(10, 85, 30, 85), _line(31, 85, 60, 85)
    plan = Plan.from_strokes([[ell, far, a, b]], np.array([False]))
    cut = splits.edit_plan(plan, _splitter(5.0, -5.0))  # split every corner, join nothing
    assert len(cut.strokes[0]) == 5
    kept = splits.edit_plan(plan, _splitter(-5.0, -5.0))
    assert len(kept.strokes[0]) == 4
    joined = splits.edit_plan(plan, _splitter(-5.0, 5.0))  # a and b are one line
    assert len(joined.strokes[0]) == 3
    for p in (cut, kept, joined):
        np.testing.assert_array_equal(
            geometry.render_strokes(p.strokes[0]), geometry.render_strokes([ell, far, a, b])
        )


def test_drop_covered_keeps_the_ink_and_drops_only_strokes_drawn_over():
    a = _line(10, 50, 90, 50)
    piece, cross = _line(40, 50, 47, 50), _line(45, 20, 45, 80)
    out = splits.drop_covered([a, piece, cross])
    assert len(out) == 2 and out[0] is a and out[1] is cross
    np.testing.assert_array_equal(
        geometry.render_strokes(out), geometry.render_strokes([a, piece, cross])
    )
    twice = splits.drop_covered([a, a.copy()])  # one of two copies goes, not both
    assert len(twice) == 1


def test_a_splitter_that_joins_near_ends_only_still_loads(tmp_path):
    """The first splitters (no reach, 21 join features) load and join as they did."""
    old = splits.Splitter(hidden=8, patches=False, reach=0, rngs=nnx.Rngs(0))
    splits.save(old, tmp_path)
    back = splits.load(tmp_path)
    assert back.reach == 0 and back.join_net.l1.kernel.shape[0] == splits.NEAR_GEOMETRY
    a, b, c = _line(10, 50, 46, 50), _line(54, 50, 90, 50), _line(50, 20, 50, 80)
    ink = geometry.render_strokes([a, b, c])
    ink[50, 46:55] = True
    assert splits.all_pairs([a, b, c], ink, patches=False, reach=0)[0] == []
    pairs, x = splits.all_pairs([a, b, c], ink, patches=False, reach=back.reach)
    assert pairs == [] and x.shape == (0, splits.NEAR_GEOMETRY)
    near = [_line(10, 50, 30, 50), _line(32, 50, 60, 50)]
    _, x = splits.all_pairs(near, patches=False, reach=0)
    assert x.shape == (1, splits.NEAR_GEOMETRY)
    new = splits.Splitter(hidden=8, patches=False, rngs=nnx.Rngs(0))
    assert new.reach == joins.REACH and splits.all_pairs(
        [a, b, c], ink, patches=False, reach=new.reach
    )[1].shape == (1, joins.JOIN_GEOMETRY)


@pytest.mark.parametrize("patches", [True, False])
def test_splitter_round_trips_through_a_bundle_folder(tmp_path, patches):
    import json

    sp = splits.Splitter(hidden=8, patches=patches, rngs=nnx.Rngs(3))
    splits.save(sp, tmp_path, provenance={"config": {"name": "t"}})
    back = splits.load(tmp_path)
    assert back.patches == patches
    x = splits.all_corners([_ell()])[1]
    x = x if patches else x[:, : corner_geometry.GEOMETRY_FEATURES]
    np.testing.assert_allclose(np.asarray(back.split_net(x)), np.asarray(sp.split_net(x)))
    assert splits.load(tmp_path / "none") is None
    meta = json.loads((tmp_path / "splitter.json").read_text())
    meta["corner_features"] += 1  # made by another version of the features
    (tmp_path / "splitter.json").write_text(json.dumps(meta))
    with pytest.raises(Exception, match="retrain"):
        splits.load(tmp_path)
    (tmp_path / "splitter.npz").write_bytes(b"not an npz")
    meta["corner_features"] -= 1
    (tmp_path / "splitter.json").write_text(json.dumps(meta))
    with pytest.raises(Exception, match="splitter.npz"):
        splits.load(tmp_path)


def test_patches_show_the_ink_as_drawn_and_the_strokes_around_a_corner():
    ell = _ell()
    img = np.zeros((100, 100), bool)
    img[58:63, 18:23] = True  # a square lump of ink at the corner (20, 60)
    p = splits.patch(img, (20, 60))
    side = 2 * splits.PATCH + 1
    assert p.shape == (side * side,) and p.reshape(side, side)[3:8, 3:8].all() and p.sum() == 25
    edge = np.ones((100, 100), bool)
    assert splits.patch(edge, (0, 0)).sum() == (splits.PATCH + 1) ** 2  # off the canvas: no ink
    _, thin = splits.all_corners([ell])
    _, thick = splits.all_corners([ell], img)
    g = corner_geometry.GEOMETRY_FEATURES
    np.testing.assert_array_equal(thin[:, :g], thick[:, :g])
    assert not np.array_equal(thin[:, g:], thick[:, g:])  # the drawn ink is seen


def test_examples_label_corners_and_joins_from_the_reference_strokes():
    refs = [_line(20, 20, 20, 60), _line(20, 60, 70, 60)]
    ink = geometry.render_strokes(refs)
    xs, ys, xj, yj, cs, cj = splitter_train.examples([_ell()], refs, ink)
    assert xs.shape == (1, splits.CORNER_FEATURES) and ys.tolist() == [1.0]
    assert len(xj) == 1 and yj.tolist() == [0.0]  # cut there: the two parts are not one line
    line = [_line(10, 50, 40, 50)]
    a, b = _line(10, 50, 24, 50), _line(26, 50, 40, 50)
    xs, ys, xj, yj, _, cj = splitter_train.examples([a, b], line, geometry.render_strokes(line))
    assert len(xs) == 0 and yj.tolist() == [1.0]  # one reference line cut in two
    assert cj.shape == (1, CONTEXT_FEATURES) and cj[0, 0] == np.float32(np.log1p(2) / 3)


def test_fit_learns_a_rule_both_nets_can_see():
    rng = np.random.default_rng(0)
    xs = rng.normal(size=(400, splits.CORNER_FEATURES)).astype(np.float32)
    xj = rng.normal(size=(400, splits.JOIN_FEATURES)).astype(np.float32)
    ys, yj = (xs[:, 0] > 0).astype(np.float32), (xj[:, 1] > 0).astype(np.float32)
    model, logs = splitter_train.fit((xs, ys, xj, yj), steps=300, batch=128, hidden=16)
    assert logs[-1]["split_acc"] > 0.9 and logs[-1]["join_acc"] > 0.9
    assert model.patches


def test_join_shares_decide_which_pairs_a_batch_draws():
    """A set given all of every batch's pairs is all the join net learns from: here a
    small set of joins among many non-joins, the same features for both."""
    from jdraw.train.ranker import shares_of

    rng = np.random.default_rng(0)
    xs = rng.normal(size=(64, splits.CORNER_FEATURES)).astype(np.float32)
    xj = rng.normal(size=(400, splits.JOIN_FEATURES)).astype(np.float32)
    yj = np.zeros(400, np.float32)
    yj[:20] = 1.0  # the small set: joins
    groups = np.where(np.arange(400) < 20, "small", "big")
    data = (xs, (xs[:, 0] > 0).astype(np.float32), xj, yj)
    kw = dict(steps=150, batch=64, hidden=8, patches=False)
    plain, _ = splitter_train.fit(data, **kw)
    drawn, _ = splitter_train.fit(data, join_draw=shares_of(groups, {"small": 1.0}), **kw)
    x = xj[20:, : splits.join_width(False, joins.REACH)]
    assert (np.asarray(plain.join_net(x)) < 0).mean() > 0.9  # mostly not joins
    assert (np.asarray(drawn.join_net(x)) > 0).mean() > 0.9  # never saw a non-join


def test_negative_weights_tip_pairs_the_net_cannot_tell_apart():
    """Three joins to each non-join, all alike: the plain net says "join"; with the
    non-joins weighing 9 each they outweigh the joins and it says "do not"."""
    rng = np.random.default_rng(0)
    xs = rng.normal(size=(64, splits.CORNER_FEATURES)).astype(np.float32)
    xj = 0.05 * rng.normal(size=(400, splits.JOIN_FEATURES)).astype(np.float32)  # alike
    yj = (np.arange(400) % 4 != 0).astype(np.float32)
    groups = np.where(np.arange(400) < 200, "cursive", "kanji")
    w = splitter_train.negative_weights(groups, yj, {"cursive": 4.0})
    assert sorted(set(w.tolist())) == [1.0, 4.0]
    assert (w == 4.0).sum() == ((groups == "cursive") & (yj == 0)).sum()
    data = (xs, (xs[:, 0] > 0).astype(np.float32), xj, yj)
    kw = dict(steps=150, batch=64, hidden=8, patches=False)
    x = xj[:, : splits.join_width(False, joins.REACH)]
    plain, _ = splitter_train.fit(data, **kw)
    weighted, _ = splitter_train.fit(
        data,
        join_weight=splitter_train.negative_weights(np.full(400, "cursive"), yj, {"cursive": 9.0}),
        **kw,
    )
    assert (np.asarray(plain.join_net(x)) > 0).mean() > 0.9
    assert (np.asarray(weighted.join_net(x)) < 0).mean() > 0.9
    with pytest.raises(ValueError, match="must be > 0"):
        splitter_train.negative_weights(groups, yj, {"cursive": 0.0})


def test_cross_weight_variant_is_the_default_with_cursive_non_joins_weighed(tmp_path):
    from configs import default

    base, c = default.get_config().to_dict(), default.get_config("cross_weight").to_dict()
    assert c["stages"]["splitter"].pop("join_negatives") == {"cursive": 4.0}
    assert c["stages"] == base["stages"]
    cfg = default.get_config("cross_weight").stages.splitter
    cfg.join_negatives = {"hebrew": 2.0}  # a set the stage does not trace
    with pytest.raises(ValueError, match="not trained on.*hebrew"):
        splitter_train.train(cfg, tmp_path, progress=False)
    assert not (tmp_path / "examples").exists()  # refused before any tracing


def test_plan_refuses_split_without_a_splitter():
    from jdraw.planner import plan as api

    with pytest.raises(ValueError, match="splitter"):
        api.plan(np.zeros((1, 100, 100), bool), checkpoint="jdraw/checkpoints/paper", split=True)
    with pytest.raises(ValueError, match="retrace.*splitter"):
        api.plan(np.zeros((1, 100, 100), bool), checkpoint="jdraw/checkpoints/paper", retrace=40)
    with pytest.raises(ValueError, match="retrace must be a non-negative integer"):
        api.plan(np.zeros((1, 100, 100), bool), retrace=-1)


def test_plan_takes_a_splitter_from_a_folder(tmp_path):
    from jdraw.planner import plan as api

    img = np.zeros((1, 100, 100), bool)
    img[0, 20:60, 20] = True
    img[0, 60, 20:70] = True
    with pytest.raises(ValueError, match="no splitter"):
        api.plan(img, checkpoint="jdraw/checkpoints/paper", split=tmp_path)
    splits.save(_splitter(9.0, -9.0), tmp_path)  # cut at every corner
    (cut,) = api.plan(img, checkpoint="jdraw/checkpoints/paper", split=tmp_path).strokes
    (kept,) = api.plan(img, checkpoint="jdraw/checkpoints/paper", split=False).strokes
    assert len(kept) == 1 and len(cut) == 2


def test_examples_of_other_features_are_refused_by_name(tmp_path):
    from jdraw.train.ranker import write_chunk

    refs = [_line(20, 20, 20, 60), _line(20, 60, 70, 60)]
    ex = splitter_train.examples([_ell()], refs, geometry.render_strokes(refs))
    good, old = tmp_path / "good.npz", tmp_path / "old.npz"
    write_chunk(good, [ex])
    assert splitter_train.load_examples([good])[2].shape[1] == splits.JOIN_FEATURES
    write_chunk(old, [(ex[0], ex[1], ex[2][:, 2:], ex[3])])  # joins made before the bridge
    with pytest.raises(ValueError, match="delete them"):
        splitter_train.load_examples([old])
    write_chunk(old, [ex[:4]])  # made before examples carried their drawing's context
    assert len(splitter_train.load_examples([old])) == 4
    with pytest.raises(ValueError, match="context; delete them"):
        splitter_train.load_examples([old], context=True)


def test_a_splitter_with_context_judges_the_same_corner_by_the_drawing_around_it(tmp_path):
    # One right-angle corner and one more stroke far from it, inside the corner's box, so the
    # corner's own features are the same either way. Beside a bar the rule is to cut it (as
    # a kanji's), beside a ring to keep it (as a letter's): only the context tells them apart.
    t = np.linspace(0, 2 * np.pi, 50)
    ring = np.rint(np.stack([55 + 8 * np.cos(t), 30 + 8 * np.sin(t)], 1))
    bar = _line(45, 25, 65, 25)
    cut = [_line(20, 20, 20, 60), _line(20, 60, 70, 60)]
    parts = []
    for k in range(40):
        other = bar if k % 2 else ring
        refs = (cut if k % 2 else [_ell()]) + [other]
        parts.append(splitter_train.examples([_ell(), other], refs, geometry.render_strokes(refs)))
    data = tuple(np.concatenate([p[i] for p in parts]) for i in range(6))
    assert data[1].sum() == 20  # the corners beside a bar are cuts
    kw = dict(steps=300, batch=64, hidden=16, patches=False)
    model, _ = splitter_train.fit(data, context=True, **kw)
    splits.save(model, tmp_path)
    back = splits.load(tmp_path)
    assert back.context
    by_bar, by_ring = splits.split_many(back, [[_ell(), bar], [_ell(), ring]])
    assert len(by_bar) == 3 and len(by_ring) == 2
    blind, _ = splitter_train.fit(data, context=False, **kw)
    by_bar, by_ring = splits.split_many(blind, [[_ell(), bar], [_ell(), ring]])
    assert len(by_bar) == len(by_ring)  # without the context the corner looks the same


def test_a_splitter_ensemble_scores_its_members_mean_through_its_bundle(tmp_path):
    rng = np.random.default_rng(0)
    members = [
        splits.Splitter(hidden=8, patches=False, reach=16, context=True, rngs=nnx.Rngs(s))
        for s in range(3)
    ]
    ens = splits.ensemble(members)
    assert ens.hidden == 24 and ens.context and ens.reach == 16 and not ens.patches
    c = CONTEXT_FEATURES
    xs = rng.normal(size=(7, corner_geometry.GEOMETRY_FEATURES + c)).astype(np.float32)
    xj = rng.normal(size=(5, splits.join_width(False, 16) + c)).astype(np.float32)
    tol = 1e-5  # float32 sums in another order
    mean_split = np.mean([np.asarray(m.split_net(xs)) for m in members], 0)
    mean_join = np.mean([np.asarray(m.join_net(xj)) for m in members], 0)
    np.testing.assert_allclose(ens.split_net(xs), mean_split, atol=tol)
    np.testing.assert_allclose(ens.join_net(xj), mean_join, atol=tol)
    assert np.abs(mean_join - np.asarray(members[0].join_net(xj))).max() > 100 * tol
    splits.save(ens, tmp_path)
    back = splits.load(tmp_path)
    assert back.hidden == 24
    np.testing.assert_allclose(back.join_net(xj), mean_join, atol=tol)
    with pytest.raises(ValueError, match="same width"):
        splits.ensemble([members[0], splits.Splitter(hidden=8, patches=False, rngs=nnx.Rngs(0))])


def test_a_stage_with_members_fits_each_seed_and_writes_their_mean():
    import ml_collections

    rng = np.random.default_rng(0)
    xs = rng.normal(size=(64, splits.CORNER_FEATURES)).astype(np.float32)
    xj = rng.normal(size=(64, splits.JOIN_FEATURES)).astype(np.float32)
    data = (xs, (xs[:, 0] > 0).astype(np.float32), xj, (xj[:, 1] > 0).astype(np.float32))
    cfg = ml_collections.ConfigDict(
        dict(steps=20, batch=16, learning_rate=3e-3, seed=4, patches=False, hidden=8, members=2)
    )
    model, logs = splitter_train.fit_members(data, cfg)
    assert model.hidden == 16 and len(logs) == 2
    kw = dict(steps=20, batch=16, lr=3e-3, patches=False, hidden=8)
    one = [splitter_train.fit(data, seed=s, **kw)[0] for s in (4, 5)]
    x = xj[:, : splits.join_width(False, joins.REACH)]
    want = (np.asarray(one[0].join_net(x)) + np.asarray(one[1].join_net(x))) / 2
    np.testing.assert_allclose(model.join_net(x), want, atol=1e-5)
    cfg.members = 1
    single = splitter_train.fit_members(data, cfg)[0]
    np.testing.assert_allclose(single.join_net(x), one[0].join_net(x), atol=1e-6)


def test_long_join_examples_only_where_plan_image_asks_for_them():
    """``retrace_where="joined"``: end pairs back over a stroke's own line are examples
    in joined-up writing only, as plan_image asks for them there only."""
    x = np.arange(10, 91, dtype=np.float64)  # humps 12 px high running 80 px: joined-up
    wave = geometry.render_strokes([np.stack([x, 60 - 12 * np.abs(np.sin(np.pi * x / 16))], 1)])
    square = geometry.render_strokes([_line(20, 20, 80, 20), _line(80, 20, 80, 80)])
    square |= geometry.render_strokes([_line(20, 20, 20, 80), _line(20, 80, 80, 80)])
    assert splitter_train.retrace_for(wave, 40, "joined") == 40
    assert splitter_train.retrace_for(square, 40, "joined") == 0
    assert splitter_train.retrace_for(square, 40) == 40 and splitter_train.retrace_for(wave, 0) == 0


def test_a_splitter_stage_can_bundle_a_shorter_retrace_than_it_learned(tmp_path, monkeypatch):
    """``bundle_retrace``: the splitter learned with ``retrace`` keeps this one in its
    bundle, what jdraw.plan joins with unless asked (plan_image asks for more)."""
    import ml_collections

    rng = np.random.default_rng(0)
    xs = rng.normal(size=(64, splits.CORNER_FEATURES)).astype(np.float32)
    xj = rng.normal(size=(64, splits.JOIN_FEATURES)).astype(np.float32)
    data = (xs, (xs[:, 0] > 0).astype(np.float32), xj, (xj[:, 1] > 0).astype(np.float32))
    monkeypatch.setattr(splitter_train, "make_examples", lambda cfg, wd, progress: [])
    monkeypatch.setattr(splitter_train, "load_examples", lambda paths, context: data)
    cfg = ml_collections.ConfigDict(
        dict(
            out=str(tmp_path / "out"),
            steps=4,
            batch=16,
            learning_rate=3e-3,
            seed=0,
            patches=False,
            hidden=8,
            reach=16,
            retrace=40,
        )
    )
    splitter_train.train(cfg, tmp_path / "stage", progress=False)
    assert splits.load(tmp_path / "out").retrace == 40
    cfg.bundle_retrace = 0
    splitter_train.train(cfg, tmp_path / "stage2", progress=False)
    assert splits.load(tmp_path / "out").retrace == 0


def test_t_cuts_cut_a_line_where_another_strokes_end_meets_it():
    """A bar with a stem hanging from its middle: the bar is cut there in two, the parts
    sharing the point; an end near the bar's own end, or off its line, cuts nothing."""
    bar, stem = _line(20, 50, 80, 50), _line(50, 51, 50, 80)
    parts = corner_geometry.t_cuts([bar, stem])
    assert len(parts) == 3
    np.testing.assert_array_equal(parts[0][-1], [50, 50])
    np.testing.assert_array_equal(parts[1][0], [50, 50])
    np.testing.assert_array_equal(parts[2], stem)
    assert geometry.render_strokes(parts).tolist() == geometry.render_strokes([bar, stem]).tolist()
    assert len(corner_geometry.t_cuts([bar, _line(22, 51, 22, 80)])) == 2  # at the bar's end
    assert len(corner_geometry.t_cuts([bar, _line(50, 54, 50, 80)])) == 2  # 4 px off its line


def test_a_splitter_that_learned_t_cuts_draws_a_branch_on_the_way_through(monkeypatch):
    """Where joins may go back over the line (plan_image's joined-up writing), a splitter
    whose join net learned T's cuts a stroke where another's end meets it, so a stem can
    be drawn on the way along the bar: along to the stem, down it and back up, on along
    the bar. A cut no join takes is joined again. A splitter that did not learn T's, or
    joins that may not go back over the line, cut nothing."""
    bar, stem = _line(5, 50, 95, 50), _line(50, 51, 50, 70)  # each bar end 45 px off
    ink = geometry.render_strokes([bar, stem])
    seen = []
    real = splits.all_pairs
    monkeypatch.setattr(splits, "all_pairs", lambda *a, **k: seen.append(real(*a, **k)) or seen[-1])
    # A join net that joins the bar's parts to the stem (stroke 2 once the bar is cut) only.
    score = lambda fn, sp, x: np.array([9.0 if 2 in (i, j) else -9.0 for i, _, j, _ in seen[-1][0]])
    monkeypatch.setattr(splits, "_score", score)
    sp = _splitter(0.0, 0.0)
    assert len(splits.join_many(sp, [[bar, stem]], [ink], retrace=40)[0]) == 2
    sp.t_cuts = True
    (one,) = splits.join_many(sp, [[bar, stem]], [ink], retrace=40)
    assert len(one) == 1 and geometry.render_strokes(one).tolist() == ink.tolist()
    assert np.abs(np.diff(one[0], axis=0)).max() <= 2  # no jump: back up the stem's own line
    assert len(splits.join_many(sp, [[bar, stem]], [ink], retrace=0)[0]) == 2
    monkeypatch.setattr(splits, "_score", lambda fn, sp, x: np.full(len(x), -9.0))
    (kept,) = splits.join_many(sp, [[bar, stem]], [ink], retrace=40)
    assert len(kept) == 2
    moved = np.r_[True, np.abs(np.diff(kept[0], axis=0)).max(1) > 0]  # the cut point once
    np.testing.assert_array_equal(kept[0][moved], bar)  # the cut joined again, as it was


def test_t_cuts_survive_a_bundle_and_an_ensemble(tmp_path):
    sp = _splitter(0.0, 0.0)
    sp.t_cuts = True
    splits.save(splits.ensemble([sp, sp]), tmp_path)
    assert splits.load(tmp_path).t_cuts
    splits.save(_splitter(0.0, 0.0), tmp_path)
    assert not splits.load(tmp_path).t_cuts


def test_a_t_cut_is_labelled_by_whether_the_writer_ran_straight_through_it():
    """The two parts of a bar cut at a T are one line to join again only where a reference
    stroke runs from one straight into the other; a writer who drew the stem on the way
    (along, down the stem and back, on) came to the T twice and never went straight on."""
    left, right, stem = _line(10, 50, 40, 50), _line(40, 50, 70, 50), _line(40, 50, 40, 20)
    assert splitter_train.through(left, right, [_line(10, 50, 70, 50), stem])
    assert splitter_train.through(left, right, [_line(70, 50, 10, 50)])  # either way
    detour = np.concatenate([left, stem[1:], stem[::-1][1:], right[1:]])
    assert not splitter_train.through(left, right, [detour])
    assert not splitter_train.through(left, right, [left, right])  # two strokes meeting there
    bar, traced_stem = _line(10, 50, 70, 50), _line(40, 49, 40, 20)
    ink = geometry.render_strokes([bar, traced_stem])
    cut = corner_geometry.t_cuts([bar, traced_stem])
    seam = splits.all_pairs(cut, ink, retrace=40)[0].index((0, True, 1, False))
    for refs, rejoin in (([detour], 0.0), ([_line(10, 50, 70, 50), stem], 1.0)):
        _, _, _, yj, _, _ = splitter_train.examples(
            [bar, traced_stem], refs, ink, retrace=40, t_cuts=True
        )
        plain = splitter_train.examples([bar, traced_stem], refs, ink, retrace=40)[3]
        assert len(yj) > len(plain)  # the cut's pairs are examples too
        assert yj[seam] == rejoin  # the bar's two parts


def test_a_pairs_features_count_the_other_strokes_ends_and_lines_near_it():
    """Two ends 3 px apart on one line (meeting at x 41.5): a third stroke that starts
    2 px below the meeting point is one end near it and a line 2 px off; the pair's own
    strokes and a far stroke count for neither (their crowd gathered once or per pair)."""
    a, b = _line(10, 50, 40, 50), _line(43, 50, 80, 50)
    stem, far = _line(42, 52, 42, 80), _line(90, 90, 95, 95)
    pair = (0, True, 1, False)
    ends, lines = 14, 15  # the features' places (joins.join_features)
    for strokes, want in (([a, b, stem, far], (0.25, 0.2)), ([a, b, far], (0.0, 1.0))):
        f = joins.join_features(strokes, pair)
        assert (f[ends], f[lines]) == pytest.approx(want)
        np.testing.assert_array_equal(
            f, joins.join_features(strokes, pair, near=joins.crowd(strokes))
        )
