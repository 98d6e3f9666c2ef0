import numpy as np
import pytest

import jdraw
from jdraw.data import demos as demo
from jdraw.planner import plan as api


@pytest.fixture(scope="module")
def char(kanji_set):
    return demo.sample(kanji_set, 42)


def test_plan_covers_ink_and_stays_on_it(char):
    p = jdraw.plan(char.target)
    assert len(p) == 1 and p.actions.shape[0] == 1 and p.actions.shape[2] == 3
    drawn = jdraw.render(p)[0]
    assert not p.truncated[0]
    assert jdraw.pixel_accuracy(char.target, drawn) == 1.0  # masks keep the pen on ink
    a = p.actions[0, : p.lengths[0]]
    local = a[a[:, 2] == 1]
    assert np.abs(local[:, :2]).max() <= 2
    assert np.all(p.actions[0, p.lengths[0] :] == 0)


def test_batched_plan_matches_single_and_does_not_recompile(char, kanji_set):
    other = demo.sample(kanji_set, 7).target
    batch = np.stack([char.target, other])
    p2 = jdraw.plan(batch)
    before = api._TRACES["plan"]
    p2b = jdraw.plan(batch.astype(np.float32))
    assert api._TRACES["plan"] == before  # same shape: no new trace
    np.testing.assert_array_equal(p2.actions, p2b.actions)
    p1 = jdraw.plan(other)
    n = p1.lengths[0]
    np.testing.assert_array_equal(p1.actions[0, :n], p2.actions[1, :n])


def test_window_and_full_encoding_plan_identically(char):
    a = jdraw.plan(char.target, max_steps=120)
    b = jdraw.plan(char.target, max_steps=120, local_encoding="full")
    np.testing.assert_array_equal(a.actions, b.actions)


def test_empty_image_gives_no_strokes():
    p = jdraw.plan(np.zeros((100, 100), np.uint8))
    assert p.strokes == [[]] and p.lengths[0] == 0 and not p.truncated[0]


def test_all_ink_ends_within_bound():
    p = jdraw.plan(np.ones((100, 100)), max_steps=64, canonicalise=False)  # not lines: the bound
    assert p.lengths[0] <= 64 and p.truncated[0]


@pytest.mark.parametrize(
    "bad, match",
    [
        (np.zeros((50, 50)), "100x100"),
        (np.zeros((2, 3, 100, 100)), "channels"),
        (np.zeros((100, 100, 3)), "channels"),
        (np.zeros(100), "rank"),
        (np.full((100, 100), np.nan), "NaN"),
        (np.full((100, 100), np.inf), "NaN or inf"),
        (np.array([["a"] * 100] * 100), "dtype"),
    ],
)
def test_bad_input_raises(bad, match):
    with pytest.raises(ValueError, match=match):
        jdraw.plan(bad)
