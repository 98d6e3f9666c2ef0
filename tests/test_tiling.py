"""Drawings beyond one canvas: layout, stitching across tile borders, reading order."""

import cv2
import numpy as np
import pytest

from jdraw import geometry
from jdraw.images.load import load_image
from jdraw.images.prepare import prepare
from jdraw.plans import Plan
from jdraw.tiling import layout
from jdraw.tiling import plan_image as tiling
from jdraw.tiling.stitch import stitch
from tests.doubles import trace_planner
from tests.synthetic import centreline_scores, photo_like, text_centrelines

TOL_PX = 4.0
MIN_SCORE = 0.95
# A lone wave's lines are far apart (its gap is capped at four stroke widths), so it is
# drawn small; four times the default min_gap draws it at min_gap / width, over many tiles.
ACROSS_TILES = 16.0


def wave(length=900.0, amplitude=110.0, periods=3.5, x0=40.0, y0=150.0):
    """One long stroke that does not cross itself: a word's worth of humps."""
    t = np.linspace(0.0, 1.0, 800)
    return np.stack([x0 + length * t, y0 + amplitude * np.sin(2 * np.pi * periods * t)], 1)


def reversing_planner(images, **kwargs):
    """Plans like :func:`trace_planner`, then draws every tile backwards."""
    plan = trace_planner(images, **kwargs)
    strokes = [[s[::-1] for s in tile[::-1]] for tile in plan.strokes]
    return Plan(strokes, plan.actions, plan.lengths, plan.truncated)


@pytest.mark.parametrize("planner", [trace_planner, reversing_planner])
@pytest.mark.parametrize("light", [False, True])
def test_stroke_crossing_tile_borders_stays_one_polyline(planner, light):
    line = wave()
    img = photo_like([line], (300, 980), width=6, light_ink=light, gradient=0.6, noise=0.08)
    result = tiling.plan_image(img, planner=planner, min_gap=ACROSS_TILES, progress=False)
    cols = {round(t.transform.offset[0]) for t in result.tiles}
    rows = {round(t.transform.offset[1]) for t in result.tiles}
    assert len(cols) >= 4 and len(rows) >= 2  # the stroke crosses vertical and horizontal borders
    assert len(result.strokes) == 1
    assert result.border_joins >= len(result.tiles) - 1 and result.border_breaks == 0
    precision, recall = centreline_scores(result.strokes, [line], TOL_PX)
    assert precision >= MIN_SCORE and recall >= MIN_SCORE, (precision, recall)
    # In input pixel coordinates, in one motion from one end of the wave to the other.
    ends = result.strokes[0][[0, -1]]
    gaps = np.linalg.norm(ends[:, None] - line[None, [0, -1]], axis=-1)
    assert min(gaps[0, 0] + gaps[1, 1], gaps[0, 1] + gaps[1, 0]) < 2 * TOL_PX


def test_sentence_photo_any_size_in_reading_order():
    lines, shape = text_centrelines("hello world", 4.0)
    img = photo_like(lines, shape, width=9, gradient=0.6, noise=0.08, seed=5)
    result = tiling.plan_image(img, planner=trace_planner, progress=False)
    assert len(result.tiles) > 1 and result.shape == shape
    precision, recall = centreline_scores(result.strokes, lines, TOL_PX)
    assert precision >= MIN_SCORE and recall >= MIN_SCORE, (precision, recall)
    starts = np.array([s[:, 0].mean() for s in result.strokes])
    # Left to right: the words' strokes come in order of position, up to a letter's width.
    assert np.all(np.diff(starts) > -0.1 * shape[1])
    boxes = np.array(result.regions)
    assert np.all(np.diff((boxes[:, 0] + boxes[:, 2]) / 2) > 0)


def test_small_drawing_fits_one_canvas():
    lines, shape = text_centrelines("R", 2.0, script=False)
    img = photo_like(lines, shape, width=3, noise=0.03)
    result = tiling.plan_image(img, planner=trace_planner, progress=False)
    assert len(result.tiles) == 1
    ys, xs = np.nonzero(result.tiles[0].image)
    assert max(np.ptp(xs), np.ptp(ys)) == pytest.approx(80, abs=2)
    precision, recall = centreline_scores(result.strokes, lines, TOL_PX)
    assert precision >= MIN_SCORE and recall >= MIN_SCORE


def test_stitch_joins_across_tiles_before_inside_a_tile():
    a = np.array([[95, 5], [96, 5], [97, 5], [98, 5], [99, 5]])
    b = np.array([[103, 6], [102, 5], [101, 5], [100, 5]])  # drawn towards the border
    # touches a's end but lies in a's tile (longer than a crumb, which would be drawn with a)
    c = np.array([[99, 6], [98, 7], [97, 8], [96, 9], [95, 10], [94, 11]])
    joined = stitch([(0, a), (1, b), (0, c)])
    assert len(joined) == 2
    np.testing.assert_array_equal(joined[0], np.concatenate([a, b[::-1]]))
    np.testing.assert_array_equal(joined[1], c)
    # The stroke runs the way most of its pixels were planned: a's 5 against b's 4,
    # even when b is the earliest piece (which set the direction until 2026-12-05).
    joined = stitch([(1, b), (0, a)])
    np.testing.assert_array_equal(joined[0], np.concatenate([a, b[::-1]]))
    # On a tie the earliest piece's way.
    joined = stitch([(1, b), (0, a[1:])])
    np.testing.assert_array_equal(joined[0], np.concatenate([b, a[1:][::-1]]))


def test_stitch_draws_a_border_crumb_as_part_of_the_stroke_it_touches():
    # A line crosses a tile border; the second tile also drew a pixel of its own
    # beside the line's first pixel there, which no join can take.
    a = line_px([90, 5], [99, 5])
    b = line_px([100, 5], [110, 5])
    crumb = np.array([[100, 6]])
    report = {}
    joined = stitch([(0, a), (1, b), (1, crumb)], report)
    assert len(joined) == 1 and report["crumbs"] == 1 and report["joins"] == 1
    drawn = {tuple(q) for q in joined[0].tolist()}
    assert drawn == {tuple(q) for q in np.concatenate([a, b, crumb]).tolist()}
    assert np.all(np.abs(np.diff(joined[0], axis=0)) <= 1)  # still one motion
    # Without crumbs (the tiler's join_lifts=False knobs), it stays a pen lift.
    assert len(stitch([(0, a), (1, b), (1, crumb)], fragment=0)) == 2
    # A dot apart from every line is a stroke of its own.
    assert len(stitch([(0, a), (1, b), (1, np.array([[104, 9]]))])) == 2


def line_px(*corners):
    return geometry.polyline_pixels(np.array(corners))


def test_stitch_removes_pen_lifts_only_where_a_line_continues():
    # A hump: two strokes of one tile start at its top and run down either side.
    left, right = line_px([10, 10], [2, 13]), line_px([10, 10], [18, 13])
    report = {}
    joined = stitch([(0, left), (0, right)], report)
    assert len(joined) == 1
    assert report == {"joins": 0, "breaks": 0, "lift_joins": 1, "fragments": 0, "crumbs": 0}
    np.testing.assert_array_equal(joined[0], np.concatenate([right[::-1], left[1:]]))
    assert len(stitch([(0, left), (0, right)], smooth_cos=-2.0, fragment=0)) == 2
    # A corner is a pen lift a writer makes on purpose: kept.
    top, side = line_px([0, 0], [10, 0]), line_px([10, 0], [10, 10])
    assert len(stitch([(0, top), (0, side)])) == 2
    # Two ends meeting on a third stroke are a junction: kept.
    up, down = line_px([20, 19], [20, 10]), line_px([20, 20], [20, 30])
    bar = line_px([10, 20], [30, 20])
    assert len(stitch([(0, bar), (0, up), (0, down)])) == 3


def test_stitch_trims_retraces_and_fragments():
    a = line_px([0, 0], [10, 0], [6, 0])  # overshoots and comes back
    extra = line_px([10, 0], [8, 0], [11, 0])  # retraces a's end to reach one more pixel
    inside = line_px([3, 0], [5, 0])  # drawn again, adds nothing
    report = {}
    joined = stitch([(0, a), (0, inside), (0, extra)], report)
    assert report["fragments"] == 1 and report["lift_joins"] == 1
    assert len(joined) == 1
    np.testing.assert_array_equal(joined[0], line_px([0, 0], [11, 0]))


def test_trim_retrace_cuts_ends_drawn_twice_and_keeps_a_closed_loop():
    from jdraw.tiling.stitch import _trim_retrace

    def trim(points, least=2):
        return [tuple(q) for q in _trim_retrace(np.array(points, np.int64), least)]

    line = [(x, 0) for x in range(4)]
    assert trim(line + [(2, 0), (1, 0)]) == line  # overshoot and back: cut
    assert trim(line + [(2, 0)]) == line + [(2, 0)]  # one pixel back: fewer than `least`
    assert trim(line + [(2, 0)], least=1) == line
    ring = [(0, 0), (1, 0), (1, 1), (0, 1), (0, 0)]
    assert trim(ring) == ring  # a loop that ends on its first pixel keeps it
    run = [(x, 0) for x in range(5)]
    assert trim([(2, 0), (1, 0)] + run) == run  # started over what it draws next
    assert trim([(2, 0), (1, 0)] + run + [(3, 0), (2, 0)]) == run  # both ends
    assert trim([(5, 5)]) == [(5, 5)] and trim(np.zeros((0, 2))) == []


def test_stitch_keeps_every_pixel():
    rng = np.random.default_rng(0)
    pieces = []
    for _ in range(12):
        pts = np.cumsum(rng.integers(-2, 3, size=(rng.integers(1, 9), 2)), axis=0) + 20
        pieces.append((int(rng.integers(0, 3)), pts))
    joined = stitch(pieces)
    drawn = {tuple(q) for p in joined for q in p.tolist()}
    planned = {tuple(q) for _, p in pieces for q in geometry.polyline_pixels(p).tolist()}
    assert planned <= drawn
    for p in joined:
        assert np.all(np.abs(np.diff(p, axis=0)) <= 1)  # one 8-connected motion each


def test_reading_order_lines_then_left_to_right():
    boxes = [
        (300, 10, 360, 60),  # line 1, right
        (10, 110, 60, 160),  # line 2, left
        (12, 12, 70, 58),  # line 1, left
        (45, 0, 50, 5),  # a dot above line 1's left word
        (200, 105, 260, 150),  # line 2, right
    ]
    assert layout._reading_order(boxes) == [2, 3, 0, 1, 4]  # the dot by its centre


def test_dots_outnumbering_letter_bodies_stay_marks():
    # Two joined pieces and four dots (an Arabic word): a median over boxes would be a
    # dot's height, the dots would count as letters, and the two over the left piece
    # would make a text line of their own, drawn before everything else.
    boxes = [
        (300, 40, 470, 120),  # right piece
        (10, 30, 250, 160),  # left piece
        (100, 0, 115, 15),  # two dots over the left piece
        (125, 0, 140, 15),
        (150, 170, 165, 185),  # two dots under it
        (170, 170, 185, 185),
    ]
    tall = layout.tall_boxes(np.asarray(boxes, float))
    assert tall.tolist() == [True, True, False, False, False, False]
    line_of, spans = layout.text_lines(boxes)
    assert len(spans) == 1 and set(line_of.tolist()) == {0}
    assert layout._reading_order(boxes, rtl=True) == [0, 1, 5, 4, 3, 2]
    assert layout._reading_order(boxes) == [1, 2, 3, 4, 5, 0]


def test_an_underline_does_not_make_the_letters_marks():
    letters = [(10 + 60 * k, 0, 50 + 60 * k, 50) for k in range(5)]
    underline = (0, 60, 300, 62)
    assert layout.tall_boxes(np.asarray([*letters, underline], float)).all()


def test_a_flat_piece_is_not_a_mark():
    # A kana drawn large: a wide flat top stroke apart from a tall one (like the two
    # strokes of katakana a). Under half the tall one's height, but wide: not a mark.
    boxes = [(0, 0, 70, 28), (20, 10, 50, 80)]
    assert layout.tall_boxes(np.asarray(boxes, float)).all()
    dots = [(0, 0, 60, 60), (70, 0, 84, 14)]  # a dot beside a letter
    assert layout.tall_boxes(np.asarray(dots, float)).tolist() == [True, False]


def test_batches_have_fixed_sizes_and_truncated_plans_are_completed():
    calls = []

    def forgetful(images, **kwargs):
        calls.append((images.shape, images.dtype))
        plan = trace_planner(images)
        strokes = [s[:-1] if len(s) > 1 else s for s in plan.strokes]
        return Plan(strokes, plan.actions, plan.lengths, np.ones(len(images), bool))

    line = wave()
    img = photo_like([line], (300, 980), width=6, noise=0.04)
    result = tiling.plan_image(
        img, planner=forgetful, batch_size=4, min_gap=ACROSS_TILES, progress=False
    )
    n = len(result.tiles)
    assert all(s[1:] == (100, 100) and s[0] in (1, 2, 4) and d == np.dtype(bool) for s, d in calls)
    assert sum(min(4, n - 4 * i) for i in range(len(calls))) == n
    assert result.truncated == n and result.completed_pixels > 0
    _, recall = centreline_scores(result.strokes, [line], TOL_PX)
    assert recall >= MIN_SCORE
    drawn = geometry.render_strokes(result.strokes, result.shape)
    assert drawn.any()


@pytest.mark.parametrize("light", [False, True])
def test_trained_planner_draws_a_line_across_tiles_in_one_motion(light):
    """With the bundled model the wave over 12 tiles is one polyline.

    The model lifts the pen inside tiles too (it starts strokes at the tops
    of humps, as KanjiVG strokes start); stitching removes those lifts.
    """
    line = wave()
    img = photo_like([line], (300, 980), width=6, light_ink=light, gradient=0.6, noise=0.08)
    result = tiling.plan_image(img, min_gap=ACROSS_TILES, progress=False)
    assert len(result.tiles) >= 8
    assert result.border_joins >= len(result.tiles) - 1 and result.border_breaks == 0
    assert len(result.strokes) == 1, len(result.strokes)
    precision, recall = centreline_scores(result.strokes, [line], TOL_PX)
    assert precision >= MIN_SCORE and recall >= MIN_SCORE, (precision, recall)


def test_character_sized_image_is_fitted_to_one_canvas():
    # The README's example (京, thick ink, 5 separate pieces) is one character:
    # the model must see it whole to order its strokes, not 5 regions.
    import pathlib

    path = pathlib.Path(__file__).parent.parent / "examples" / "images" / "kanji.png"
    prep = prepare(load_image(path))
    _, tiles, regions = layout.layout(prep)
    assert len(tiles) == 1 and len(regions) == 1


def _word_and_letters(thickness: int = 1, rings: int = 2) -> tuple[np.ndarray, list[np.ndarray]]:
    """``uint8 [120, 430]`` with 255 ink (wider with more ``rings``): a joined-up word and
    printed letters on one line.

    The word: five humps 30 px high (its x-height) and a loop rising 50 px above them,
    one line of ink 200 px long. The letters, as high: ``rings`` rings, an m (two
    arches, 50 px wide) and a dot over it. Returns the image and the word's lines.
    """
    x = np.arange(10, 211, dtype=np.float64)
    word = [np.stack([x, 80 - 30 * np.abs(np.sin(np.pi * (x - 10) / 40))], 1)]
    t = np.linspace(0, 2 * np.pi, 60)
    word.append(np.stack([110 + 8 * np.sin(t), 50 - 25 * (1 - np.cos(t))], 1))  # the loop
    ring = np.stack([255 + 15 * np.cos(t), 65 + 15 * np.sin(t)], 1)
    x0 = 280 + 40 * (rings - 1)  # where the m starts, 10 px after the last ring
    xm = np.arange(x0, x0 + 51, dtype=np.float64)
    m = np.stack([xm, 80 - 30 * np.abs(np.sin(np.pi * (xm - x0) / 50))], 1)
    dot = np.array([[x0 + 25.0, 35.0], [x0 + 26.0, 36.0]])
    img = np.zeros((120, x0 + 110), np.uint8)
    for p in [*word, *(ring + [40 * k, 0] for k in range(rings)), m, dot]:
        cv2.polylines(img, [np.rint(p).astype(np.int32)], False, 255, thickness)
    return img, word


def test_a_piece_running_through_several_letters_is_joined_up_writing():
    img, _ = _word_and_letters()
    n, labels, stats, _ = cv2.connectedComponentsWithStats(
        (img > 0).astype(np.uint8), connectivity=8
    )
    joined = layout.joined_pieces(labels, stats)
    left = np.argsort(stats[1:, cv2.CC_STAT_LEFT])  # word, two rings, m, dot
    assert n == 6 and joined[left].tolist() == [True, False, False, False, False]
    # The line's core is its x-height (the loop above it holds little ink): the word is
    # joined at 2.5 times it, and not by its box, which the loop makes 80 px high.
    word = left[0]
    assert stats[word + 1, cv2.CC_STAT_HEIGHT] * layout.JOINED_WIDTH > stats[word + 1, 2]
    # Squares the size of a kanji, side by side: their core is their whole height.
    squares = np.zeros((80, 300), np.uint8)
    for k in range(4):
        cv2.rectangle(squares, (10 + 70 * k, 10), (70 + 70 * k, 70), 1, 1)
    _, labels, stats, _ = cv2.connectedComponentsWithStats(squares, connectivity=8)
    assert not layout.joined_pieces(labels, stats).any()


def test_joined_up_writing_is_planned_with_joins_back_over_its_line(monkeypatch, tmp_path):
    """plan_image asks the default planner for ``retrace`` in joined-up writing's tiles
    only, and never where the plan has no splitter or is told not to. (With eight rings
    the printed letters hold most of the ink; where the word does, every tile is
    joined-up writing: tests/test_gaps.py.)"""
    from jdraw.planner.splits import JOINED_RETRACE

    img, _ = _word_and_letters(thickness=3, rings=8)
    calls = []

    def recording(images, **kwargs):
        calls.append((kwargs.get("retrace"), int(np.asarray(images).any(axis=(1, 2)).sum())))
        return trace_planner(images, **{k: v for k, v in kwargs.items() if k != "split"})

    monkeypatch.setattr(tiling, "default_planner", recording)
    plan = tiling.plan_image(255 - img, polarity="dark", progress=False)
    joined = sum(t.joined for t in plan.tiles)
    assert 0 < joined < len(plan.tiles)
    assert sum(n for r, n in calls if r == JOINED_RETRACE) == joined
    assert sum(n for r, n in calls if r is None) == len(plan.tiles) - joined
    for off in (dict(split=False), dict(retrace=False)):
        calls.clear()
        tiling.plan_image(255 - img, polarity="dark", progress=False, **off)
        assert {r for r, _ in calls} == {None}
    with pytest.raises(ValueError, match="retrace must be True or False"):
        tiling.plan_image(255 - img, progress=False, retrace=40)
    # jdraw draw --no-retrace reaches it.
    from jdraw import cli

    path = tmp_path / "word.png"
    cv2.imwrite(str(path), 255 - img)
    for flags, want in (([], {None, JOINED_RETRACE}), (["--no-retrace"], {None})):
        calls.clear()
        assert cli.main(["draw", str(path), "--no-progress", *flags]) == 0
        assert {r for r, _ in calls} == want


def test_tile_borders_run_through_the_least_ink_the_grid_allows():
    """A region 150 px wide takes two canvases, with 50 px to spare. Centred, their
    border would cut the ink at x = 85; it goes through the gap at 70-80 instead."""
    profile = np.full(300, 3)
    profile[:10] = profile[160:] = 0  # the region spans x = 10..159
    profile[70:81] = 0  # a gap between two letters
    g = layout._grid_start(profile, 10, 150, 2)
    assert g == -22  # its border at 78: no ink within 3 px of it
    assert g <= 10 and g + 2 * geometry.CANVAS >= 160  # the grid still covers the region
    assert layout._grid_start(np.full(300, 3), 10, 150, 2) == -15  # no gap: centred
    assert layout._grid_start(profile, 10, 60, 1) == -10  # one canvas: centred


def test_layout_places_each_regions_grid_by_its_ink(monkeypatch):
    """layout() asks _grid_start where each region's grid begins, with the region's
    own centreline pixels per column and row, and puts its tiles there."""
    img = np.full((200, 1500), 255, np.uint8)
    cv2.polylines(img, [np.array([[20, 100], [400, 40], [800, 160], [1480, 60]])], False, 0, 3)
    calls, real = [], layout._grid_start

    def spy(profile, start, size, n):
        g = real(profile, start, size, n)
        calls.append((int(np.sum(profile)), start, size, n, g))
        return g

    monkeypatch.setattr(layout, "_grid_start", spy)
    scale, tiles, _ = layout.layout(prepare(img))
    (sx, x, bw, nx, gx), (sy, y, bh, ny, gy) = calls  # one region: along x, then along y
    assert nx >= 2 and sx == sy > 0  # the same ink, counted by column and by row
    lefts = sorted({round(-t.transform.offset[0]) for t in tiles})
    assert lefts[0] == gx and all(b - a == geometry.CANVAS for a, b in zip(lefts, lefts[1:]))
    assert {round(-t.transform.offset[1]) for t in tiles} == {gy}
