"""Cursive-word demonstrations (jdraw.data.cursive) from the committed EMS Allure glyphs."""

import numpy as np
import pytest

from jdraw import geometry
from jdraw.data import cursive, demos, kanji
from jdraw.data.make_single_line import parse_path

TOL = 1e-4  # canvas pixels: control points vs the polyline they encode


def test_parse_path_reads_polylines_and_refuses_curves():
    # EMS Allure's i: the body, then the dot.
    d = "M -31.5 183 L 6.3 233 L 217 183 M 123 476 L 94.5 438"
    assert parse_path(d) == [
        [[-31.5, 183.0], [6.3, 233.0], [217.0, 183.0]],
        [[123.0, 476.0], [94.5, 438.0]],
    ]
    with pytest.raises(ValueError, match="polylines"):
        parse_path("M 0 0 C 1 1 2 2 3 3")


def test_committed_glyphs():
    f = cursive.font()
    assert f["font"] == "EMS Allure" and f["units_per_em"] == 1000 and f["ascent"] == 800
    g = f["glyphs"]
    assert sorted(g) == sorted("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ")
    for ch, v in g.items():
        assert v["adv"] > 0 and v["paths"], ch
        assert all(len(p) >= 2 for p in v["paths"]), ch
    # Values in EMSAllure.svg: i starts at the entry point and has a separate dot.
    assert g["i"]["adv"] == 249 and len(g["i"]["paths"]) == 2
    assert g["i"]["paths"][0][0] == [-31.5, 183.0]
    assert len(g["N"]["paths"]) == 2  # the font's duplicated serif dropped


def test_joined_letters_make_one_stroke_and_dots_come_last():
    glyphs = cursive.font()["glyphs"]
    h, i = glyphs["h"], glyphs["i"]
    strokes = cursive.word_strokes_units("hi")
    assert len(strokes) == 2  # h and i in one motion, then the dot
    body, dot = strokes
    assert len(body) == len(h["paths"][0]) + len(i["paths"][0]) - 1
    np.testing.assert_allclose(body[0], cursive.ENTRY)
    np.testing.assert_allclose(body[-1], np.add(i["paths"][0][-1], (h["adv"], 0)))
    np.testing.assert_allclose(dot, np.add(i["paths"][1], (h["adv"], 0)))
    # "hit": the i's dot and the t's cross both after the body, left to right.
    s = cursive.word_strokes_units("hit")
    t = glyphs["t"]
    assert len(s) == 3
    np.testing.assert_allclose(s[1], np.add(i["paths"][1], (h["adv"], 0)))
    np.testing.assert_allclose(s[2], np.add(t["paths"][1], (h["adv"] + i["adv"], 0)))
    # b ends at the foot of its bowl, away from m's entry and lines: two strokes.
    assert len(cursive.word_strokes_units("bm")) == 2


def test_a_connector_landing_on_the_next_letter_runs_on_through_it():
    glyphs = cursive.font()["glyphs"]
    h = np.asarray(glyphs["h"]["paths"][0])
    a = np.asarray(glyphs["a"]["paths"][0])[::-1] + (glyphs["h"]["adv"], 0)  # as written
    (s,) = cursive.word_strokes_units("ha")
    np.testing.assert_allclose(s[: len(h)], h)
    np.testing.assert_allclose(s[len(s) - len(a) :], a)  # then all of a, from its start
    # In between, the pen goes back along a, from where h's tail lands to a's start.
    back = s[len(h) - 1 : len(s) - len(a) + 1]
    assert np.linalg.norm(back[1] - back[0]) <= cursive.JOIN_TOL
    for q in back[1:]:
        assert min(np.linalg.norm(q - a, axis=1).min(), _to_line(q, a)) < 1e-6


def test_direction_is_the_writers_not_the_fonts():
    # The font draws a from its exit tail back to the top of its oval.
    glyph = np.asarray(cursive.font()["glyphs"]["a"]["paths"][0])
    (a,) = cursive.word_strokes_units("a")
    np.testing.assert_allclose(a, glyph[::-1])
    # y down: the baseline is y = ascent.
    (a_down,) = cursive.word_strokes("a")
    np.testing.assert_allclose(a_down[:, 1], 800 - a[:, 1])


def test_split_is_fixed_disjoint_and_by_word():
    parts = {s: cursive.split_words(s) for s in ("train", "val", "test")}
    assert sum(map(len, parts.values())) == len(set(cursive.WORDS))
    for s, words in parts.items():
        assert all(cursive.split_of(w) == s == cursive.split_of(w.lower()) for w in words)
    assert len(parts["val"]) >= 40 and len(parts["test"]) >= 40
    with pytest.raises(ValueError, match="split"):
        cursive.split_words("dev")
    with pytest.raises(ValueError, match="glyph"):
        cursive.word_strokes("naïve")


def test_fragments_lie_in_the_canvas_and_encode_the_polylines():
    ks = cursive.fragments("val")
    assert len(ks) > 100 and len(ks.stroke_start) == len(ks) + 1
    m = cursive.MARGIN
    assert ks.ctrl.min() >= m - TOL and ks.ctrl.max() <= kanji.CANVAS - 1 - m + TOL
    for i in (0, len(ks) // 2, len(ks) - 1):
        name = str(ks.names[i])
        word, rng = name.split("[")
        s, e = (int(v) for v in rng[:-1].split(":"))
        lines = cursive.fragment_strokes(word, s, e)
        scale, offset = cursive.fit(lines)
        assert scale >= cursive.MIN_SCALE
        got = ks.strokes(i)
        assert len(got) == len(lines)
        for c, p in zip(got, lines):
            q = p * scale + offset
            # Control points are the polyline's vertices and thirds of its segments.
            np.testing.assert_allclose(c[:, 0], q[:-1], atol=TOL)
            np.testing.assert_allclose(c[:, 3], q[1:], atol=TOL)
            np.testing.assert_allclose(c[:, 1], q[:-1] + (q[1:] - q[:-1]) / 3, atol=TOL)
        # The demonstration's pixels are the polylines' pixels, to a pixel. The demo's
        # path cleaning (jdraw.data.demos.clean_path) shortens a cusp where a stroke
        # turns back on itself by a pixel or two, so a little of the line may be missing.
        d = demos.sample(ks, i, keep_turns=True)
        assert len(d.strokes) == len(lines)
        covered = total = 0
        for st, p in zip(d.strokes, lines):
            ref = geometry.render_strokes([np.floor(p * scale + offset + 0.5)])
            drawn = geometry.render_strokes([st])
            assert not np.any(drawn & ~_dilate(ref))
            covered += np.count_nonzero(ref & _dilate(drawn))
            total += np.count_nonzero(ref)
        assert covered >= 0.97 * total


def _to_line(q, p):
    a, d = p[:-1], np.diff(p, axis=0)
    t = np.clip(np.sum((q - a) * d, 1) / np.sum(d * d, 1), 0, 1)
    return np.linalg.norm(a + t[:, None] * d - q, axis=1).min()


def _dilate(img):
    import cv2

    return cv2.dilate(img.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)


def test_clean_path_keeps_a_line_drawn_back_over_itself():
    there_and_back = np.array([[0, 0], [4, 0], [1, 0], [1, 3]])
    p = demos.clean_path(there_and_back, keep_turns=True)
    np.testing.assert_array_equal(p[:, 0], [0, 1, 2, 3, 4, 3, 2, 1, 1, 1])  # (1, 0) a corner
    assert np.max(np.abs(np.diff(p, axis=0))) == 1
    # By default the way back erases the way there; staircase corners go either way.
    np.testing.assert_array_equal(demos.clean_path(there_and_back)[:, 0], [0, 1, 1, 1])
    stairs = demos.clean_path(np.array([[0, 0], [1, 0], [1, 1], [2, 1], [2, 2]]), True)
    assert np.all(np.max(np.abs(stairs[2:] - stairs[:-2]), axis=1) == 2)


def test_a_prefix_is_the_writing_stopped_part_way():
    strokes = cursive.word_strokes("dot")  # body, then the t's cross
    total = sum(float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum()) for p in strokes)
    body = float(np.linalg.norm(np.diff(strokes[0], axis=0), axis=1).sum())
    cut = cursive._prefix(strokes, 0.5 * body)
    assert len(cut) == 1  # stopped inside the body: the cross is not drawn yet
    np.testing.assert_allclose(cut[0][:-1], strokes[0][: len(cut[0]) - 1])
    assert np.linalg.norm(np.diff(cut[0], axis=0), axis=1).sum() == pytest.approx(0.5 * body)
    assert len(cursive._prefix(strokes, total + 1)) == len(strokes)


def test_prefixes_are_fragments_cut_to_a_share_of_their_length():
    ks = cursive.prefixes("val", n=40, seed=3)
    assert len(ks) == 40 and ks.keep_turns
    for i in range(len(ks)):
        name = str(ks.names[i])
        word, rest = name.split("[")
        s, e = (int(v) for v in rest.split("]")[0].split(":"))
        share = float(name.split("@")[1])
        assert 0.4 <= share <= 1.0 and cursive.split_of(word) == "val"
        full = cursive.fragment_strokes(word, s, e)
        length = sum(float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum()) for p in full)
        drawn = sum(
            float(np.linalg.norm(np.diff(c[:, [0, 3]], axis=1), axis=-1).sum())
            for c in ks.strokes(i)
        )
        scale = cursive.fit(cursive._prefix(full, share * length))[0]
        assert drawn == pytest.approx(share * length * scale, rel=2e-3, abs=0.05)
        pts = np.concatenate(ks.strokes(i)).reshape(-1, 2)
        assert pts.min() >= cursive.MARGIN - 1e-3 and pts.max() <= 99 - cursive.MARGIN + 1e-3


def test_prefixes_are_a_training_set_by_name():
    from jdraw.data import mix

    ks, pool = mix.load("cursive_prefix", progress=False)
    assert len(pool) == len(ks) == 2000 and ks.keep_turns
    assert {cursive.split_of(str(n).split("[")[0]) for n in ks.names} == {"train"}
