"""Canonical lines: other rasterisers, thick pens and 1-pixel breaks become jdraw's lines."""

import cv2
import numpy as np
import pytest

from jdraw import geometry
from jdraw.data import demos as demo
from jdraw.data import kanji
from jdraw.evaluation import evaluate, metrics
from jdraw.images import canonical


def _line(points, shape=(40, 40)):
    return geometry.render_strokes([np.asarray(points)], shape)


def test_canonical_lines_are_left_as_they_are():
    # Demonstration paths (jdraw's rasteriser, staircase joints cleaned) are canonical.
    path = demo.clean_path(geometry.polyline_pixels(np.array([[3, 5], [30, 12], [20, 35]])))
    img = np.zeros((40, 40), bool)
    img[path[:, 1], path[:, 0]] = True
    assert np.array_equal(canonical.canonicalise(img), img)


def test_staircase_corners_are_dropped_and_line_stays_connected():
    # A 4-connected staircase: every other pixel is a corner the planner never saw.
    img = np.zeros((20, 20), bool)
    y = 2
    for x in range(2, 16):
        img[y, x] = True
        if x % 2:
            y += 1
            img[y, x] = True
    out = canonical.canonicalise(img)
    n, _ = cv2.connectedComponents(out.astype(np.uint8), connectivity=8)
    assert n == 2  # background and one line
    assert out.sum() < img.sum() and not (out & ~img).any()
    assert not canonical.drop_staircase_corners(out).sum() < out.sum()  # nothing left to drop


@pytest.mark.parametrize("thickness", [2, 3, 4])
def test_thick_pen_becomes_a_centreline(thickness):
    img = np.zeros((60, 60), np.uint8)
    cv2.polylines(img, [np.array([[8, 10], [50, 20], [30, 50]], np.int32)], False, 255, thickness)
    ink = img > 0
    out = canonical.canonicalise(ink)
    assert not canonical.is_thick(out)
    assert out.sum() < 0.7 * ink.sum()
    # Every canonical pixel lies on the input's ink.
    assert not (out & ~ink).any()


def test_one_pixel_break_is_filled_only_between_ends_facing_each_other():
    img = _line([[5, 10], [34, 10]])
    broken = img.copy()
    broken[10, 20] = False
    assert np.array_equal(canonical.canonicalise(broken), img)
    # Two parallel line ends 2 px apart side by side are not joined.
    side = _line([[5, 10], [15, 10]], (30, 30)) | _line([[5, 12], [15, 12]], (30, 30))
    assert np.array_equal(canonical.bridge_gaps(side), side)


def test_kanjivg_targets_stay_nearly_untouched(kanji_set):
    idx = kanji.split_indices(kanji_set, "test")[:40]
    changed = 0
    for i in idx:
        t = demo.sample(kanji_set, int(i)).target
        c = canonical.canonicalise(t)
        assert not (c & ~t).any()  # never adds ink to a canonical drawing
        changed += int((t & ~c).sum())
    assert changed <= 4  # at most a stray staircase pixel where strokes meet


def test_opencv_drawing_becomes_close_to_jdraw_drawing(kanji_set):
    from jdraw.evaluation import metrics

    i = int(kanji.split_indices(kanji_set, "test")[3])
    ref = demo.sample(kanji_set, i).target
    for style in ("cv2", "thick3", "aa"):
        c = canonical.canonicalise(evaluate.rasterise(kanji_set, i, style))
        assert metrics.tolerant_pixel_accuracy(ref, c, 1) > 0.95, style


def _ends_and_junctions(img):
    """Line ends, junction clusters (8-connected pixels with 3+ neighbours) and components."""
    deg = canonical._degree(img)
    ends = int(np.count_nonzero(img & (deg == 1)))
    junctions = cv2.connectedComponents((img & (deg >= 3)).astype(np.uint8), connectivity=8)[0]
    parts = cv2.connectedComponents(img.astype(np.uint8), connectivity=8)[0]
    return ends, junctions - 1, parts - 1


@pytest.mark.parametrize("thickness", [2, 3])
@pytest.mark.parametrize(
    "shape, ends",
    [
        ("cross", 4),  # two strokes crossing: one junction, no spur
        ("tee", 3),  # a stroke ending on another
    ],
)
def test_thick_cross_and_tee_have_one_junction_and_no_spurs(thickness, shape, ends):
    img = np.zeros((60, 60), np.uint8)
    lines = {
        "cross": [((10, 30), (50, 30)), ((30, 8), (30, 52))],
        "tee": [((10, 12), (50, 12)), ((30, 12), (30, 52))],
    }[shape]
    for a, b in lines:
        cv2.line(img, a, b, 255, thickness)
    ink = img > 0
    out = canonical.canonicalise(ink)
    assert _ends_and_junctions(out) == (ends, 1, 1)
    assert metrics.tolerant_pixel_accuracy(_line_union(lines), out, 1) > 0.97


def _line_union(lines, shape=(60, 60)):
    return geometry.render_strokes([np.asarray(ab) for ab in lines], shape)


def test_polyline_joints_are_thinned_to_one_path(kanji_set):
    # OpenCV's polyline through points 1.5 px apart leaves lumps (pixels with three
    # neighbours) at its joints; the planner reads those as junctions and stops there.
    lumpy = paths = 0
    for i in kanji.split_indices(kanji_set, "train")[:30]:
        for c in kanji_set.strokes(int(i)):
            img = np.zeros((100, 100), np.uint8)
            pts = np.rint(kanji.sample_cubics(c, step=1.5)).astype(np.int32)
            cv2.polylines(img, [pts.reshape(-1, 1, 2)], False, 255, 1, cv2.LINE_8)
            ink = img > 0
            if not (canonical._degree(ink)[ink] >= 3).any():
                continue
            lumpy += 1
            paths += _ends_and_junctions(canonical.canonicalise(ink)) == (2, 0, 1)
    assert lumpy >= 20  # the case is common
    assert paths >= 0.75 * lumpy  # all but strokes that cross or retrace themselves


@pytest.mark.parametrize("offset", [(2, 0), (2, 1), (2, 2), (1, 2)])
def test_one_pixel_break_at_any_slope_is_filled(offset):
    dx, dy = offset
    a = _line([[4, 4], [4 + 6 * dx, 4 + 6 * dy]])
    b = _line([[4 + 7 * dx, 4 + 7 * dy], [4 + 13 * dx, 4 + 13 * dy]])
    out = canonical.canonicalise(a | b)
    assert _ends_and_junctions(out) == (2, 0, 1)
    assert (out & ~(a | b)).sum() == 1


def test_one_pixel_break_at_a_corner_is_filled():
    img = _line([[4, 10], [20, 10]]) | _line([[22, 12], [22, 30]])  # the corner pixel is gone
    out = canonical.canonicalise(img)
    assert _ends_and_junctions(out) == (2, 0, 1)


def test_curve_rule_matches_demonstrations(kanji_set):
    # Thick ink is redrawn with the demonstrations' own rule (jdraw.data.demos).
    for c in kanji_set.strokes(int(kanji.split_indices(kanji_set, "train")[0])):
        q = kanji.sample_cubics(c)
        ref = demo.clean_path(np.floor(q + 0.5).astype(np.int64))
        assert np.array_equal(canonical._draw_curve(q), ref)


@pytest.mark.parametrize("thickness", [2, 3, 5])
def test_thick_line_becomes_a_straight_jdraw_line(thickness):
    img = np.zeros((60, 60), np.uint8)
    cv2.line(img, (8, 10), (52, 31), 255, thickness)
    out = canonical.canonicalise(img > 0)
    assert _ends_and_junctions(out) == (2, 0, 1)
    ref = _line([[8, 10], [52, 31]], (60, 60))
    near = cv2.dilate(ref.astype(np.uint8), np.ones((3, 3), np.uint8)) > 0
    assert not (out & ~near).any()  # within 1 px of the line jdraw draws
    assert abs(int(out.sum()) - int(ref.sum())) <= thickness + 1  # ends a radius short at most


def test_antialiased_lines_are_redrawn_and_clean_lines_are_not(kanji_set):
    # Anti-aliased lines thresholded are lumpy all along: they are redrawn from their
    # skeleton like thick ink; jdraw's own lines are not touched that way.
    rough = 0
    for i in kanji.split_indices(kanji_set, "train")[:10]:
        t = demo.sample(kanji_set, int(i)).target
        assert not canonical.is_rough(t)
        aa = evaluate.rasterise(kanji_set, int(i), "aa")
        rough += canonical.is_rough(aa)
        c = canonical.canonicalise(aa)
        assert sum(1 for _ in canonical._lumps(c)) <= 2
        assert metrics.tolerant_pixel_accuracy(t, c, 1) > 0.97
    assert rough >= 8


def test_a_lone_lump_in_a_clean_drawing_is_kept(kanji_set):
    # jdraw draws a lump where a stroke overshoots the corner it meets by a pixel: the
    # planner's cue that two strokes meet there. A drawing with just one keeps it.
    found = 0
    for i in kanji.split_indices(kanji_set, "train")[:600]:
        t = demo.sample(kanji_set, int(i)).target
        lumps = list(canonical._lumps(t))
        if len(lumps) != 1:
            continue
        found += 1
        y0, x0, cl = lumps[0]
        c = canonical.canonicalise(t)
        assert c[y0 : y0 + cl.shape[0], x0 : x0 + cl.shape[1]][cl].all()
        if found == 2:
            break
    assert found == 2


def _ray(angle_deg, n=10):
    """``[n + 1, 2]`` points from the origin outwards at ``angle_deg``."""
    a = np.radians(angle_deg)
    return np.arange(n + 1)[:, None] * np.array([np.cos(a), np.sin(a)])


def test_join_straight_draws_lines_through_junctions_as_one():
    from jdraw.images import skeleton

    # A crossing: four rays from one node; 0/180 and 60/240 degrees go straight through.
    polys = {k: _ray(a) for k, a in enumerate((0, 60, 180, 240))}
    out = skeleton.join_straight(polys, {"n": [(k, True) for k in polys]}, reach=5)
    assert len(out) == 2
    for line in out:  # each a straight line through the node, end to end
        d = line[-1] - line[0]
        assert np.linalg.norm(d) == pytest.approx(20)
        u = line - line[0]
        assert np.allclose(u[:, 0] * d[1] - u[:, 1] * d[0], 0, atol=1e-9)  # on the line
    # A T: the bar is one line, the stem stays alone; an L corner is not joined.
    tee = {k: _ray(a) for k, a in enumerate((0, 180, 90))}
    out = skeleton.join_straight(tee, {"n": [(k, True) for k in tee]}, reach=5)
    assert sorted(len(p) for p in out) == [11, 21]
    ell = {k: _ray(a) for k, a in enumerate((0, 90))}
    assert len(skeleton.join_straight(ell, {"n": [(0, True), (1, True)]}, reach=5)) == 2
    # Ends given as last points, and a chain of joins through two nodes.
    chain = {0: _ray(180)[::-1], 1: np.array([[0.0, 0], [10, 0]]), 2: _ray(0) + [10, 0]}
    ends = {"a": [(0, False), (1, True)], "b": [(1, False), (2, True)]}
    (line,) = skeleton.join_straight(chain, ends, reach=5)
    assert abs(line[-1][0] - line[0][0]) == pytest.approx(30)


@pytest.mark.parametrize("style", ["px3", "px5"])
def test_thick_crossing_lines_stay_straight_through_the_crossing(style):
    """Two thick lines crossing at 45 degrees: each canonical line goes straight on
    through the crossing, as jdraw draws two crossing strokes (the thinned lump
    of an earlier version bent one line into the other there)."""
    from jdraw.data import variants

    a = [np.array([[[20.0, 50], [40, 50], [60, 50], [80, 50]]])]  # one cubic: horizontal
    b = [np.array([[[30.0, 80], [45, 65], [65, 45], [80, 30]]])]  # rising at 45 degrees
    out = canonical.canonicalise(variants.draw(a + b, style))
    ys, xs = np.nonzero(out)
    near_a = (np.abs(ys - 50) <= 1) & (xs >= 25) & (xs <= 75)
    # The horizontal line: one pixel per column across the crossing, within 1 px of y = 50.
    cols = xs[near_a & (np.abs(xs - 60) <= 6)]  # they cross at x = 60
    assert sorted(set(cols)) == list(range(54, 67))
    assert len(cols) <= 13 + 2  # the other line's own pixels where it passes
