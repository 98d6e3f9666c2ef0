"""Outputs: SVG, G-code (checked with the pygcode interpreter), JSON, ROS JointTrajectory."""

import json
import xml.etree.ElementTree as ET

import cv2
import numpy as np
import pytest

from jdraw.io.gcode import PRESETS, PlotterPreset, to_gcode
from jdraw.io.outputs import write_outputs
from jdraw.io.plan_json import to_json
from jdraw.io.svg import to_svg
from jdraw.robot.ros import joint_trajectory, joint_trajectory_from_report
from jdraw.tiling.plan_image import plan_image
from tests.doubles import trace_planner

STROKES = [
    np.array([[10.0, 20.0], [30.5, 20.0], [30.5, 45.25]]),
    np.array([[60.0, 5.0]]),  # a dot
    np.array([[70.0, 70.0], [90.0, 10.0], [95.0, 12.0]]),
]
SHAPE = (80, 120)  # (H, W)
SVG = "{http://www.w3.org/2000/svg}"


def test_svg_polylines_in_input_pixels():
    root = ET.fromstring(to_svg(STROKES, SHAPE).encode())
    assert root.tag == SVG + "svg"
    assert root.get("viewBox") == "0 0 120 80"
    assert (root.get("width"), root.get("height")) == ("120", "80")
    polys = root.findall(f".//{SVG}polyline")
    assert len(polys) == len(STROKES)
    for poly, s in zip(polys, STROKES, strict=True):
        pts = np.array([[float(v) for v in p.split(",")] for p in poly.get("points").split()])
        want = s if len(s) > 1 else np.concatenate([s, s])
        np.testing.assert_allclose(pts, want, atol=0.005)


def test_svg_physical_size_keeps_aspect_and_loads_in_svgpathtools(tmp_path):
    text = to_svg(STROKES, SHAPE, width_mm=150)
    root = ET.fromstring(text.encode())
    assert (root.get("width"), root.get("height")) == ("150mm", "100mm")
    assert root.get("viewBox") == "0 0 120 80"
    path = tmp_path / "out.svg"
    path.write_text(text)
    from svgpathtools import svg2paths

    paths, _ = svg2paths(str(path))
    assert len(paths) == len(STROKES)
    assert paths[0].start == complex(10, 20) and paths[0].end == complex(30.5, 45.25)


def _pen_down_paths(gcode: str, preset: PlotterPreset):
    """Interprets G-code with pygcode and returns the polylines drawn with the pen down."""
    from pygcode import Line, Machine

    machine = Machine()
    drawn, current = [], None
    pen_down = z_set = False  # the machine's Z is unknown until the first Z move
    units = None
    for text in gcode.splitlines():
        line = Line(text)  # raises on anything that is not G-code
        words = {str(g.word_key) if g.word_key else "" for g in line.block.gcodes}
        if "G21" in words:
            units = "mm"
        machine.process_block(line.block)
        pos = machine.pos.values
        if preset.name == "zaxis":
            z_set = z_set or any(g.params and "Z" in g.params for g in line.block.gcodes)
            down = z_set and pos["Z"] <= preset.z_down + 1e-9
        elif "M05" in words:
            down = False
        elif "M03" in words:
            (speed,) = [w.value for w in line.block.words if w.letter == "S"]
            down = float(speed) == preset.servo_down
        else:
            down = pen_down
        xy = (round(pos["X"], 6), round(pos["Y"], 6))
        if down and not pen_down:
            current = [xy]
            drawn.append(current)
        elif down and current[-1] != xy:
            current.append(xy)
        pen_down = down
    assert units == "mm"
    return drawn


@pytest.mark.parametrize("name", sorted(PRESETS))
def test_gcode_parses_and_draws_the_strokes(name):
    preset = PRESETS[name]
    code = to_gcode(STROKES, SHAPE, preset=name, width_mm=60)
    assert "G21" in code and "G90" in code
    drawn = _pen_down_paths(code, preset)
    assert len(drawn) == len(STROKES)
    k = 60 / SHAPE[1]  # mm per pixel
    for path, s in zip(drawn, STROKES, strict=True):
        want = np.stack([(s[:, 0] + 0.5) * k, (SHAPE[0] - 0.5 - s[:, 1]) * k], 1)
        np.testing.assert_allclose(np.array(path), want, atol=1e-3)


def test_gcode_feeds_and_templates_override():
    code = to_gcode(
        STROKES, SHAPE, preset="servo", feed=2500, travel_feed=6000, pen_down="M3 S40\\nG4 P0.3"
    )
    assert "F2500" in code and "G1 X" in code and "F6000" in code
    assert code.count("M3 S40") == len(STROKES) and code.count("G4 P0.3") == len(STROKES)
    with pytest.raises(ValueError, match="unknown field"):
        to_gcode(STROKES, SHAPE, pen_up="G0 Z{nope}")


def test_json_strokes_and_pen_up_moves():
    d = json.loads(json.dumps(to_json(STROKES, SHAPE)))
    assert (d["width"], d["height"], d["units"]) == (120, 80, "px")
    assert len(d["strokes"]) == 3 and d["strokes"][1] == [[60.0, 5.0]]
    pens = [m["pen"] for m in d["moves"]]
    assert pens == ["up", "down"] * 3
    up = d["moves"][2]
    assert up["from"] == [30.5, 45.25] and up["to"] == [60.0, 5.0]
    assert up["length"] == pytest.approx(np.hypot(29.5, 40.25), abs=1e-3)
    assert d["pen_down_length"] == pytest.approx(
        20.5 + 25.25 + np.hypot(20, 60) + np.hypot(5, 2), abs=1e-2
    )


def test_joint_trajectory_shape_and_time_split():
    names = ["shoulder", "elbow"]
    t = np.array([0.0, 0.5, 1.25, 1.9999999999, 3.0])
    q = np.arange(10.0).reshape(5, 2)
    msg = joint_trajectory(names, t, q, velocities=q * 0.1)
    assert msg["joint_names"] == names and len(msg["points"]) == 5
    p = msg["points"][2]
    assert p["positions"] == [4.0, 5.0] and p["velocities"] == pytest.approx([0.4, 0.5])
    assert p["time_from_start"] == {"sec": 1, "nanosec": 250_000_000}
    assert msg["points"][3]["time_from_start"] == {"sec": 2, "nanosec": 0}
    json.dumps(msg)  # plain JSON types only
    assert joint_trajectory(names, t, q)["points"][0]["velocities"] == []
    with pytest.raises(ValueError):
        joint_trajectory(names, t, q[:, :1])
    with pytest.raises(ValueError):
        joint_trajectory(names, t[::-1], q)


def test_joint_trajectory_from_a_robot_report():
    from types import SimpleNamespace

    t = np.arange(6) * 0.01
    q = np.stack([np.zeros((6, 7)), np.outer(t, np.arange(7.0))])  # [B=2, T, J]
    valid = np.array([[True] * 6, [False, True, True, True, True, False]])
    msg = joint_trajectory_from_report(SimpleNamespace(t=t, q_ref=q, valid=valid), index=1)
    assert msg["joint_names"] == [f"joint{i}" for i in range(1, 8)] and len(msg["points"]) == 4
    assert msg["points"][0]["time_from_start"] == {"sec": 0, "nanosec": 0}
    assert msg["points"][1]["time_from_start"] == {"sec": 0, "nanosec": 10_000_000}
    np.testing.assert_allclose(msg["points"][2]["velocities"], np.arange(7.0))


def test_write_outputs_writes_what_is_asked(tmp_path):
    """What ``jdraw draw --svg --json`` writes, from a notebook: one call."""
    img = np.full((60, 90), 255, np.uint8)
    cv2.line(img, (10, 30), (80, 30), 0, 5)
    result = plan_image(img, planner=trace_planner, progress=False)
    written = write_outputs(result, svg=tmp_path / "a.svg", json=tmp_path / "a.json", width_mm=90)
    assert set(written.paths) == {"svg", "json"}
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.json", "a.svg"]
    assert (tmp_path / "a.svg").read_text() == to_svg(result.strokes, result.shape, width_mm=90)
    data = json.loads((tmp_path / "a.json").read_text())
    assert data["stats"] == written.stats.as_dict() and written.stats.units == "mm"
    assert data["strokes"] == to_json(result.strokes, result.shape)["strokes"]
