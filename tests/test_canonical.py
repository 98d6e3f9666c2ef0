"""Canonical lines: other rasterisers, thick pens and 1-pixel breaks become jdraw's lines."""

import cv2
import numpy as np
import pytest

from jdraw import geometry as raster
from jdraw.data import demos as demo
from jdraw.data import kanji
from jdraw.evaluation import evaluate
from jdraw.images import canonical


def _line(points, shape=(40, 40)):
    return raster.render_strokes([np.asarray(points)], shape)


def test_canonical_lines_are_left_as_they_are():
    # Demonstration paths (jdraw's rasteriser, staircase joints cleaned) are canonical.
    path = demo.clean_path(raster.polyline_pixels(np.array([[3, 5], [30, 12], [20, 35]])))
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
