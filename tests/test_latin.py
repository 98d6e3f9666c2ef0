"""The Latin table (jdraw.data.latin): what the school model says, as demonstrations."""

import numpy as np

from jdraw.data import demos as demo
from jdraw.data import latin, mix


def _first_last(g):
    s = latin.GLYPHS[g]
    return s[0][0], s[0][-1]


def test_table_follows_the_school_rules():
    # One stroke each where the school model writes one.
    for g in "023678NMSZsovzCGO":
        assert len(latin.GLYPHS[g]) == 1, g
    # Strokes start at the top: straight strokes are pulled down, bars slide right.
    for g in "EFHILT":
        start, end = _first_last(g)
        assert start[1] < end[1], g  # the stem first, top to bottom
    for g, k in [("E", 1), ("E", 2), ("E", 3), ("t", 1), ("f", 1)]:
        bar = latin.GLYPHS[g][k]
        assert bar[0][0] < bar[-1][0], (g, k)  # left to right
    # E's bars top to bottom; 5's top bar last; i and j dotted last.
    assert [latin.GLYPHS["E"][k][0][1] for k in (1, 2, 3)] == [0, 0.5, 1]
    top_bar = latin.GLYPHS["5"][-1]
    assert np.ptp(top_bar[:, 1]) == 0 and top_bar[0][1] == 0
    for g in "ij":
        assert np.ptp(latin.GLYPHS[g][-1], 0).max() < 0.1  # the dot
    # Circles start at the top right and run counter-clockwise (y down: the signed
    # area of the closed path is negative).
    for g in "ocO0":
        p = latin.GLYPHS[g][0]
        x, y = p[:, 0], p[:, 1]
        area = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
        assert area < 0, g
        assert p[0][1] < np.median(y), g  # starts in the upper half


def test_dev_glyphs_are_held_out_of_training():
    dev, train = set(latin.names("dev")), set(latin.names("train"))
    assert len(dev) == 14 and not dev & train and dev | train == set(latin.GLYPHS)
    ks, pool = mix.load("latin")
    assert {chr(int(c)) for c in ks.codes[pool]} == train


def test_glyphs_become_demonstrations_inside_the_canvas():
    ks = latin.load()
    assert len(ks) == len(latin.GLYPHS)
    for i in range(len(ks)):
        g = chr(int(ks.codes[i]))
        d = demo.sample(ks, i)
        assert len(d.strokes) == len(latin.GLYPHS[g])
        pts = np.concatenate(d.strokes)
        assert pts.min() >= 0 and pts.max() <= 99
        # Fitted to the canvas as plan_image fits a small drawing: the longer side ~80 px.
        assert 70 <= np.ptp(pts, 0).max() <= 82, g
        # The demonstration starts where the table's first stroke does (within a pixel
        # of the scaled point).
        first = latin.to_canvas(latin.GLYPHS[g])[0][0]
        assert np.abs(d.strokes[0][0] - first).max() <= 1.0, g


def test_extra_sets_leave_kanjivg_chunks_as_they_were(kanji_set):
    import ml_collections

    from jdraw.data import kanji
    from jdraw.train import ranker as ranker_train

    cfg = ml_collections.ConfigDict(
        {"seed": 0, "chunk": 3, "chars": 6, "demo_chars": 3, "augment": 1.0, "extra": {"latin": 4}}
    )
    jobs = ranker_train.chunk_jobs(cfg)
    assert jobs == [
        ("kanji", "demo", 0),
        ("kanji", "traced", 0),
        ("kanji", "traced", 1),
        ("latin", "traced", 0),
        ("latin", "traced", 1),
    ]
    import pathlib

    w = pathlib.Path("w")
    assert ranker_train.chunk_path(w, "kanji", "traced", 1).name == "traced_0001.npz"
    assert ranker_train.chunk_path(w, "latin", "traced", 1).name == "traced_latin_0001.npz"
    # KanjiVG's draws are those of the seed it always had; another set's are salted apart.
    pool = kanji.split_indices(kanji_set, "train")
    demos, drawn = ranker_train.traced_chunk(cfg, kanji_set, pool, "demo", 0)
    rng = np.random.default_rng([0, 0, 1])
    ref = [demo.sample(kanji_set, int(rng.choice(pool)), rng, 1.0) for _ in range(3)]
    for d, r in zip(demos, ref):
        np.testing.assert_array_equal(d.target, r.target)
    ks, lpool = mix.load("latin")
    a, _ = ranker_train.traced_chunk(cfg, ks, lpool, "demo", 0, salt=mix.salt("latin"))
    b, _ = ranker_train.traced_chunk(cfg, ks, lpool, "demo", 0)
    assert any(not np.array_equal(x.target, y.target) for x, y in zip(a, b))


def test_printed_words_are_training_glyphs_written_one_after_another_left_to_right():
    from jdraw.data import demos as D

    ks = latin.words("train", n=30, seed=3)
    assert len(ks) == 30 and ks.names.tolist() == latin.words("train", n=30, seed=3).names.tolist()
    train = set(latin.names("train"))
    for i in range(len(ks)):
        text = [chr(int(c, 16)) for c in str(ks.names[i]).split("-")[2:]]
        assert 2 <= len(text) <= 4 and set(text) <= train  # never a dev glyph
        strokes = D.sample(ks, i).strokes
        assert len(strokes) == sum(len(latin.GLYPHS[g]) for g in text)
        pts = np.concatenate([np.asarray(s, float) for s in strokes])
        assert pts.min() >= 0 and pts.max() <= 99
        # each glyph's strokes lie left of the next glyph's (the words are laid out with gaps)
        at, right = 0, -np.inf
        for g in text:
            own = np.concatenate(
                [np.asarray(s, float) for s in strokes[at : at + len(latin.GLYPHS[g])]]
            )
            assert own[:, 0].min() > right
            right, at = own[:, 0].max(), at + len(latin.GLYPHS[g])


def test_latin_scores_jdraws_own_lines_exactly_and_with_a_pixel_of_tolerance(monkeypatch):
    from jdraw.evaluation import latin as latin_eval

    seen = []

    def no_planner(inputs, checkpoint, **_):  # no model to load: metrics.score is replaced too
        return "plan"

    monkeypatch.setattr(latin_eval, "plan_batched", no_planner)
    monkeypatch.setattr(latin_eval.api, "load_ranker", lambda ck: None)
    monkeypatch.setattr(latin_eval.ranker, "reorder", lambda plan, order, rk: plan)
    monkeypatch.setattr(latin_eval.metrics, "score", lambda d, p, i, tol: seen.append(tol) or tol)
    out = latin_eval.evaluate_latin(copies=1, styles=("clean", "px3"), progress=False)
    assert seen == [0, 1, 1]
    assert (out["clean"], out["clean_1px"], out["px3"]) == (0, 1, 1)
