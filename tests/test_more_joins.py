"""As many accepted joins as can be made (jdraw.planner.more_joins), in joined-up writing."""

import numpy as np
from flax import nnx

from jdraw.planner import more_joins, splits

# Best first: the greedy take of A (stroke 0's end to 1's start) blocks B and C, which
# use one end of A each and a free end each.
A, B, C = (0, True, 1, False), (0, True, 2, False), (1, False, 3, True)


def test_one_join_given_up_for_two_that_it_blocked():
    assert more_joins.greedy([A, B, C], 4) == [A]
    assert sorted(more_joins.most_joins([A, B, C], 4)) == sorted([B, C])
    assert more_joins.most_joins([A, B], 4) == [A]  # nothing to gain: no swap


def test_a_swap_that_would_close_a_ring_of_strokes_is_not_made():
    # D keeps 1 and 2 one chain; B' and E would then join 0 to 2 and 1 to 0: a ring.
    D, B2, E = (1, True, 2, False), (0, True, 2, True), (1, False, 0, False)
    assert more_joins.most_joins([A, D, B2, E], 3) == [A, D]
    # With a fourth stroke for E's other end, the same swap makes a chain 3-1-2-0.
    E4 = (1, False, 3, False)
    taken = more_joins.most_joins([A, D, B2, E4], 4)
    assert sorted(taken) == sorted([D, B2, E4])


def _line(x0, y0, x1, y1):
    n = max(abs(x1 - x0), abs(y1 - y0))
    t = np.arange(n + 1)[:, None] / n
    return np.rint(np.array([x0, y0]) + t * np.array([x1 - x0, y1 - y0]))


def test_join_many_makes_most_joins_where_joins_go_back_over_the_line_only(monkeypatch):
    strokes = [
        _line(10, 10, 30, 10),
        _line(32, 10, 50, 10),
        _line(32, 12, 32, 30),
        _line(10, 30, 10, 12),
    ]
    pairs = [A, B, C]
    monkeypatch.setattr(
        splits, "all_pairs", lambda s, *a, **k: (pairs, np.zeros((len(pairs), 4), np.float32))
    )
    monkeypatch.setattr(splits, "drawing_rows", lambda rows, s, on=True: rows)
    score = lambda fn, sp, x: np.array([3.0, 2.0, 1.0])  # the net accepts all three, A best
    monkeypatch.setattr(splits, "_score", score)
    sp = splits.Splitter(hidden=8, patches=False, rngs=nnx.Rngs(0))
    (plain,) = splits.join_many(sp, [strokes], retrace=0)
    assert len(plain) == 3  # A only: 4 strokes, one join
    (joined,) = splits.join_many(sp, [strokes], retrace=40)
    assert len(joined) == 2  # B and C instead: two joins
    # B: 0's end to 2's start; C: 3's end to 1's start. Chains 0-2 and 3-1, by their ends:
    chains = {frozenset({tuple(s[0]), tuple(s[-1])}) for s in joined}
    assert chains == {
        frozenset({(10.0, 10.0), (32.0, 30.0)}),
        frozenset({(10.0, 30.0), (50.0, 10.0)}),
    }
