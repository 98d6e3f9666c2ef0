"""Demonstrations beyond KanjiVG for the model stages: scribbles, retraces, mixtures."""

import numpy as np
import pytest

from jdraw import geometry
from jdraw.data import batches, cursive, mix, scribbles, variants
from jdraw.data import demos as demo
from jdraw.data.kanji import CANVAS, KanjiSet


def _repeats(stroke: np.ndarray) -> int:
    """Pixels a stroke's 1-pixel path passes more than once."""
    path = [tuple(p) for p in demo.clean_path(np.asarray(stroke), keep_turns=True)]
    return len(path) - len(set(path))


def test_scribbles_are_seeded_on_the_canvas_and_keep_their_turns():
    a, b = scribbles.load(40, seed=3), scribbles.load(40, seed=3)
    assert np.array_equal(a.ctrl, b.ctrl) and len(a) == 40
    assert not np.array_equal(a.ctrl, scribbles.load(40, seed=4).ctrl)
    assert a.keep_turns
    assert a.ctrl.min() >= scribbles.MARGIN / 2 - 1e-6
    assert a.ctrl.max() <= CANVAS - 1 - scribbles.MARGIN / 2 + 1e-6
    counts = np.diff(a.stroke_start)
    assert counts.min() >= 1 and counts.max() <= 3


@pytest.mark.parametrize("kind", scribbles.KINDS)
def test_each_kind_replays_to_its_target(kind):
    rng = np.random.default_rng(0)
    c = scribbles.curve(kind, rng)
    c = (c - c.min(0)) / max(float(np.ptp(c, 0).max()), 1e-9) * 80 + 10
    ks = KanjiSet.from_strokes(["s"], [0], [[cursive.to_cubics(c)]], keep_turns=True)
    d = demo.sample(ks, 0)
    assert len(d.strokes) == 1
    assert np.array_equal(geometry.render_strokes([d.strokes[0].astype(float)]), d.target)
    assert np.abs(np.diff(d.strokes[0], axis=0)).max() <= 2


def _retrace_set() -> KanjiSet:
    """One stroke: right along a line, back over half of it, then down."""
    p = np.array([[20.0, 50.0], [80.0, 50.0], [50.0, 50.0], [50.0, 85.0]])
    return KanjiSet.from_strokes(["r"], [0], [[cursive.to_cubics(p)]], keep_turns=True)


def test_a_set_that_keeps_turns_draws_its_retrace_twice():
    ks = _retrace_set()
    d = demo.sample(ks, 0)
    assert _repeats(d.strokes[0]) >= 25  # the way back over about 30 pixels
    flat = demo.sample(ks, 0, keep_turns=False)
    assert _repeats(flat.strokes[0]) == 0


@pytest.mark.parametrize("style", ["cv2", "px3"])
def test_a_retrace_lays_onto_lines_drawn_another_way(style):
    """The stroke goes back over its own line: laid onto canonical lines it still does,
    where each pixel nearest the first pass alone would have lost the way back."""
    from jdraw.images import canonical

    ks = _retrace_set()
    ctrl = ks.strokes(0)
    ink = canonical.canonicalise(variants.draw(ctrl, style))
    d = variants.on_lines(ctrl, ink, keep_turns=True)
    assert d is not None
    assert _repeats(d.strokes[0]) >= 20
    assert np.linalg.norm(d.strokes[0][-1] - [50, 85]) <= 4


def test_mixture_draws_each_set_at_its_share(kanji_set):
    pool = np.arange(50)
    m = mix.mixture(kanji_set, pool, {"scribble": 0.3, "latin": 0.1}, progress=False)
    assert m.names == ("kanji", "scribble", "latin")
    rng = np.random.default_rng(0)
    picks = [m.pick(rng) for _ in range(2000)]
    share = {n: np.mean([ks is s[0] for ks, _ in picks]) for n, s in zip(m.names, m.sets)}
    assert abs(share["kanji"] - 0.6) < 0.04 and abs(share["scribble"] - 0.3) < 0.04
    assert all(i in pool for ks, i in picks if ks is kanji_set)
    with pytest.raises(ValueError, match="shares"):
        mix.mixture(kanji_set, pool, {"latin": 0.7, "cursive": 0.5}, progress=False)
    with pytest.raises(ValueError, match="unknown training set"):
        mix.mixture(kanji_set, pool, {"hershey": 0.1}, progress=False)


def test_local_batches_from_a_mixture_are_seeded(kanji_set):
    m = mix.mixture(kanji_set, np.arange(50), {"scribble": 0.5}, progress=False)
    kw = dict(windows=256, strokes=16, max_len=48, per_char=4, strength=1.0)
    a = batches.local_batch(m, None, np.random.default_rng(5), **kw)
    b = batches.local_batch(m, None, np.random.default_rng(5), **kw)
    assert a["n_strokes"] > 0
    for k in ("target", "pts", "move", "slot_valid"):
        assert np.array_equal(a[k], b[k])
    only_kanji = batches.local_batch(kanji_set, np.arange(50), np.random.default_rng(5), **kw)
    assert not np.array_equal(a["target"], only_kanji["target"])


def test_a_model_stage_trains_on_a_mixture(tmp_path, monkeypatch):
    """``data.extra`` reaches the batches: the run draws from the mixture it names."""
    from configs import tiny
    from jdraw.train import feed
    from jdraw.train import loop as training

    seen = []
    real = feed.make_batch

    def spy(source, pool, cfg, step):
        seen.append(source)
        return real(source, pool, cfg, step)

    monkeypatch.setattr(feed, "make_batch", spy)
    c = tiny.get_config()
    c.train.update(num_steps=2, checkpoint_every=100, log_every=1)
    c.data.extra = {"scribble": 0.5, "cursive": 0.25}
    out = training.train(c, tmp_path, progress=False)
    assert out["done"] and (tmp_path / "bundle" / "bundle.json").exists()
    assert seen and all(isinstance(s, mix.Mixture) for s in seen)
    shares = dict(zip(seen[0].names, seen[0].p))
    assert shares == pytest.approx({"kanji": 0.25, "scribble": 0.5, "cursive": 0.25})


def test_scripts_variant_names_sets_that_load():
    from configs import default

    base, c = default.get_config().to_dict(), default.get_config("scripts").to_dict()
    for name in ("local", "start"):
        extra = c["stages"][name]["data"]["extra"]
        assert 0 < sum(extra.values()) < 1
        assert {k: v for k, v in c["stages"][name].items() if k not in ("data", "name")} == {
            k: v for k, v in base["stages"][name].items() if k not in ("data", "name")
        }
    assert "scribble" not in c["stages"]["start"]["data"]["extra"]  # its starts mean nothing
    names = set(c["stages"]["local"]["data"]["extra"]) | set(c["stages"]["splitter"]["extra"])
    for name in names:
        ks, pool = mix.load(name, progress=False)
        assert len(pool) > 0


def test_tune_start_variant_trains_the_start_model_on_tunes_local_stage():
    from configs import default

    tune, c = default.get_config("tune").to_dict(), default.get_config("tune_start").to_dict()
    assert c["stages"]["local"] == tune["stages"]["local"]  # reuses a tune run's local stage
    st = c["stages"]["start"]
    assert st["train"]["init_from"] == "stage:local" and not st["train"]["train_local"]
    assert st["train"]["global_weight"] > 0 and "scribble" not in st["data"]["extra"]
    assert c["stage_order"] == ("local", "start", "splitter", "ranker")
    assert c["stages"]["splitter"]["tracer"] == c["stages"]["ranker"]["tracer"] == "stage:start"
    for name in st["data"]["extra"]:
        ks, pool = mix.load(name, progress=False)
        assert len(pool) > 0


def _measured_base() -> dict:
    """The default's config with the splitter stage its variants were measured against
    (configs/default.py:splitter_12_05): the bundled splitter of 2026-12-05."""
    from configs import default

    c = default.get_config()
    c.stages.splitter = default.splitter_12_05()
    return c.to_dict()


def test_retrace_variant_changes_only_the_splitters_reach_and_sets():
    from configs import default

    base, c = _measured_base(), default.get_config("retrace").to_dict()
    for name in ("local", "start"):
        assert c["stages"][name] == base["stages"][name]
    before = default.ranker_before(default.ranker()).to_dict()  # as it was measured
    assert c["stages"]["ranker"] == before and before["hidden"] == 64 and "extra" not in before
    sp = c["stages"]["splitter"]
    assert sp["reach"] == 32 > base["stages"]["splitter"]["reach"]
    before = default.splitter_before(default.splitter_12_05()).to_dict()  # as it was measured
    same = {k: v for k, v in sp.items() if k not in ("reach", "extra")}
    assert same == {k: v for k, v in before.items() if k != "reach"} and not sp["context"]
    for name in sp["extra"]:
        ks, pool = mix.load(name, progress=False)
        assert len(pool) > 0


def test_own_retrace_variant_changes_only_the_splitters_retrace_and_join_shares():
    from configs import default

    base, c = _measured_base(), default.get_config("own_retrace").to_dict()
    for name in ("local", "start", "ranker"):
        assert c["stages"][name] == base["stages"][name]
    sp, before = c["stages"]["splitter"], base["stages"]["splitter"]
    assert sp.pop("retrace") == 40 and "retrace" not in before
    assert sp.pop("join_shares") == {"latin": 0.1} and sp == before


def _splitter_only(base: str, variant: str | None) -> tuple[dict, dict]:
    """The splitter stages of two configs/default.py variants, their other stages equal."""
    from configs import default

    a, b = default.get_config(base).to_dict(), default.get_config(variant).to_dict()
    for name in ("local", "start", "ranker"):
        assert b["stages"][name] == a["stages"][name]
    return b["stages"]["splitter"], a["stages"]["splitter"]


def test_joined_retrace_variant_is_own_retrace_learned_and_asked_in_joined_writing_only():
    sp, own = _splitter_only("own_retrace", "joined_retrace")
    assert sp.pop("retrace_where") == "joined" and sp.pop("bundle_retrace") == 0
    assert sp == own


def test_joined_t_cuts_variants_are_joined_retrace_with_t_cuts_three_seeds_and_patches():
    sp, joined = _splitter_only("joined_retrace", "joined_t_cuts")
    assert sp.pop("t_cuts") is True and sp.pop("members") == 3
    assert sp == joined
    sp, cuts = _splitter_only("joined_t_cuts", "joined_t_cuts_patches")
    assert sp.pop("patches") is True and cuts.pop("patches") is False
    assert sp == cuts
    # ... which is the bundled default's splitter stage, the rest of the default unchanged
    sp, bundled = _splitter_only("joined_t_cuts_patches", None)
    assert sp == bundled


def test_scribble_splitter_variant_adds_scribbles_to_the_splitters_sets_only():
    from configs import default

    base = _measured_base()
    c = default.get_config("scribble_splitter").to_dict()
    for name in ("local", "start", "ranker"):
        assert c["stages"][name] == base["stages"][name]
    sp, before = c["stages"]["splitter"], base["stages"]["splitter"]
    extra = sp.pop("extra")
    assert extra.pop("scribble") == 3000 and extra == before.pop("extra") and sp == before


def test_splitter_members_variant_fits_five_splitters_and_changes_nothing_else():
    from configs import default

    base = _measured_base()
    c = default.get_config("splitter_members").to_dict()
    for name in ("local", "start", "ranker"):
        assert c["stages"][name] == base["stages"][name]
    sp = c["stages"]["splitter"]
    assert sp.pop("members") == 5 and "members" not in base["stages"]["splitter"]
    assert sp == base["stages"]["splitter"]


def test_context_variant_is_retraces_splitter_reading_the_context_and_the_1204_ranker():
    from configs import default

    base, c = _measured_base(), default.get_config("context").to_dict()
    retrace = default.get_config("retrace").to_dict()
    assert c["stages"]["splitter"] == {**retrace["stages"]["splitter"], "context": True}
    # the default's ranker as it was on 2026-12-04: no printed words, no heading shares,
    # one seed
    drop = ("heading_shares", "members")
    before = {k: v for k, v in base["stages"]["ranker"].items() if k not in drop}
    before["extra"] = {"latin": 2000, "cursive": 400}
    assert c["stages"]["ranker"] == {**before, "tracer_split": "stage:splitter"}
    assert base["stages"]["ranker"]["context"] and base["stages"]["splitter"]["context"]
    assert (
        base["stages"]["splitter"]["reach"] == 16 and retrace["stages"]["splitter"]["reach"] == 32
    )
    assert default.get_config("mix").stages.splitter.reach == 8  # as the variants were measured
