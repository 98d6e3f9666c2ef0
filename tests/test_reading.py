"""Reading direction: detected from the image, a hint that overrides it, right-to-left plans.

The two word images in tests/data were set in fonts the detector never saw
(Noto Serif Hebrew, Amiri; see jdraw.data.fonts.DETECTOR_EVAL), so the tests
need no font installed.
"""

import pathlib

import jax
import numpy as np
import pytest
from flax import nnx

from jdraw import plan
from jdraw.images import reading
from jdraw.images.load import load_image
from jdraw.images.prepare import prepare
from jdraw.planner import ranker
from jdraw.planner.plan import load_ranker
from jdraw.tiling import layout
from jdraw.tiling import plan_image as tiling
from jdraw.train import reading as training
from tests.doubles import trace_planner
from tests.synthetic import photo_like

ROOT = pathlib.Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples" / "images").glob("*"))
RTL_WORDS = [
    ROOT / "tests" / "data" / "hebrew_noto_serif.png",
    # The detector bundled until 2026-12-04 missed this one (3.8, threshold 5.5).
    ROOT / "tests" / "data" / "arabic_amiri.png",
]


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_examples_read_left_to_right(path):
    # A kanji, a cursive "hello", a printed sentence and a sketch.
    assert reading.detect(prepare(load_image(path))) == "ltr"


@pytest.mark.parametrize("path", RTL_WORDS, ids=lambda p: p.name)
def test_hebrew_and_arabic_read_right_to_left(path):
    prep = prepare(load_image(path))
    assert reading.detect(prep) == "rtl"


def test_mirrored_hebrew_no_longer_reads_as_hebrew():
    # The detector reads the script's letters, not the mere ink: Hebrew's letters
    # mirrored are not Hebrew. (Mirrored Arabic keeps its joins and dots, and reads
    # as Arabic still: docs/reading_direction.md.)
    img = load_image(RTL_WORDS[0])
    mirrored = reading.rtl_score(prepare(img[:, ::-1]))
    assert mirrored < reading.load().threshold < reading.rtl_score(prepare(img))


def test_line_windows_are_normalised():
    prep = prepare(load_image(RTL_WORDS[0]))
    (line,) = reading.line_images(prep)  # one line of two words
    assert line.shape[0] == reading.WINDOW and line.shape[1] > 3 * reading.WINDOW
    x, ink = reading.drawing_windows(prep)
    assert x.shape[1:] == (reading.WINDOW, reading.WINDOW) and np.all(ink > 0)
    assert x.max() <= 1.0 and x.min() >= 0.0


def test_the_hint_overrides_the_image():
    img = load_image(RTL_WORDS[0])
    auto = tiling.plan_image(img, planner=trace_planner, progress=False)
    ltr = tiling.plan_image(img, planner=trace_planner, progress=False, direction="ltr")
    assert auto.direction == "rtl" and ltr.direction == "ltr"
    cx = lambda r: np.array([(b[0] + b[2]) / 2 for b in r.regions])
    bodies = lambda r: cx(r)[np.array([b[3] - b[1] for b in r.regions]) > 20]
    assert np.all(np.diff(bodies(auto)) < 0) and np.all(np.diff(bodies(ltr)) > 0)
    with pytest.raises(ValueError, match="direction"):
        tiling.plan_image(img, planner=trace_planner, progress=False, direction="up")


@pytest.mark.parametrize("name", ["sentence.jpg", "sketch.jpg"])
def test_left_to_right_images_plan_as_before(name):
    """Read from the image, a left-to-right drawing is planned exactly as with ``"ltr"``."""
    img = load_image(ROOT / "examples" / "images" / name)
    auto = tiling.plan_image(img, planner=trace_planner, progress=False)
    ltr = tiling.plan_image(img, planner=trace_planner, progress=False, direction="ltr")
    rtl = tiling.plan_image(img, planner=trace_planner, progress=False, direction="rtl")
    assert len(auto.strokes) == len(ltr.strokes)
    assert all(np.array_equal(a, b) for a, b in zip(auto.strokes, ltr.strokes))
    assert not all(np.array_equal(a, b) for a, b in zip(rtl.strokes, ltr.strokes))


def test_reading_order_right_to_left_with_marks_after_their_body():
    boxes = [
        (300, 10, 360, 60),  # line 1, right
        (10, 110, 60, 160),  # line 2, left
        (12, 12, 70, 58),  # line 1, left
        (45, 0, 50, 5),  # a dot above line 1's left word
        (200, 105, 260, 150),  # line 2, right
        (20, 62, 26, 68),  # a dot under line 1's left word, left of the other
        (150, 30, 156, 36),  # a stray dot between the words: on its own
    ]
    assert layout._reading_order(boxes) == [2, 5, 3, 6, 0, 1, 4]
    assert layout._reading_order(boxes, rtl=True) == [0, 6, 2, 3, 5, 4, 1]


def _canvas_word():
    """Two letter bodies (right: x 60-90, left: x 10-40, each an L 20 px tall) and a dot
    over the right one's right end; strokes as polylines on the canvas."""
    img = np.zeros((100, 100), bool)
    right_a = np.array([[90.0, 30], [90, 50], [75, 50]])  # the right body's right part
    right_b = np.array([[75.0, 50], [60, 50]])  # and its left part
    left = np.array([[40.0, 30], [40, 50], [10, 50]])
    for p in (right_a, right_b, left):
        for (x0, y0), (x1, y1) in zip(p[:-1], p[1:]):
            img[
                int(min(y0, y1)) : int(max(y0, y1)) + 1, int(min(x0, x1)) : int(max(x0, x1)) + 1
            ] = 1
    img[22:24, 84:86] = 1  # the dot
    dot = np.array([[84.0, 22], [85, 23]])
    return img, right_a, right_b, left, dot


def test_a_mark_is_drawn_right_after_its_letter_not_after_the_next_piece():
    from jdraw.tiling.marks import marks_after_bodies

    img, right_a, right_b, left, dot = _canvas_word()
    right = np.concatenate([right_a, right_b[1:]])
    # the ranker's order: right body, left body, then the dot (a cursive word's marks last)
    assert marks_after_bodies(img, [right, left, dot]) == [0, 2, 1]
    # a body in two strokes: the dot follows the stroke that passes nearest it
    assert marks_after_bodies(img, [right_a, right_b, left, dot]) == [0, 3, 1, 2]
    assert marks_after_bodies(img, [dot, right_a, right_b, left]) == [1, 0, 2, 3]
    # already in place, or nothing but bodies: the order stays
    assert marks_after_bodies(img, [right_a, dot, right_b, left]) == [0, 1, 2, 3]
    assert marks_after_bodies(img & (np.arange(100) < 80)[None], [left, right_b]) == [0, 1]


def test_wide_region_tiles_go_right_to_left():
    t = np.linspace(0, 1, 400)
    line = np.stack([40 + 900 * t, 150 + 100 * np.sin(7 * np.pi * t)], 1)
    prep = prepare(photo_like([line], (300, 980), width=6))
    xs = lambda tiles: [t.transform.offset[0] for t in tiles]
    # A lone wave is drawn small (jdraw.images.gaps); 16 draws it at min_gap / width.
    ltr, rtl = layout.layout(prep, 16.0)[1], layout.layout(prep, 16.0, rtl=True)[1]
    assert len(ltr) >= 8 and sorted(xs(ltr)) == sorted(xs(rtl))
    # Offsets map input to tile pixels, so a tile further right has a more negative offset.
    assert xs(ltr)[0] == max(xs(ltr)) and xs(rtl)[0] == min(xs(rtl))


def test_ranker_orders_right_to_left_as_the_mirror_image():
    rk = load_ranker()
    assert rk is not None
    rng = np.random.default_rng(0)
    strokes = []
    for x in (15, 40, 65, 85):  # four vertical bars of a word, each with a wiggle
        y = np.arange(20, 80, dtype=np.float64)
        strokes.append(np.stack([x + np.round(2 * np.sin(y / 7 + rng.random())), y], 1))
    order, flip = ranker.order_many(rk, [strokes])[0]
    r_order, r_flip = ranker.order_many(rk, [ranker.mirrored(strokes)], mirror=True)[0]
    assert (order, flip) == (r_order, r_flip)  # mirroring twice is the identity
    rtl_order, _ = ranker.order_many(rk, [strokes], mirror=True)[0]
    assert order[0] == 0 and rtl_order[0] == 3  # leftmost first; rightmost first


def test_plan_direction_reaches_the_ranker():
    img = np.zeros((100, 100), bool)
    for x in (20, 45, 70):
        img[20:80, x] = True
    ltr, rtl = plan(img, direction="ltr"), plan(img, direction="rtl")
    first = lambda p: p.strokes[0][0][0][0]
    assert first(ltr) == 20 and first(rtl) == 70
    with pytest.raises(ValueError, match="direction"):
        plan(img, direction="down")


def test_fit_learns_and_round_trips(tmp_path):
    from jdraw.train import reading as training

    rng = np.random.default_rng(0)
    x = np.zeros((200, reading.WINDOW, reading.WINDOW), np.uint8)
    y = np.arange(200) % 2 == 0
    for k in range(200):  # class 1: horizontal lines; class 0: vertical lines
        i = rng.integers(4, 28)
        if y[k]:
            x[k, i, 4:28] = 255
        else:
            x[k, 4:28, i] = 255
    net, logs = training.fit(x, y, steps=150, batch=32, lr=1e-2, channels=(4, 8, 8))
    logits = reading.window_logits(net, x.astype(np.float32) / 255)
    assert np.mean((logits > 0) == y) >= 0.95, logs
    reading.save(net, tmp_path, {"test": True})
    again = reading.load(tmp_path)
    np.testing.assert_allclose(reading.window_logits(again, x[:8] / 255.0), logits[:8], atol=1e-5)
    assert isinstance(again, nnx.Module)


def test_font_splits_never_overlap():
    from jdraw.data import cjk_faces
    from jdraw.data import fonts as F

    for script in F.DETECTOR_TRAIN:
        train = set(F.DETECTOR_TRAIN[script])
        val, held = set(F.DETECTOR_VAL.get(script, ())), set(F.DETECTOR_EVAL.get(script, ()))
        assert not (train & val) and not (train & held) and not (val & held), script
        check = set(cjk_faces.DETECTOR_CHECK.get(script, ()))
        assert not (check & (train | val | held)), script  # the check's faces are in no split
        more = set(cjk_faces.DETECTOR_MORE_TRAIN.get(script, ()))
        assert not (more & (train | val | held | check)), script
    assert set(F.DETECTOR_VAL) <= set(F.DETECTOR_TRAIN)
    assert set(cjk_faces.DETECTOR_CHECK) <= set(F.DETECTOR_TRAIN) - set(F.RTL_SCRIPTS)


def test_more_cjk_faces_are_fitted_on_only_where_the_config_asks():
    from configs import reading_direction as rd
    from jdraw.data import cjk_faces

    plain = training._font_splits(rd.get_config())
    more = training._font_splits(rd.get_config("elastic_cjk"))
    assert more[1:] == plain[1:]  # the same validation and held-out fonts
    for script, faces in cjk_faces.DETECTOR_MORE_TRAIN.items():
        assert not set(faces) & set(plain[0][script])
        assert more[0][script] == plain[0][script] + faces
    assert rd.get_config("elastic").elastic > 0 and not rd.get_config("elastic").more_cjk


def test_threshold_lets_through_at_most_the_allowed_false_rtl():
    from jdraw.train import reading as training

    ltr = list(np.linspace(-3.0, 2.0, 100))  # 100 left-to-right drawings' scores
    val = {"latin": ltr[:60], "han": ltr[60:] + [-np.inf], "hebrew": [5.0, 0.5]}
    t = training.choose_threshold(val, 0.02)
    assert sum(v > t for v in ltr) <= 2 and sum(v >= t for v in ltr) == 3
    assert training.choose_threshold({"latin": [-4.0, -3.0]}, 0.0) == 0.0  # never below 0
    assert training.choose_threshold({"hebrew": [1.0]}, 0.1) == reading.THRESHOLD


def test_stretched_lines_keep_their_height_and_ink():
    from jdraw.train import reading as training

    (line,) = reading.line_images(prepare(load_image(RTL_WORDS[0])))
    for f in (0.7, 1.4):
        out = training.stretch(line, f)
        assert out.shape == (line.shape[0], round(line.shape[1] * f))
        assert abs(out.sum() / line.sum() - f) < 0.05
    x, ink = reading.windows(training.stretch(line[:, :20], 0.5), 48)  # short: padded
    assert x.shape == (1, reading.WINDOW, 48) and ink[0] > 0


def _word_with_dots() -> np.ndarray:
    """A flat word body 40 px high with a round dot far over it and a dash under it."""
    import cv2

    img = np.full((260, 300), 255, np.uint8)
    cv2.polylines(img, [np.array([[20, 120], [280, 120], [280, 160], [20, 160]])], False, 0, 5)
    cv2.circle(img, (150, 40), 6, 0, -1)  # its centreline is one point
    cv2.line(img, (100, 222), (100, 230), 0, 5)
    return img


def test_span_all_keeps_the_marks_that_span_tall_clips():
    # Arabic dots lie far over and under a flat word body. Scaled to the bodies alone
    # ("tall", the detectors before 2026-12-06) they fall outside the window; scaled
    # to all the line's ink ("all") both marks are drawn, the round dot too.
    prep = prepare(_word_with_dots())
    (tall,) = reading.line_images(prep, "tall")
    (full,) = reading.line_images(prep, "all")
    assert tall.shape[0] == full.shape[0] == reading.WINDOW

    def runs_of_ink_rows(line):  # blank rows split the runs
        rows = np.flatnonzero(line.max(1) > 0.2)
        return 1 + int(np.count_nonzero(np.diff(rows) > 1)) if len(rows) else 0

    assert runs_of_ink_rows(tall) == 1  # the body alone
    assert runs_of_ink_rows(full) == 3  # the dot, the body, the dash
    with pytest.raises(ValueError, match="span"):
        reading.line_images(prep, "marks")


def test_span_is_stored_with_the_net_and_old_nets_read_tall(tmp_path):
    import json

    net = reading.DirectionNet((4, 4), width=64, span="all", rngs=nnx.Rngs(0))
    reading.save(net, tmp_path / "new")
    assert reading.load(tmp_path / "new").span == "all"
    reading.save(reading.DirectionNet((4, 4), width=64, rngs=nnx.Rngs(0)), tmp_path / "old")
    meta = tmp_path / "old" / "direction.json"
    d = json.loads(meta.read_text())
    del d["span"]  # as the detectors bundled before 2026-12-06 were written
    meta.write_text(json.dumps(d))
    assert reading.load(tmp_path / "old").span == "tall"
    with pytest.raises(ValueError, match="span"):
        reading.DirectionNet((4,), span="marks", rngs=nnx.Rngs(0))


def test_threshold_and_width_are_stored_with_the_net(tmp_path):
    net = reading.DirectionNet((4, 4, 4, 4), threshold=-50.0, width=64, rngs=nnx.Rngs(0))
    reading.save(net, tmp_path)
    again = reading.load(tmp_path)
    assert again.threshold == -50.0 and again.width == 64 and len(again.convs) == 4
    prep = prepare(load_image(EXAMPLES[0]))
    assert reading.detect(prep, again) == "rtl"  # any score beats -50
    again.threshold = 50.0
    assert reading.detect(prep, again) == "ltr"


def test_an_interrupted_fit_goes_on_from_its_checkpoint_as_if_it_had_not_stopped(tmp_path):
    rng = np.random.default_rng(0)
    x = (rng.random((40, reading.WINDOW, reading.WINDOW)) < 0.1).astype(np.uint8) * 255
    y = np.arange(40) % 2 == 0
    kw = dict(steps=4, batch=8, lr=1e-2, channels=(4, 4), seed=0, augment_strength=1.0)
    whole, _ = training.fit(x, y, **kw)
    training.fit(x, y, **kw, workdir=tmp_path, checkpoint_every=3, stop_after=2)  # stopped
    assert (tmp_path / "fit" / "2").is_dir()
    again, log = training.fit(x, y, **kw, workdir=tmp_path, checkpoint_every=3)
    assert (tmp_path / "fit" / "4").is_dir()
    for a, b in zip(jax.tree.leaves(nnx.state(whole)), jax.tree.leaves(nnx.state(again))):
        np.testing.assert_allclose(np.asarray(a), np.asarray(b), rtol=1e-6, atol=1e-7)
    assert [e["step"] for e in log] == [0, 3]  # the log of the first two steps came back too
    done, log = training.fit(x, y, **kw, workdir=tmp_path)  # finished: fits nothing
    for a, b in zip(jax.tree.leaves(nnx.state(whole)), jax.tree.leaves(nnx.state(done))):
        np.testing.assert_allclose(np.asarray(a), np.asarray(b), rtol=1e-6, atol=1e-7)


def test_augment_keeps_shapes_and_range_and_distorts(tmp_path):
    rng = np.random.default_rng(1)
    xb = np.zeros((16, reading.WINDOW, 64), np.float32)
    xb[:, 14:16, 8:56] = 1.0  # a horizontal bar
    out = training.augment(xb, rng, 1.0)
    assert out.shape == xb.shape and out.min() >= 0.0 and out.max() <= 1.0
    assert not np.allclose(out, xb)
    rows = [np.flatnonzero(o.sum(1) > 0) for o in out]
    assert len({(r.min(), r.max()) for r in rows}) > 3  # windows distorted differently


def test_bending_moves_a_line_smoothly_and_elastic_augment_bends():
    from jdraw.train import reading_data

    v = np.zeros((reading.WINDOW, 64), np.float32)
    v[15, 8:56] = 1.0  # a straight horizontal line, one pixel thick
    bent = [reading_data.bend(v, np.random.default_rng(s), 2.0) for s in range(8)]
    for b in bent:
        cols = np.flatnonzero(b.max(0) > 0.3)
        rows = b[:, cols].argmax(0)  # where the line passes in each column
        # Still one line: ink kept within 30% (a 2-px spread moves it, does not
        # break or thicken it) and its height changes by at most 1 px per column.
        assert abs(b.sum() - v.sum()) < 0.3 * v.sum()
        assert np.abs(np.diff(rows)).max() <= 1
    assert sum(not np.array_equal(np.argmax(b, 0), np.argmax(v, 0)) for b in bent) >= 6
    np.testing.assert_array_equal(reading_data.bend(v, np.random.default_rng(0), 0.0), v)

    xb = np.repeat(v[None], 16, 0)
    plain = training.augment(xb, np.random.default_rng(3), 1.0)
    assert not np.array_equal(training.augment(xb, np.random.default_rng(3), 1.0, 2.0), plain)


def test_examples_are_made_once_per_data_setting(tmp_path, monkeypatch):
    from configs import reading_direction as rd

    cfg = rd.tiny()
    per = {s: 1 for s in training.F.DETECTOR_TRAIN}
    calls = []

    def fake(fonts, per_script, sketches, cfg, seed):
        calls.append(seed)
        return np.zeros((3, 32, 64), np.uint8), np.array([True, False, True]), np.zeros(3, int)

    monkeypatch.setattr(training, "make_examples", fake)
    x, y = training._cached_examples(cfg, tmp_path, per)
    x2, y2 = training._cached_examples(cfg, tmp_path, per)
    assert calls == [cfg.seed] and x2.shape == (3, 32, 64) and y2.tolist() == y.tolist()
    cfg.seed = 5
    training._cached_examples(cfg, tmp_path, per)
    assert calls == [0, 5]  # another data setting: made again


POOL_TOL = 1e-9  # float64 sums of a few terms


def test_probability_pooling_bounds_what_one_sure_window_can_say(tmp_path):
    z, ink = np.array([40.0, -2.0, -2.0, -2.0, -2.0]), np.ones(5)
    assert reading.pool_scores(z, ink, "logit") == pytest.approx(6.4, abs=POOL_TOL)  # outvoted
    p = (1.0 + 4.0 / (1.0 + np.exp(2.0))) / 5.0
    assert reading.pool_scores(z, ink, "prob") == pytest.approx(np.log(p / (1 - p)), abs=POOL_TOL)
    assert reading.pool_scores(z, ink, "prob") < 0  # the four windows win
    for pool in ("logit", "prob"):  # windows that agree: their logit, either way; ink weighs
        assert reading.pool_scores(np.full(3, 1.5), np.arange(1.0, 4.0), pool) == pytest.approx(
            1.5, abs=POOL_TOL
        )
    for pool in reading.POOLS:
        assert reading.pool_scores(np.zeros(0), np.zeros(0), pool) == -np.inf
    # Evidence: the mean times sqrt(n); n counts windows by their ink.
    for n in (1, 4, 16):
        got = reading.pool_scores(np.full(n, 0.5), np.full(n, 7.0), "evidence")
        assert got == pytest.approx(0.5 * np.sqrt(n), abs=POOL_TOL)
    got = reading.pool_scores(np.array([1.0, 1.0]), np.array([1.0, 0.0]), "evidence")
    assert got == pytest.approx(1.0, abs=POOL_TOL)  # a window with no ink adds nothing
    assert reading.pool_scores(np.array([3.0, -1.0]), np.array([1.0, 3.0]), "logit") == 0.0
    with pytest.raises(ValueError, match="pool"):
        reading.pool_scores(z, ink, "max")
    net = reading.DirectionNet((4, 4), pool="prob", rngs=nnx.Rngs(0))
    reading.save(net, tmp_path)
    assert reading.load(tmp_path).pool == "prob"


def test_cursive_drawings_join_the_detector_splits_by_word_split():
    from configs import reading_direction as rd

    cfg = rd.tiny()
    train, val, held = training._font_splits(cfg)
    assert (train["cursive"], val["cursive"], held["cursive"]) == (["train"], ["val"], ["test"])
    assert val["sketch"] == held["sketch"] == [None] and "sketch" not in train
    cfg.cursive_words = 0
    assert all("cursive" not in d for d in training._font_splits(cfg))
    cfg.slant, cfg.two_words = 0.0, 0.0
    img = training.sample("cursive", "val", np.random.default_rng(0), cfg)
    ink = img < 128
    assert img.dtype == np.uint8 and ink.any() and not ink[0].any() and not ink[:, 0].any()
    rows = np.flatnonzero(ink.any(1))
    assert cfg.min_height - 2 <= rows[-1] - rows[0] + 1 <= cfg.max_height + 8  # ink height, pen


def test_hand_printed_latin_is_fitted_on_only_and_drawn_from_the_training_glyphs(monkeypatch):
    from configs import reading_direction as rd
    from jdraw.data import latin

    cfg = rd.tiny()
    train, val, held = training._font_splits(cfg)
    assert train["print"] == ["train"] and "print" not in val and "print" not in held
    cfg.print_words = 0
    assert all("print" not in d for d in training._font_splits(cfg))
    cfg.slant, cfg.two_words = 0.0, 0.0
    drawn = []
    monkeypatch.setattr(latin, "GLYPHS", _Spy(latin.GLYPHS, drawn))
    img = training.sample("print", None, np.random.default_rng(0), cfg)
    assert drawn and set(drawn) <= set(latin.names("train"))
    assert 3 <= len(drawn) <= 8  # one string of 3-8 glyphs
    ink = img < 128
    assert img.dtype == np.uint8 and ink.any() and not ink[0].any() and not ink[:, 0].any()
    assert img.shape[1] > img.shape[0]  # letters side by side along a line
    rows = np.flatnonzero(ink.any(1))
    assert cfg.min_height - 2 <= rows[-1] - rows[0] + 1 <= cfg.max_height + 8


class _Spy(dict):
    """A glyph table that notes each glyph read from it."""

    def __init__(self, table, seen):
        super().__init__(table)
        self.seen = seen

    def __getitem__(self, g):
        self.seen.append(g)
        return super().__getitem__(g)


ENSEMBLE_TOL = 1e-6  # float32 logits


def test_an_ensemble_reads_the_mean_of_its_members_and_is_saved_whole(tmp_path):
    a = reading.DirectionNet((4, 4), width=64, rngs=nnx.Rngs(0))
    b = reading.DirectionNet((4, 8), width=64, rngs=nnx.Rngs(1))
    e = reading.DirectionEnsemble([a, b], threshold=1.25)
    x = np.random.default_rng(0).random((5, reading.WINDOW, 64)).astype(np.float32)
    za, zb, ze = (reading.window_logits(n, x) for n in (a, b, e))
    assert not np.allclose(za, zb)
    np.testing.assert_allclose(ze, (za + zb) / 2, atol=ENSEMBLE_TOL)
    reading.save(e, tmp_path)
    got = reading.load(tmp_path)
    assert isinstance(got, reading.DirectionEnsemble) and len(got.members) == 2
    assert (got.threshold, got.pool, got.width) == (1.25, "logit", 64)
    np.testing.assert_allclose(reading.window_logits(got, x), ze, atol=ENSEMBLE_TOL)
    with pytest.raises(ValueError, match="windows"):
        reading.DirectionEnsemble([a, reading.DirectionNet((4,), width=32, rngs=nnx.Rngs(0))])


def test_a_config_with_members_fits_each_seed_once_and_writes_them_as_one(tmp_path, monkeypatch):
    from configs import reading_direction as rd

    cfg = rd.tiny()
    cfg.members, cfg.out = (0, 1), str(tmp_path / "out")
    rng = np.random.default_rng(0)
    x = (rng.random((40, reading.WINDOW, 64)) * 255).astype(np.uint8)
    y = np.arange(40) % 2 == 0
    monkeypatch.setattr(training, "_cached_examples", lambda *a, **k: (x, y))
    fake = {"hebrew": [3.0, 1.0], "latin": [-2.0, 0.5]}  # no fonts: scored drawings made up
    monkeypatch.setattr(training, "scores", lambda net, *a: {p: fake for p in a[-1]})
    monkeypatch.setattr(training, "accuracy", lambda *a, **k: {})
    fits = []
    real_fit = training.fit

    def fit(*a, **k):
        fits.append(k["seed"])
        return real_fit(*a, **k)

    monkeypatch.setattr(training, "fit", fit)
    r = training.train(cfg, tmp_path)
    assert fits == [0, 1] and r["members"] == 2
    assert r["threshold"] == 0.5  # the highest left-to-right validation score
    e = reading.load(tmp_path / "out")
    one = [reading.load(tmp_path / f"seed{s}" / "out") for s in (0, 1)]
    xs = x[:8].astype(np.float32) / 255
    want = np.mean([reading.window_logits(n, xs) for n in one], 0)
    np.testing.assert_allclose(reading.window_logits(e, xs), want, atol=ENSEMBLE_TOL)
    training.train(cfg, tmp_path)
    assert fits == [0, 1]  # the members made are read back, not fitted again
