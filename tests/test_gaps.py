"""jdraw.images.gaps: how close a drawing's separate lines come, and the scale it sets."""

import cv2
import numpy as np

from jdraw.images.prepare import prepare
from jdraw.tiling import layout

PEN = 5  # px, OpenCV thickness
TOL = 2.0  # px, centreline distances measured on a thinned, binarised drawing


def drawn(*polylines, shape=(200, 400), closed=False) -> np.ndarray:
    img = np.full(shape, 255, np.uint8)
    for p in polylines:
        q = np.round(np.asarray(p, float)).astype(np.int32).reshape(-1, 1, 2)
        cv2.polylines(img, [q], closed, 0, PEN, cv2.LINE_8)
    return img


def test_two_lines_keep_the_distance_between_them():
    for d in (12, 16):
        prep = prepare(drawn([(20, 60), (380, 60)], [(20, 60 + d), (380, 60 + d)]))
        assert abs(prep.gap - d) <= TOL, (d, prep.gap, prep.width)


def test_a_lone_line_and_a_junction_set_no_gap():
    """Nothing comes close: the gap is the largest looked for, four stroke widths."""
    line = prepare(drawn([(20, 100), (380, 120)]))
    assert line.gap == 4 * line.width
    # Arms meeting at 60 degrees are close only at their apex, which is not a gap.
    vee = prepare(drawn([(60, 20), (200, 180), (340, 20)]))
    assert vee.gap == 4 * vee.width


def test_a_round_loop_keeps_its_width():
    r = 7  # centreline radius: the loop's sides are 2 r apart
    prep = prepare(
        drawn(
            *[[(200 + r * np.cos(t), 100 + r * np.sin(t)) for t in np.linspace(0, 2 * np.pi, 60)]],
            [(20, 100), (193, 100)],
        )
    )
    assert abs(prep.gap - 2 * r) <= TOL, (prep.gap, prep.width)


def test_a_tiled_drawing_is_drawn_at_min_gap_over_its_gap():
    wave = [(20 + x, 100 + 60 * np.sin(x / 40)) for x in np.linspace(0, 1500, 400)]
    prep = prepare(drawn(wave, shape=(200, 1560)))
    scale, single = layout.choose_scale(prep, 4.0)
    assert not single
    assert np.isclose(scale, 4.0 / prep.gap) and scale < 4.0 / prep.width
    # A character-sized drawing is still fitted to one canvas as before.
    small = prepare(drawn([(20, 20), (90, 20), (90, 90)], shape=(120, 120)))
    scale, single = layout.choose_scale(small, 4.0)
    assert single and np.isclose(scale, layout.CHAR_EXTENT / 70, rtol=0.1)


def test_joined_up_writing_is_drawn_at_the_size_the_planner_learned_it(monkeypatch):
    """A joined word whose lines would allow it larger is drawn with its x-height band
    JOINED_CORE canvas px high (at the default min_gap; twice that at twice min_gap).
    A row of kanji-sized boxes, whose lines allow the same scale, is drawn at it."""
    x_height = 80.0
    humps = [
        (20 + x, 150 - x_height * abs(np.sin(np.pi * x / 60))) for x in np.arange(0, 1200, 2.0)
    ]
    word = prepare(drawn(humps, shape=(200, 1240)))
    boxes = prepare(
        drawn(
            *[
                [
                    (20 + 180 * k, 20),
                    (180 + 180 * k, 20),
                    (180 + 180 * k, 180),
                    (20 + 180 * k, 180),
                    (20 + 180 * k, 20),
                ]
                for k in range(6)
            ],
            shape=(200, 1100),
        )
    )
    monkeypatch.setattr(layout, "choose_scale", lambda prep, min_gap: (0.8, False))
    scale, tiles, _ = layout.layout(word)
    assert tiles and all(t.joined for t in tiles)
    assert abs(scale * x_height - layout.JOINED_CORE) <= 0.1 * layout.JOINED_CORE, scale
    wider, _, _ = layout.layout(word, min_gap=2 * layout.MIN_GAP)
    assert np.isclose(wider, 2 * scale, rtol=0.05)
    scale, tiles, _ = layout.layout(boxes)
    assert scale == 0.8 and not any(t.joined for t in tiles)


def test_joined_up_writing_is_drawn_no_smaller_than_keeps_its_lines_apart(monkeypatch):
    """Shrinking stops where the drawing's separate lines (its measured gap) would come
    closer than SEPARATE canvas px: a long line drawing taken for joined-up writing (a
    skyline over houses) keeps its detail."""
    from jdraw.images.prepare import Prepared

    x_height = 80.0
    humps = [
        (20 + x, 150 - x_height * abs(np.sin(np.pi * x / 60))) for x in np.arange(0, 1200, 2.0)
    ]
    word = prepare(drawn(humps, shape=(200, 1240)))
    monkeypatch.setattr(layout, "choose_scale", lambda prep, min_gap: (0.8, False))
    free = layout.JOINED_CORE / x_height  # about the scale that makes the core JOINED_CORE
    monkeypatch.setattr(Prepared, "gap", property(lambda self: layout.SEPARATE / (2 * free)))
    scale, _, _ = layout.layout(word)
    assert np.isclose(scale, 2 * free)  # held at the lines' floor, twice as large
    monkeypatch.setattr(Prepared, "gap", property(lambda self: layout.SEPARATE / (0.5 * free)))
    scale, _, _ = layout.layout(word)
    assert abs(scale - free) <= 0.1 * free  # the floor is below: shrunk as far as the core asks


def test_a_short_piece_of_mostly_joined_writing_is_joined_too(monkeypatch):
    """A cursive hand lifts now and then inside a word ("riv" + "er"): the short piece
    after the lift is still joined-up writing when most of the drawing is. A short
    piece beside boxes (a printed drawing) is not."""
    x_height = 80.0
    wave = lambda x0, x1: [
        (x0 + x, 150 - x_height * abs(np.sin(np.pi * x / 60))) for x in np.arange(0, x1 - x0, 2.0)
    ]
    word = prepare(drawn(wave(20, 900), wave(960, 1050), shape=(200, 1100)))
    monkeypatch.setattr(layout, "choose_scale", lambda prep, min_gap: (0.8, False))
    _, tiles, regions = layout.layout(word)
    assert len(regions) == 2
    assert all(t.joined for t in tiles)
    box = [(20, 20), (180, 20), (180, 180), (20, 180), (20, 20)]
    printed = prepare(
        drawn(*[[(x + 180 * k, y) for x, y in box] for k in range(6)], wave(1120, 1210),
              shape=(200, 1260))
    )  # fmt: skip
    _, tiles, regions = layout.layout(printed)
    assert len(regions) == 7 and not any(t.joined for t in tiles)
