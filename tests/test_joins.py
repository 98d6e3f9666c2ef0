"""Joining a stroke to the one that goes on from its end (jdraw.planner.joins)."""

import numpy as np
import pytest

from jdraw import geometry
from jdraw.planner import joins
from jdraw.plans import Plan, actions_from_strokes, strokes_from_actions


def _line(x0, y0, x1, y1):
    n = max(abs(x1 - x0), abs(y1 - y0))
    t = np.arange(n + 1)[:, None] / n
    return np.rint(np.array([x0, y0]) + t * np.array([x1 - x0, y1 - y0]))


def test_a_line_cut_in_two_is_joined_in_either_direction():
    a, b = _line(10, 50, 40, 50), _line(42, 50, 80, 50)  # 2-px gap, same heading
    (one,) = joins.join_strokes([a, b])
    assert tuple(one[0]) == (10, 50) and tuple(one[-1]) == (80, 50)
    assert np.abs(np.diff(one, axis=0)).max() <= 2  # every move a local one
    (one,) = joins.join_strokes([a, b[::-1]])  # the second drawn backwards
    assert tuple(one[0]) == (10, 50) and tuple(one[-1]) == (80, 50)
    (one,) = joins.join_strokes([b, a])  # found in either order; the first keeps its place
    assert {tuple(one[0]), tuple(one[-1])} == {(10, 50), (80, 50)}


def test_a_stroke_turned_round_to_be_joined_inks_the_same_pixels():
    a = np.array([[10.0, 50], [12, 51], [14, 52], [16, 53]])  # knight moves
    b = np.array([[17.0, 53], [19, 54], [21, 55], [23, 56]])
    for second in (b, b[::-1]):
        for strokes in ([a, second], [second, a], [a[::-1], second]):
            (one,) = joins.join_strokes(strokes)
            np.testing.assert_array_equal(
                geometry.render_strokes([one]), geometry.render_strokes(strokes)
            )


def test_corners_parallel_lines_and_far_ends_are_not_joined():
    down = _line(10, 10, 10, 50)
    right = _line(10, 50, 50, 50)  # an L: the line turns 90 degrees
    assert len(joins.join_strokes([down, right])) == 2
    assert len(joins.join_strokes([_line(10, 50, 40, 50), _line(40, 52, 10, 52)])) == 2
    assert len(joins.join_strokes([_line(10, 50, 40, 50), _line(45, 50, 80, 50)])) == 2
    slight = _line(42, 50, 80, 60)  # turns about 15 degrees: one line
    assert len(joins.join_strokes([_line(10, 50, 40, 50), slight])) == 1


def test_joins_stay_on_ink():
    a, b = _line(10, 50, 40, 50), _line(43, 50, 80, 50)
    ink = geometry.render_strokes([a, b])
    assert len(joins.join_strokes([a, b], ink)) == 2  # the 2 pixels between are not ink
    ink[50, 41:43] = True
    assert len(joins.join_strokes([a, b], ink)) == 1


def test_join_plan_keeps_actions_and_strokes_in_step():
    strokes = [[_line(10, 50, 40, 50), _line(60, 10, 60, 30), _line(41, 50, 80, 50)], []]
    rows = [actions_from_strokes(s) for s in strokes]
    T = max(len(r) for r in rows)
    actions = np.zeros((2, T, 3), np.int32)
    for b, r in enumerate(rows):
        actions[b, : len(r)] = r
    plan = Plan(strokes, actions, np.array([len(r) for r in rows]), np.zeros(2, bool))
    out = joins.join_plan(plan)
    assert len(out.strokes[0]) == 2 and out.strokes[1] == []
    replayed = strokes_from_actions(out.actions[0], int(out.lengths[0]))
    for s, r in zip(out.strokes[0], replayed):
        np.testing.assert_array_equal(s, r)
    np.testing.assert_array_equal(
        geometry.render_strokes(out.strokes[0]), geometry.render_strokes(strokes[0])
    )
    # A bound on the rows it may take leaves an image as it was.
    assert len(joins.join_plan(plan, max_rows=1).strokes[0]) == 3


def test_plan_joins_as_the_bundle_says(tmp_path):
    import jdraw
    from jdraw.model import bundle, checkpoints
    from jdraw.planner import plan as api

    paper = bundle.PAPER_BUNDLE
    assert api.planner_settings(paper) == {}
    mdl, cfg = bundle.load(paper)
    bundle.write(mdl, cfg, tmp_path / "b", planner={"join": True})
    assert api.planner_settings(tmp_path / "b") == {"join": True}
    checkpoints.export(tmp_path / "b", tmp_path / "c")  # the setting survives a copy
    assert api.planner_settings(tmp_path / "c") == {"join": True}
    img = geometry.render_strokes([_line(10, 50, 80, 50), _line(45, 20, 45, 80)])
    calls = []
    real = joins.join_plan
    try:
        joins.join_plan = lambda *a, **k: calls.append(1) or real(*a, **k)
        jdraw.plan(img, checkpoint=paper)
        assert calls == []
        jdraw.plan(img, checkpoint=tmp_path / "b")
        assert calls == [1]
        jdraw.plan(img, checkpoint=tmp_path / "b", join=False)
        assert calls == [1]
    finally:
        joins.join_plan = real


@pytest.mark.parametrize("gap", [1, 3])
def test_gap_bounds_the_distance_between_ends(gap):
    a, b = _line(10, 50, 40, 50), _line(40 + gap, 50, 80, 50)
    assert len(joins.join_strokes([a, b], gap=gap)) == 1
    assert len(joins.join_strokes([a, b], gap=gap - 1)) == 2
