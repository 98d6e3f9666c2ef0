"""Crumbs: a stroke of a pixel or two drawn as part of the stroke it touches."""

import numpy as np

from jdraw import geometry
from jdraw.planner import crumbs


def _line(x0, y0, x1, y1):
    n = max(abs(x1 - x0), abs(y1 - y0))
    t = np.arange(n + 1)[:, None] / n
    return np.rint(np.array([x0, y0]) + t * np.array([x1 - x0, y1 - y0]))


def test_crumbs_are_drawn_as_part_of_the_stroke_they_touch():
    bar = _line(10, 50, 60, 50)
    tail = _line(61, 51, 63, 53)  # touches the bar's end: drawn on from it
    nub = _line(30, 49, 30, 47)  # touches its middle: a detour out and back
    dot = _line(80, 80, 81, 80)  # touches nothing: stays a stroke
    long = _line(40, 51, 40, 60)  # longer than a crumb: stays a stroke
    strokes = [bar, nub, tail, dot, long]
    out = crumbs.absorb_crumbs(strokes)
    assert len(out) == 3
    np.testing.assert_array_equal(geometry.render_strokes(out), geometry.render_strokes(strokes))
    host = out[0]
    assert tuple(host[0]) == (10, 50) and tuple(host[-1]) == (63, 53)
    assert np.abs(np.diff(host, axis=0)).max() <= 1  # every move to a neighbour
    assert any(np.array_equal(s, dot) for s in out)
    assert len(crumbs.absorb_crumbs(strokes, crumb=0)) == 5


def test_a_stroke_that_adds_a_pixel_or_two_is_cut_down_to_them_and_drawn_with_its_neighbour():
    # An N's apex cut by a pixel: the stem stops one short of the top, and the
    # pen comes back for that pixel and runs on down the stem it already drew.
    stem_and_slant = np.concatenate([_line(20, 80, 20, 21), _line(21, 21, 40, 60)])
    back = _line(20, 20, 20, 40)  # adds (20, 20) only
    strokes = [stem_and_slant, back]
    trimmed = crumbs.trim_to_new_ink(strokes)
    np.testing.assert_array_equal(trimmed[1], [[20, 20]])
    out = crumbs.absorb_crumbs(strokes)
    assert len(out) == 1
    np.testing.assert_array_equal(geometry.render_strokes(out), geometry.render_strokes(strokes))
    # More new pixels than a crumb, new pixels in two runs, or none: left as they are.
    long = _line(20, 14, 20, 40)  # adds 7 pixels above the stem
    gaps = np.concatenate([[[19, 50]], _line(20, 51, 20, 70), [[21, 71]]])  # two runs of one
    for other in (long, gaps):
        np.testing.assert_array_equal(crumbs.trim_to_new_ink([stem_and_slant, other])[1], other)
    covered = _line(20, 30, 20, 40)
    np.testing.assert_array_equal(crumbs.trim_to_new_ink([stem_and_slant, covered])[1], covered)


def test_with_ends_a_stroke_adding_pixels_in_two_runs_loses_only_its_covered_ends():
    line = _line(10, 50, 40, 50)
    # Drawn over the line's middle, adding a pixel above it at two places.
    other = np.array(
        [[18, 50], [19, 50], [20, 49], [21, 50], [22, 50], [23, 50], [24, 49], [25, 50], [26, 50]],
        float,
    )
    cut = crumbs.trim_to_new_ink([line, other], ends=True)[1]
    np.testing.assert_array_equal(cut, other[2:7])  # from the first new pixel to the last
    np.testing.assert_array_equal(crumbs.trim_to_new_ink([line, other])[1], other)
    covered = _line(15, 50, 20, 50)
    assert crumbs.trim_to_new_ink([line, covered], drop=True)[1] is None
