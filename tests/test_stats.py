"""Plot statistics against a drawing measured by hand."""

import json
import re

import cv2
import numpy as np
import pytest

from jdraw import cli
from jdraw.io import stats
from jdraw.tiling import plan_image as tiling
from tests.doubles import trace_planner
from tests.synthetic import photo_like, text_centrelines

# A 100 x 50 px image drawn 200 mm wide (2 mm a pixel): an L (30 + 40 px), a bar
# (30 px) and a dot; pen-up travel (30,40)->(60,40) and (60,10)->(90,10), 30 px each.
SHAPE = (50, 100)
STROKES = [
    np.array([[0.0, 0.0], [30.0, 0.0], [30.0, 40.0]]),
    np.array([[60.0, 40.0], [60.0, 10.0]]),
    np.array([[90.0, 10.0]]),
]


def test_zaxis_in_mm():
    s = stats.plot_stats(STROKES, SHAPE, width_mm=200)
    assert (s.strokes, s.units) == (3, "mm")
    assert s.pen_down == pytest.approx(200.0) and s.pen_up == pytest.approx(120.0)
    # 200 mm at 1500 mm/min; 120 mm of G0 at 3000 mm/min; per stroke a 5 mm Z drop at
    # 600 mm/min (0.5 s) and a 5 mm G0 lift (0.1 s).
    assert s.draw_s == pytest.approx(8.0)
    assert s.travel_s == pytest.approx(2.4)
    assert s.lift_s == pytest.approx(1.8)
    assert s.time_s == pytest.approx(12.2)
    # The height binds when the box is narrower than the aspect: 50 px -> 50 mm.
    assert stats.plot_stats(STROKES, SHAPE, width_mm=500, height_mm=50).pen_down == 100


def test_servo_with_feeds_and_pixels():
    s = stats.plot_stats(STROKES, SHAPE, width_mm=200, preset="servo", feed=3000, travel_feed=6000)
    # 4 s drawing, 1.2 s travel, a 0.15 s dwell after each of 3 drops and 3 lifts.
    assert (s.draw_s, s.travel_s, s.lift_s) == pytest.approx((4.0, 1.2, 0.9))
    # No size: lengths in input pixels, time for G-code's default 100 mm width (1 mm/px).
    s = stats.plot_stats(STROKES, SHAPE)
    assert (s.units, s.pen_down, s.pen_up, s.mm_per_unit) == ("px", 100.0, 60.0, 1.0)
    assert s.time_s == pytest.approx(4.0 + 1.2 + 1.8)
    assert s.summary() == "3 strokes, pen-down 100.0 px, pen-up 60.0 px, plotting ~7 s"


def test_cli_summary_and_json(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(tiling, "default_planner", trace_planner)
    lines, shape = text_centrelines("hi", 3.0)
    path = tmp_path / "word.png"
    cv2.imwrite(str(path), photo_like(lines, shape, width=6, noise=0.02))
    out = tmp_path / "out.json"
    argv = ["draw", str(path), "--no-progress", "--json", str(out), "--width-mm", "80"]
    assert cli.main(argv + ["--feed", "1000"]) == 0
    data = json.loads(out.read_text())
    want = stats.plot_stats(
        [np.array(s) for s in data["strokes"]], shape, width_mm=80, feed=1000
    ).as_dict()
    assert data["stats"].keys() == want.keys() and data["stats"]["units"] == "mm"
    for key, v in want.items():  # the JSON's points are rounded to 0.001 px
        assert data["stats"][key] == (v if isinstance(v, str) else pytest.approx(v, abs=0.01))
    k = 80 / shape[1]
    assert want["pen_down"] == pytest.approx(data["pen_down_length"] * k, abs=0.01)
    assert want["pen_up"] == pytest.approx(data["pen_up_length"] * k, abs=0.01)
    text = capsys.readouterr().out
    m = re.search(r"(\d+) strokes, pen-down ([\d.]+) mm, pen-up ([\d.]+) mm, plotting ~", text)
    assert m and int(m[1]) == want["strokes"]
    assert (float(m[2]), float(m[3])) == pytest.approx((want["pen_down"], want["pen_up"]), abs=0.1)
