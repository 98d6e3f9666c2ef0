"""The ``jdraw`` command line."""

import json
import subprocess
import sys
import xml.etree.ElementTree as ET

import cv2
import numpy as np
import pytest
from PIL import Image

from jdraw import cli
from jdraw.io.gcode import PRESETS
from jdraw.robot.ros import joint_trajectory
from jdraw.tiling import plan_image as tiling
from tests.doubles import trace_planner
from tests.synthetic import centreline_scores, photo_like, text_centrelines


@pytest.fixture
def word_photo(tmp_path):
    lines, shape = text_centrelines("hi", 3.0)
    path = tmp_path / "word.jpg"
    cv2.imwrite(str(path), photo_like(lines, shape, width=6, gradient=0.5, noise=0.05))
    return path, lines, shape


def test_help_explains_every_option(capsys):
    with pytest.raises(SystemExit) as e:
        cli.main(["draw", "--help"])
    assert e.value.code == 0
    text = capsys.readouterr().out
    draw = next(a for a in cli._parser()._actions if a.dest == "command").choices["draw"]
    for action in draw._actions:
        for flag in action.option_strings:
            assert flag in text
        assert action.help, action.dest
    for preset in PRESETS:
        assert preset in text


def test_errors_are_clear(tmp_path, capsys):
    assert cli.main(["draw", str(tmp_path / "nope.png")]) == 2
    assert "no such file" in capsys.readouterr().err
    (tmp_path / "a.txt").write_text("not an image")
    assert cli.main(["draw", str(tmp_path / "a.txt")]) == 2
    assert "unsupported image format" in capsys.readouterr().err
    (tmp_path / "bad.png").write_bytes(b"\x89PNG\r\n\x1a\n" + b"\0" * 40)
    assert cli.main(["draw", str(tmp_path / "bad.png")]) == 2
    assert "cannot read" in capsys.readouterr().err
    cv2.imwrite(str(tmp_path / "blank.png"), np.full((60, 80), 250, np.uint8))
    assert cli.main(["draw", str(tmp_path / "blank.png")]) == 2
    assert "blank" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        cli.main(["draw", str(tmp_path / "blank.png"), "--preset", "laser"])


def test_draw_writes_every_format(word_photo, tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(tiling, "default_planner", trace_planner)
    path, lines, shape = word_photo
    out = {ext: tmp_path / f"out.{ext}" for ext in ("svg", "gcode", "json", "png", "gif")}
    argv = ["draw", str(path), "--no-progress", "--preset", "servo", "--width-mm", "80"]
    for ext, p in out.items():
        argv += [f"--{ext}", str(p)]
    assert cli.main(argv) == 0
    assert "strokes" in capsys.readouterr().out
    root = ET.parse(out["svg"]).getroot()
    assert root.get("viewBox") == f"0 0 {shape[1]} {shape[0]}"
    polys = root.findall(".//{http://www.w3.org/2000/svg}polyline")
    data = json.loads(out["json"].read_text())
    assert len(polys) == len(data["strokes"]) > 0
    strokes = [np.array(s) for s in data["strokes"]]
    precision, recall = centreline_scores(strokes, lines, 4.0)
    assert precision >= 0.95 and recall >= 0.95
    assert out["gcode"].read_text().count("M3 S90") == len(strokes)
    png = cv2.imread(str(out["png"]))
    assert png is not None and png.shape[1] > shape[1]
    with Image.open(out["gif"]) as gif:
        assert gif.n_frames > 10 and max(gif.size) == 640


def test_draw_with_the_real_planner(word_photo, tmp_path):
    """End to end with :func:`jdraw.plan` (the bundled or seeded model)."""
    path, lines, shape = word_photo
    svg = tmp_path / "out.svg"
    assert cli.main(["draw", str(path), "--svg", str(svg), "--no-progress"]) == 0
    polys = ET.parse(svg).getroot().findall(".//{http://www.w3.org/2000/svg}polyline")
    strokes = [
        np.array([[float(v) for v in p.split(",")] for p in poly.get("points").split()])
        for poly in polys
    ]
    # Whatever the model's stroke order, the plan covers the ink on its centreline.
    precision, recall = centreline_scores(strokes, lines, 4.0)
    assert precision >= 0.95 and recall >= 0.95


def test_module_entry_point_runs():
    out = subprocess.run(
        [sys.executable, "-m", "jdraw.cli", "--help"], capture_output=True, text=True, timeout=120
    )
    assert out.returncode == 0 and "draw" in out.stdout


def test_trajectory_for_the_arm(tmp_path, monkeypatch, capsys):
    """``--trajectory``: the simulated arm draws the strokes; ROS-shaped joint path out."""
    monkeypatch.setattr(tiling, "default_planner", trace_planner)
    path = tmp_path / "corner.png"  # an L
    corner = np.array([[20.0, 20], [20, 100], [80, 100]])
    cv2.imwrite(str(path), photo_like([corner], (120, 100)))
    out = tmp_path / "arm.json"
    argv = ["draw", str(path), "--no-progress", "--trajectory", str(out)]
    assert cli.main(argv) == 0
    summary = capsys.readouterr().out
    assert "arm: reachable" in summary
    iou = float(summary.split("IoU vs plan ")[1].split(",")[0])
    assert iou >= 0.9  # the nib's ink on the sheet matches the plan
    traj = json.loads(out.read_text())
    assert len(traj["joint_names"]) == 7 and len(traj["points"]) > 10
    stamps = [p["time_from_start"] for p in traj["points"]]
    t = [st["sec"] + 1e-9 * st["nanosec"] for st in stamps]
    assert np.all(np.diff(t) > 0)
    assert all(len(p["positions"]) == len(p["velocities"]) == 7 for p in traj["points"])


def test_trajectory_out_of_reach_is_an_error(word_photo, tmp_path, monkeypatch, capsys):
    from types import SimpleNamespace

    from jdraw import robot

    monkeypatch.setattr(tiling, "default_planner", trace_planner)
    seen = {}

    def unreachable(strokes, shape, options):
        seen["sheet"] = options.sheet_size_mm
        report = SimpleNamespace(
            reachable=np.array([False]), iou=np.array([0.2]), drawing_time_s=np.array([9.0])
        )
        return report, joint_trajectory(["j1"], [0.0, 0.1], [[0.0], [0.1]])

    monkeypatch.setattr(robot, "image_trajectory", unreachable)
    path, _, _ = word_photo
    argv = ["draw", str(path), "--no-progress", "--trajectory", str(tmp_path / "a.json")]
    assert cli.main([*argv, "--sheet-mm", "400"]) == 1
    assert seen["sheet"] == (400.0, 400.0)
    assert "NOT reachable" in capsys.readouterr().out
    assert cli.main([*argv, "--sheet-mm", "0"]) == 2


def test_sheet_fit_keeps_aspect_and_centres():
    from jdraw import robot

    shape = (201, 401)  # H, W
    strokes = [np.array([[0.0, 0.0], [400.0, 200.0]]), np.array([[200.0, 100.0]])]
    a, b = robot.to_sheet(strokes, shape, fill=0.9)
    np.testing.assert_allclose(a, [[4.95, 27.225], [94.05, 71.775]], atol=1e-9)
    np.testing.assert_allclose(b, [[49.5, 49.5]], atol=1e-9)
    with pytest.raises(ValueError):
        robot.to_sheet(strokes, shape, fill=0.0)


def test_help_states_defaults_and_gif_input(tmp_path, monkeypatch, capsys, word_photo):
    from jdraw.planner import loop as planner

    with pytest.raises(SystemExit):
        cli.main(["draw", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert f"(default: {planner.Limits.max_steps})" in text
    assert "GIF" in text and "100x100 tiles" in text and '"tiles"' in text
    monkeypatch.setattr(tiling, "default_planner", trace_planner)
    path, lines, shape = word_photo
    gif = tmp_path / "word.gif"
    Image.open(path).save(gif)
    assert cli.main(["draw", str(gif), "--no-progress"]) == 0
    assert "strokes" in capsys.readouterr().out


def test_no_split_reaches_the_planner(word_photo, tmp_path, monkeypatch, capsys):
    seen = []

    def recording(images, **kwargs):
        seen.append(kwargs.get("split", "unset"))
        return trace_planner(images, **{k: v for k, v in kwargs.items() if k != "split"})

    monkeypatch.setattr(tiling, "default_planner", recording)
    path, _, _ = word_photo
    svg = str(tmp_path / "o.svg")
    assert cli.main(["draw", str(path), "--no-progress", "--svg", svg, "--no-split"]) == 0
    assert seen and set(seen) == {False}
    seen.clear()
    assert cli.main(["draw", str(path), "--no-progress", "--svg", svg]) == 0
    assert seen and set(seen) == {"unset"}  # the checkpoint's own setting
    with pytest.raises(ValueError, match="split"):
        tiling.plan_image(np.zeros((50, 50), np.uint8), planner=trace_planner, split=False)


def test_quick_exit_flushes_runs_atexit_and_keeps_the_status(tmp_path):
    # The jdraw command leaves with os._exit (cli.run): buffered output and atexit
    # handlers must not be lost, and the status must come through.
    flag = tmp_path / "atexit_ran"
    code = (
        "import atexit, sys\n"
        "from jdraw import cli\n"
        f"atexit.register(lambda: open({str(flag)!r}, 'w').write('yes'))\n"
        "sys.stdout.write('x' * 100000)\n"
        "sys.stderr.write('err')\n"
        "cli.quick_exit(3)\n"
        "print('not reached')\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 3
    assert out.stdout == "x" * 100000 and out.stderr == "err"
    assert flag.read_text() == "yes"
