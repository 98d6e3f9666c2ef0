"""Counting and rendering of the cursive-word evaluation (jdraw.evaluation.words)."""

import numpy as np
import pytest

from jdraw.data import cursive
from jdraw.evaluation import words


def _line(x0, x1, y):
    return np.array([[x0, y], [x1, y]], float)


def test_pieces_are_8_connected():
    ink = np.zeros((10, 10), bool)
    ink[2, 2] = ink[3, 3] = True  # diagonal neighbours: one piece
    ink[7, 1:5] = True
    assert words.pieces(ink) == 2
    assert words.pieces(np.zeros((4, 4), bool)) == 0


def test_score_word_counts_strokes_per_piece():
    ink = np.zeros((20, 40), bool)
    ink[5, 2:16] = True
    ink[14, 2:31] = True
    written = [_line(2, 15, 5), _line(2, 30, 14)]
    # The second piece drawn in two strokes, cut three quarters along.
    drawn = [_line(2, 15, 5), _line(2, 23, 14), _line(24, 30, 14)]
    r = words.score_word(ink, written, drawn)
    assert (r["written"], r["drawn"], r["pieces"]) == (2, 3, 2)
    assert r["stroke_ratio"] == pytest.approx(1.5)
    assert r["strokes_per_piece"] == pytest.approx(1.5)
    assert r["written_per_piece"] == pytest.approx(1.0)
    assert r["order_all_pairs"] == 1.0 and r["direction"] == 1.0
    assert 0.6 < r["stroke_acc"] < 1.0  # the short piece overlaps its stroke a little
    perfect = words.score_word(ink, written, written)
    assert perfect["stroke_acc"] == pytest.approx(1.0) and perfect["strokes_per_piece"] == 1.0
    # Drawn in the other order and backwards: order and direction both wrong.
    back = words.score_word(ink, written, [p[::-1] for p in written[::-1]])
    assert back["order_all_pairs"] == 0.0 and back["direction"] == 0.0


def test_render_word_inks_its_written_strokes():
    h = words.word_height("hello")
    assert words.MIN_HEIGHT <= h <= words.MAX_HEIGHT and h == words.word_height("hello")
    img, written = words.render_word("hello", 120)
    ink = img < 128
    rows = np.flatnonzero(ink.any(1))
    assert 120 <= rows[-1] - rows[0] <= 120 + words.PEN + 1  # the pen reaches past the line
    for p in written:
        q = np.floor(p + 0.5).astype(int)
        assert ink[q[:, 1], q[:, 0]].all()
    assert len(written) == len(cursive.word_strokes("hello")) and words.pieces(ink) == 1


def test_untraced_pieces_cut_a_stroke_where_it_goes_back_over_its_line():
    # Out 40 px, back 30 px over the same line, then away at a right angle.
    spur = np.array([[0, 0], [40, 0], [10, 0], [10, 40]], float)
    # The first half of the gap after the turn is not yet on the earlier line.
    assert words.retraced(spur).sum() == pytest.approx(30 - words.RETRACE_GAP / 2, abs=2)
    assert words.untraced_pieces(spur) == 2
    # Back over less than RETRACE_MIN: still one piece.
    short = np.array([[0, 0], [40, 0], [30, 0], [30, 40]], float)
    assert words.untraced_pieces(short) == 1
    # A loop that crosses its own line at a right angle draws nothing twice.
    loop = np.array([[0, 20], [40, 20], [40, 0], [20, 0], [20, 40]], float)
    assert words.untraced_pieces(loop) == 1
    # Two retraces: three pieces; the word's score reports them per written stroke.
    two = np.array([[0, 0], [40, 0], [10, 0], [10, 40], [10, 10], [50, 10]], float)
    assert words.untraced_pieces(two) == 3
    ink = np.zeros((60, 60), bool)
    r = words.score_word(ink, [spur + 5, short + 5], [spur + 5])
    assert r["untraced_ratio"] == pytest.approx(1.5)


@pytest.mark.filterwarnings("ignore:Mean of empty slice")  # no planned strokes: no direction
def test_words_can_be_written_at_one_height(monkeypatch):
    """``height=`` writes every word that high (the ink's top to its bottom) instead of
    by its hash, and the planner sees that drawing."""
    from types import SimpleNamespace

    from jdraw.tiling import plan_image as tiling

    seen = []

    def planner(img, **kwargs):
        ink = np.flatnonzero((np.asarray(img) < 128).any(1))
        seen.append(int(ink[-1] - ink[0]))
        return SimpleNamespace(strokes=[])

    monkeypatch.setattr(tiling, "plan_image", planner)
    res = words.evaluate_words("val", 3, height=150, progress=False)
    assert res["height"] == 150 and [p["height"] for p in res["words"]] == [150] * 3
    assert all(abs(h - 150) <= words.PEN + 1 for h in seen), seen  # the pen and its AA edge
    res = words.evaluate_words("val", 3, progress=False)
    assert [p["height"] for p in res["words"]] == [
        words.word_height(w) for w in cursive.split_words("val")[:3]
    ]
