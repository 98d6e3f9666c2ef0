"""The ``jdraw`` command line."""

import json
import subprocess
import sys
import xml.etree.ElementTree as ET

import cv2
import numpy as np
import pytest

import jdraw
from jdraw import cli, formats, tiling
from jdraw import image as im


@pytest.fixture
def word_photo(tmp_path):
    lines, shape = im.text_centrelines("hi", 3.0)
    path = tmp_path / "word.jpg"
    cv2.imwrite(str(path), im.photo_like(lines, shape, width=6, gradient=0.5, noise=0.05))
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
    for preset in formats.PRESETS:
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
    monkeypatch.setattr(jdraw, "plan", tiling.trace_planner)
    path, lines, shape = word_photo
    out = {ext: tmp_path / f"out.{ext}" for ext in ("svg", "gcode", "json", "png")}
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
    precision, recall = im.centreline_scores(strokes, lines, 4.0)
    assert precision >= 0.95 and recall >= 0.95
    assert out["gcode"].read_text().count("M3 S90") == len(strokes)
    png = cv2.imread(str(out["png"]))
    assert png is not None and png.shape[1] > shape[1]


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
    precision, recall = im.centreline_scores(strokes, lines, 4.0)
    assert precision >= 0.95 and recall >= 0.95


def test_module_entry_point_runs():
    out = subprocess.run(
        [sys.executable, "-m", "jdraw.cli", "--help"], capture_output=True, text=True, timeout=120
    )
    assert out.returncode == 0 and "draw" in out.stdout
