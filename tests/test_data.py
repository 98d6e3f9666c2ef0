import json

import numpy as np
import pytest

import jdraw
from jdraw import geometry
from jdraw.data import demos as demo
from jdraw.data import kanji
from jdraw.planner import plan as api
from jdraw.plans import actions_from_strokes, strokes_from_actions


def test_segment_pixels_is_8_connected_and_symmetric_rule():
    for d in [(2, 1), (1, 2), (-2, 1), (-1, -2), (2, 2), (0, 2), (7, -3)]:
        p = geometry.segment_pixels((10, 10), np.add((10, 10), d))
        assert np.max(np.abs(np.diff(p, axis=0))) == 1
        assert tuple(p[-1]) == (10 + d[0], 10 + d[1])
    # The local-move rule: the skipped pixel is a + sign(d) * (|d| // 2).
    np.testing.assert_array_equal(geometry.segment_pixels((5, 5), (6, 7))[1], (5, 6))
    np.testing.assert_array_equal(geometry.segment_pixels((5, 5), (4, 7))[1], (5, 6))


def test_polyline_is_its_segments_joined(rng):
    # The vectorised polyline equals segment_pixels run segment by segment.
    for _ in range(200):
        pts = rng.integers(-4, 30, size=(rng.integers(1, 7), 2))
        pts[rng.random(len(pts)) < 0.2] = pts[0]  # zero-length segments too
        ref = [pts[:1]] + [geometry.segment_pixels(a, b)[1:] for a, b in zip(pts[:-1], pts[1:])]
        ref = np.concatenate(ref)
        ref = ref[np.r_[True, np.any(ref[1:] != ref[:-1], axis=1)]]
        np.testing.assert_array_equal(geometry.polyline_pixels(pts), ref)


def test_actions_and_strokes_round_trip(rng):
    for _ in range(100):
        strokes = [
            np.cumsum(rng.integers(-2, 3, size=(rng.integers(1, 6), 2)), 0) + rng.integers(0, 90, 2)
            for _ in range(rng.integers(0, 5))
        ]
        strokes = [s[np.r_[True, np.any(s[1:] != s[:-1], axis=1)]] for s in strokes]
        actions = actions_from_strokes(strokes)
        back = strokes_from_actions(actions, len(actions))
        assert len(back) == len(strokes)
        for a, b in zip(back, strokes):
            np.testing.assert_array_equal(a, b)


def test_clean_path_is_thin_and_connected():
    pts = np.array([[0, 0], [1, 0], [1, 1], [2, 1], [2, 2], [5, 2]])
    p = demo.clean_path(pts)
    assert np.max(np.abs(np.diff(p, axis=0))) == 1
    # No staircase corners: path[i-1] and path[i+1] never touch.
    assert np.all(np.max(np.abs(p[2:] - p[:-2]), axis=1) == 2)


def test_split_file_is_the_rule(kanji_set):
    spec = json.loads(kanji.SPLIT_FILE.read_text())
    again = kanji.make_split(kanji_set.codes)
    assert spec["test"] == again["test"] and spec["val"] == again["val"]
    tr, va, te = (
        set(kanji_set.codes[kanji.split_indices(kanji_set, s)]) for s in ("train", "val", "test")
    )
    assert not (tr & va) and not (tr & te) and not (va & te)
    assert (
        len(va) == 1000 and len(te) == 1000 and len(kanji.split_indices(kanji_set, "train")) > 7000
    )
    assert min(kanji_set.codes) >= kanji.FIRST_CODE  # no Latin letters in training


def test_augmentation_is_seeded_and_stays_on_canvas(kanji_set):
    a = demo.sample(kanji_set, 5, np.random.default_rng(3))
    b = demo.sample(kanji_set, 5, np.random.default_rng(3))
    c = demo.sample(kanji_set, 5, np.random.default_rng(4))
    assert np.array_equal(a.target, b.target) and not np.array_equal(a.target, c.target)
    for s in a.strokes:
        assert s.min() >= 0 and s.max() < 100
        assert np.max(np.abs(np.diff(s, axis=0)), initial=0) <= 2


def test_demonstration_replays_losslessly_through_planner(kanji_set):
    """500 random characters: the planner's state machine and renderer redraw each exactly."""
    rng = np.random.default_rng(1)
    idx = rng.choice(len(kanji_set), 500, replace=False)
    demos = [demo.sample(kanji_set, i, rng) for i in idx]
    plan = api.replay(demos)
    drawn = jdraw.render(plan)
    for d, img, strokes in zip(demos, drawn, plan.strokes):
        assert jdraw.pixel_accuracy(d.target, img) == 1.0
        per_stroke = np.stack([jdraw.render_strokes([s]) for s in strokes])
        assert jdraw.stroke_accuracy(d.stroke_images(), per_stroke) == 1.0
        assert len(strokes) == len(d.strokes)
    assert not plan.truncated.any()
    # The executed actions are the demonstration's own.
    for d, a, n in zip(demos[:20], plan.actions, plan.lengths):
        np.testing.assert_array_equal(a[:n], d.actions())


@pytest.mark.parametrize("split", ["val", "test"])
def test_held_out_splits_have_no_variants(kanji_set, split):
    idx = kanji.split_indices(kanji_set, split)
    assert not any("-" in str(n) for n in kanji_set.names[idx])


def test_parse_svg_reads_strokes_whatever_the_attribute_order():
    d1, d2 = "M10,20C15,25,20,30,30,40", "M50,10L60,90"
    svg = f"""<?xml version="1.0" encoding="UTF-8"?>
<!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.0//EN" "svg10.dtd" [
<!ATTLIST path xmlns:kvg CDATA #FIXED "http://kanjivg.tagaini.net" kvg:type CDATA #IMPLIED >
]>
<svg xmlns="http://www.w3.org/2000/svg" xmlns:kvg="http://kanjivg.tagaini.net">
<g id="kvg:StrokePaths_04e8c"><g id="kvg:04e8c" kvg:element="x">
  <path d="{d2}" kvg:type="a" id="kvg:04e8c-s2"/>
  <path id="kvg:04e8c-s1" kvg:type="b" d="{d1}"/>
  <path id="kvg:04e8c-x3" d="M0,0L1,1"/>
</g></g>
<g id="kvg:StrokeNumbers_04e8c"><text transform="matrix(1 0 0 1 1 2)">1</text></g>
</svg>"""
    strokes = kanji.parse_svg(svg)
    assert len(strokes) == 2
    np.testing.assert_allclose(strokes[0], kanji._cubics(d1))
    np.testing.assert_allclose(strokes[1], kanji._cubics(d2))
    np.testing.assert_allclose(strokes[0][0, 0], np.array([10, 20]) * 100 / 109, rtol=1e-6)
