"""The stroke ranker: exact pixels after reordering, antisymmetric scores, and it learns."""

import numpy as np
import pytest
from flax import nnx

import jdraw
from jdraw import geometry
from jdraw.planner import ranker
from jdraw.plans import Plan, render, strokes_from_actions
from jdraw.train import ranker as ranker_train


def _plan_of(strokes_list):
    rows = [ranker.actions_from_strokes(s) for s in strokes_list]
    T = max(len(r) for r in rows)
    actions = np.zeros((len(rows), T, 3), np.int32)
    for b, r in enumerate(rows):
        actions[b, : len(r)] = r
    strokes = [strokes_from_actions(a, len(r)) for a, r in zip(actions, rows)]
    return Plan(strokes, actions, np.array([len(r) for r in rows]), np.zeros(len(rows), bool))


def _bars(rng, n):
    """``n`` horizontal bars at distinct random heights, drawn in a random order."""
    ys = rng.choice(np.arange(5, 95, 4), n, replace=False)
    strokes = [np.array([[10 + rng.integers(5), y], [80 + rng.integers(5), y]], float) for y in ys]
    return [strokes[k] for k in rng.permutation(n)]


def test_reorder_keeps_every_pixel_and_replays(rng):
    plan = _plan_of([_bars(rng, 5), _bars(rng, 3)])
    model = ranker.Ranker(rngs=nnx.Rngs(0))  # untrained: arbitrary orders and flips
    for method in ("xy", "ranker"):
        out = ranker.reorder(plan, method, model)
        assert np.array_equal(render(out), render(plan))
        for b in range(len(out)):
            replay = strokes_from_actions(out.actions[b], out.lengths[b])
            assert np.array_equal(geometry.render_strokes(replay), render(out)[b])
            assert len(replay) == len(plan.strokes[b])


def test_xy_sorts_by_start():
    s = [np.array([[50.0, 50], [60, 50]]), np.array([[5.0, 5], [9, 5]])]
    out = ranker.reorder(_plan_of([s]), "xy")
    assert out.strokes[0][0][0].tolist() == [5, 5]


def test_scores_are_antisymmetric(rng):
    model = ranker.Ranker(rngs=nnx.Rngs(1))
    tk = ranker.tokens(_bars(rng, 4))
    x_ab = ranker.pair_inputs(tk.feats, tk.rel, np.array([0, 1]), np.array([2, 3]))
    x_ba = ranker.pair_inputs(tk.feats, tk.rel, np.array([2, 3]), np.array([0, 1]))
    np.testing.assert_allclose(model.pair(x_ab, x_ba), -model.pair(x_ba, x_ab), atol=1e-6)
    np.testing.assert_allclose(
        model.heading(tk.feats, tk.rfeats), -model.heading(tk.rfeats, tk.feats), atol=1e-6
    )


def test_ranker_learns_top_to_bottom_and_left_to_right(rng):
    # Reference: bars top to bottom, each drawn left to right; shown drawn any way.
    parts = []
    for _ in range(60):
        ref = sorted(_bars(rng, 4), key=lambda s: s[0, 1])
        drawn = [s[::-1] if rng.random() < 0.5 else s for s in ref]
        imgs = np.stack([geometry.render_strokes([s]) for s in ref])
        perm = rng.permutation(4)
        parts.append(ranker_train.examples([drawn[k] for k in perm], imgs, ref))
    data = tuple(np.concatenate([p[i] for p in parts]) for i in range(5))
    model, logs = ranker_train.train_ranker(data, steps=300, batch=128)
    right = 0
    for _ in range(10):
        ref = sorted(_bars(rng, 5), key=lambda s: s[0, 1])
        shown = [ref[k][::-1] for k in rng.permutation(5)]
        out = ranker.reorder(_plan_of([shown]), "ranker", model).strokes[0]
        ys = [s[0][1] for s in out]
        right += ys == sorted(ys) and all(s[0][0] < s[-1][0] for s in out)
    assert right >= 9, logs


def test_plan_order_option_validated():
    import pytest

    with pytest.raises(ValueError, match="order"):
        jdraw.plan(np.zeros((100, 100)), order="alphabetical")


def test_reverse_inks_the_same_pixels_with_few_extra_rows(rng):
    moves = np.array([[dx, dy] for dx in range(-2, 3) for dy in range(-2, 3) if dx or dy])
    for _ in range(100):
        p = np.cumsum(np.vstack([[50, 50], moves[rng.integers(len(moves), size=15)]]), 0)
        r = ranker.reverse(p)
        same = geometry.render_strokes([p], (200, 200)) == geometry.render_strokes([r], (200, 200))
        assert same.all() and (r[0] == p[-1]).all() and (r[-1] == p[0]).all()
        knights = np.sum(np.sort(np.abs(np.diff(p, axis=0)), 1) == [1, 2], 1) == 2
        assert len(r) <= len(p) + knights.sum()


def test_flipping_keeps_a_plan_within_its_step_bound(rng):
    plan = _plan_of([_bars(rng, 4)])
    model = ranker.Ranker(rngs=nnx.Rngs(0))
    bound = int(plan.lengths[0])
    out = ranker.reorder(plan, "ranker", model, max_rows=bound)
    assert out.lengths[0] <= bound


def test_flipped_tokens_equal_tokens_of_reversed_strokes(rng):
    from jdraw.data import demos as demo
    from jdraw.data import kanji

    ks = kanji.load(progress=False)
    d = demo.sample(ks, int(kanji.split_indices(ks, "test")[7]))
    flip = rng.random(len(d.strokes)) < 0.5
    tk0 = ranker.tokens(d.strokes)
    tk = ranker.flipped(tk0, flip)
    ref = ranker.tokens([p[::-1] if f else p for p, f in zip(tk0.paths, flip)])  # pixel paths
    np.testing.assert_array_equal(tk.feats, ref.feats)
    np.testing.assert_array_equal(tk.rfeats, ref.rfeats)
    np.testing.assert_array_equal(tk.rel, ref.rel)


def test_characters_ordered_together_as_one_at_a_time(rng):
    # order_many scores every character's strokes in fixed-size chunks, so a
    # character's order and flips do not depend on what it is batched with.
    model = ranker.Ranker(rngs=nnx.Rngs(2))
    chars = [
        [b[::-1] if rng.random() < 0.5 else b for b in _bars(rng, int(n))]  # either way round
        for n in rng.integers(0, 20, 12)
    ]
    together = ranker.order_many(model, chars)
    assert together == [ranker.order_strokes(model, c) for c in chars]
    assert sum(len(c) ** 2 for c in chars) > ranker.CHUNK
    assert any(any(f) for _, f in together) and any(o != sorted(o) for o, _ in together)


def _counted_bars(rng, n):
    """``n`` bars and their reference order: 3 bars go top to bottom, 5 bottom to top."""
    ref = sorted(_bars(rng, n), key=lambda s: s[0, 1], reverse=n == 5)
    return ref


def _fit(rng, context):
    parts = []
    for k in range(80):
        ref = _counted_bars(rng, 3 if k % 2 else 5)
        imgs = np.stack([geometry.render_strokes([s]) for s in ref])
        perm = rng.permutation(len(ref))
        parts.append(ranker_train.examples([ref[p] for p in perm], imgs, ref))
    data = tuple(np.concatenate([p[i] for p in parts]) for i in range(7))
    return ranker_train.train_ranker(data, steps=400, batch=128, context=context)[0]


def _right(model, rng):
    right = 0
    for k in range(20):
        ref = _counted_bars(rng, 3 if k % 2 else 5)
        shown = [ref[p] for p in rng.permutation(len(ref))]
        out = ranker.reorder(_plan_of([shown]), "ranker", model).strokes[0]
        right += [s[0][1] for s in out] == [s[0][1] for s in ref]
    return right


def test_a_ranker_with_context_learns_rules_that_depend_on_the_whole_drawing(rng):
    # The rule depends on how many bars there are, which no single stroke or pair shows.
    with_ctx, without = _right(_fit(rng, True), rng), _right(_fit(rng, False), rng)
    assert with_ctx >= 18, (with_ctx, without)
    assert without <= 15, (with_ctx, without)


def test_context_does_not_depend_on_which_way_strokes_are_drawn(rng):
    from jdraw.data import demos as demo
    from jdraw.data import kanji

    ks = kanji.load(progress=False)
    d = demo.sample(ks, int(kanji.split_indices(ks, "test")[3]))
    flip = rng.random(len(d.strokes)) < 0.5
    tk = ranker.tokens(d.strokes)
    c = ranker.drawing_context(tk)
    np.testing.assert_array_equal(c, ranker.drawing_context(ranker.flipped(tk, flip)))
    t = np.linspace(0, 2 * np.pi, 60)
    circle = np.stack([50 + 20 * np.cos(t), 50 + 20 * np.sin(t)], 1)
    ring = ranker.drawing_context(ranker.tokens([circle]))
    assert ring[7] == 1.0 and ring[5] > 0.7  # one closed stroke that turns about once
    assert c[7] == 0.0 and not np.array_equal(c, ring)


def test_a_ranker_with_context_keeps_it_through_its_bundle(rng, tmp_path):
    model = ranker.Ranker(context=True, rngs=nnx.Rngs(3))
    ranker.save(model, tmp_path)
    back = ranker.load(tmp_path)
    assert back.context
    chars = [_bars(rng, 4), _bars(rng, 6)]
    assert ranker.order_many(back, chars) == ranker.order_many(model, chars)
    import json

    old = tmp_path / "old"  # a bundle from before the context: no "context" in its json
    ranker.save(ranker.Ranker(rngs=nnx.Rngs(3)), old)
    meta = json.loads((old / "ranker.json").read_text())
    del meta["context"]
    (old / "ranker.json").write_text(json.dumps(meta))
    assert not ranker.load(old).context
    assert ranker.order_many(ranker.load(old), chars)


def test_examples_made_before_the_context_train_a_ranker_without_it_only(rng, tmp_path):
    ref = sorted(_bars(rng, 3), key=lambda s: s[0, 1])
    imgs = np.stack([geometry.render_strokes([s]) for s in ref])
    old = tmp_path / "old.npz"
    ranker_train.write_chunk(old, [ranker_train.examples(ref[::-1], imgs, ref)[:5]])
    assert len(ranker_train.load_examples([old])) == 5
    import pytest

    with pytest.raises(ValueError, match="context; delete them"):
        ranker_train.load_examples([old], context=True)


def test_shares_of_gives_each_named_set_its_share_and_the_rest_by_size():
    groups = np.array(["kanji"] * 90 + ["latin"] * 6 + ["cursive"] * 4)
    index, p = ranker_train.shares_of(groups, {"cursive": 0.5})
    assert [("cursive", "kanji", "latin")[i] for i in index[[0, 90, 96]]] == [
        "kanji",
        "latin",
        "cursive",
    ]
    np.testing.assert_allclose(p, [0.5, 0.5 * 90 / 96, 0.5 * 6 / 96], atol=1e-12)
    # A set the config trains on that gave no examples is left out, the rest scaled up.
    _, p = ranker_train.shares_of(
        groups[:96], {"cursive": 0.5}, known=("kanji", "latin", "cursive")
    )
    np.testing.assert_allclose(p, [90 / 96, 6 / 96], atol=1e-12)
    with pytest.raises(ValueError, match="not trained on"):
        ranker_train.shares_of(groups, {"hebrew": 0.1})
    with pytest.raises(ValueError, match="summing to <= 1"):
        ranker_train.shares_of(groups, {"latin": 0.7, "cursive": 0.6})


def test_heading_shares_decide_whose_rule_a_ranker_learns(rng):
    # Two sets whose strokes look the same but are drawn opposite ways: the set that
    # fills more of every batch decides which way the ranker heads such a stroke.
    F, P, C = ranker.STROKE_FEATURES, ranker.PAIR_FEATURES, ranker.CONTEXT_FEATURES
    one = lambda k: np.tile(rng.normal(size=(1, k)).astype(np.float32), (100, 1))  # noqa: E731
    f, rf, ch = one(F), one(F), one(C)
    lab = np.r_[np.ones(90), np.zeros(10)].astype(np.float32)  # 90 one way, 10 the other
    x_ab, cp = rng.normal(size=(16, P)).astype(np.float32), np.zeros((16, C), np.float32)
    data = (x_ab, x_ab[::-1], f, rf, lab, cp, ch)
    groups = np.r_[np.zeros(90), np.ones(10)].astype(int)

    def heading(draw):
        kw = dict(steps=150, batch=64, hidden=8, context=True)
        model, _ = ranker_train.train_ranker(data, heading_draw=draw, **kw)
        x, rx = np.concatenate([f[:1], ch[:1]], -1), np.concatenate([rf[:1], ch[:1]], -1)
        return float(model.heading(x, rx)[0])

    assert heading(None) > 0  # drawn uniformly: the larger set's way
    assert heading((groups, np.array([0.1, 0.9]))) < 0  # the smaller set fills the batches


def test_an_ensemble_scores_the_mean_of_its_members_and_keeps_it_through_its_bundle(rng, tmp_path):
    members = [ranker.Ranker(16, context=True, rngs=nnx.Rngs(s)) for s in range(3)]
    ens = ranker.ensemble(members)
    assert ens.hidden == 48 and ens.context
    tk = ranker.tokens(_bars(rng, 5))
    ctx = ranker.drawing_context(tk)
    i, j = np.meshgrid(np.arange(5), np.arange(5), indexing="ij")
    x_ab = ranker.with_context(ranker.pair_inputs(tk.feats, tk.rel, i.ravel(), j.ravel()), ctx)
    x_ba = ranker.with_context(ranker.pair_inputs(tk.feats, tk.rel, j.ravel(), i.ravel()), ctx)
    f, rf = ranker.with_context(tk.feats, ctx), ranker.with_context(tk.rfeats, ctx)
    tol = 1e-5  # float32 sums in another order
    mean_pair = np.mean([np.asarray(m.pair(x_ab, x_ba)) for m in members], 0)
    mean_heading = np.mean([np.asarray(m.heading(f, rf)) for m in members], 0)
    np.testing.assert_allclose(ens.pair(x_ab, x_ba), mean_pair, atol=tol)
    np.testing.assert_allclose(ens.heading(f, rf), mean_heading, atol=tol)
    assert np.abs(mean_pair - np.asarray(members[0].pair(x_ab, x_ba))).max() > 100 * tol
    ranker.save(ens, tmp_path)
    back = ranker.load(tmp_path)
    np.testing.assert_allclose(back.pair(x_ab, x_ba), mean_pair, atol=tol)
    chars = [_bars(rng, 4), _bars(rng, 6)]
    assert ranker.order_many(back, chars) == ranker.order_many(ens, chars)
    with pytest.raises(ValueError, match="same width"):
        ranker.ensemble([members[0], ranker.Ranker(8, context=True, rngs=nnx.Rngs(0))])


def test_a_stage_with_members_fits_each_seed_and_writes_their_mean(rng):
    import ml_collections

    F, P, C = ranker.STROKE_FEATURES, ranker.PAIR_FEATURES, ranker.CONTEXT_FEATURES
    f, rf = rng.normal(size=(50, F)).astype(np.float32), rng.normal(size=(50, F)).astype(np.float32)
    ch, cp = rng.normal(size=(50, C)).astype(np.float32), np.zeros((16, C), np.float32)
    x_ab = rng.normal(size=(16, P)).astype(np.float32)
    data = (x_ab, x_ab[::-1], f, rf, (rng.random(50) < 0.5).astype(np.float32), cp, ch)
    cfg = ml_collections.ConfigDict(
        dict(steps=30, batch=16, learning_rate=3e-3, seed=4, context=True, hidden=8, members=2)
    )
    model, logs = ranker_train.fit_members(data, cfg)
    assert model.hidden == 16 and len(logs) == 2
    kw = dict(steps=30, batch=16, lr=3e-3, context=True, hidden=8)
    one = [ranker_train.train_ranker(data, seed=s, **kw)[0] for s in (4, 5)]
    x, rx = np.concatenate([f, ch], -1), np.concatenate([rf, ch], -1)
    want = (np.asarray(one[0].heading(x, rx)) + np.asarray(one[1].heading(x, rx))) / 2
    np.testing.assert_allclose(model.heading(x, rx), want, atol=1e-5)
    cfg.members = 1
    single = ranker_train.fit_members(data, cfg)[0]
    np.testing.assert_allclose(single.heading(x, rx), one[0].heading(x, rx), atol=1e-6)
