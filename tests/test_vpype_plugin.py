"""``vpype jdraw IMAGE``: the plan as a vpype layer (skipped when vpype is not installed)."""

import pathlib
import xml.etree.ElementTree as ET

import cv2
import numpy as np
import pytest

vp = pytest.importorskip("vpype")
vpype_cli = pytest.importorskip("vpype_cli")

import jdraw  # noqa: E402
from jdraw.io import vpype_plugin  # noqa: E402
from jdraw.tiling import plan_image as tiling  # noqa: E402
from tests.doubles import trace_planner  # noqa: E402
from tests.synthetic import photo_like, text_centrelines  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]
MM = 96.0 / 25.4  # CSS pixels (vpype's unit) per mm


@pytest.fixture(autouse=True)
def registered():
    # Installed, the entry point registers the command; a checkout on PYTHONPATH may
    # run against another install's metadata, so register it here as the entry point would.
    vpype_cli.cli.add_command(vpype_plugin.jdraw)


@pytest.fixture
def word(tmp_path):
    lines, shape = text_centrelines("hi", 3.0)
    path = tmp_path / "word.jpg"
    cv2.imwrite(str(path), photo_like(lines, shape, width=6, gradient=0.5, noise=0.05))
    return path


def layer_lines(doc, layer=1):
    return [np.stack([ln.real, ln.imag], 1) for ln in doc.layers[layer]]


def assert_same_lines(got, want, scale=1.0):
    assert len(got) == len(want)
    for g, w in zip(got, want, strict=True):
        np.testing.assert_allclose(g, np.asarray(w) * scale, atol=1e-9)


def test_entry_point_declared():
    tomllib = pytest.importorskip("tomllib")
    meta = tomllib.loads((ROOT / "pyproject.toml").read_text())
    eps = meta["project"]["entry-points"]["vpype.plugins"]
    assert eps["jdraw"] == "jdraw.io.vpype_plugin:jdraw"
    assert any(d.startswith("vpype") for d in meta["project"]["optional-dependencies"]["vpype"])


def test_layer_is_the_plan_in_order_with_sizes(word, monkeypatch):
    monkeypatch.setattr(tiling, "default_planner", trace_planner)
    want = tiling.plan_image(str(word), progress=False)
    h, w = want.shape
    assert len(want.strokes) > 1

    doc = vpype_cli.execute(f"jdraw {word}")
    assert list(doc.layers) == [1]
    assert_same_lines(layer_lines(doc), want.strokes)  # 1 input px = 1 CSS px

    assert doc.page_size == (w, h)

    doc = vpype_cli.execute(f"jdraw --width 80mm -l 3 {word}")
    assert list(doc.layers) == [3]
    assert doc.page_size == pytest.approx((80 * MM, 80 * MM * h / w))
    assert_same_lines(layer_lines(doc, 3), want.strokes, 80 * MM / w)

    # A box: the drawing fits inside both sides (here the height binds).
    doc = vpype_cli.execute(f"jdraw --size 10x1in {word}")
    k = min(10 * 96 / w, 96 / h)
    assert k == pytest.approx(96 / h)
    assert_same_lines(layer_lines(doc), want.strokes, k)

    doc = vpype_cli.execute(f"jdraw -H 2cm -w 1m {word}")
    assert_same_lines(layer_lines(doc), want.strokes, 20 * MM / h)


def test_write_svg_and_gwrite(word, tmp_path, monkeypatch):
    monkeypatch.setattr(tiling, "default_planner", trace_planner)
    result = tiling.plan_image(str(word), progress=False)
    want, (h, w) = result.strokes, result.shape
    svg, gcode = tmp_path / "out.svg", tmp_path / "out.gcode"
    vpype_cli.execute(f"jdraw --width 50mm {word} write {svg}")
    tags = [e.tag.split("}")[-1] for e in ET.parse(svg).iter()]
    paths = [t for t in tags if t in ("path", "polyline", "line")]
    assert len(paths) == len(want)
    pytest.importorskip("vpype_gcode")
    vpype_cli.execute(f"jdraw --width 50mm {word} gwrite --profile gcodemm {gcode}")
    rapids = [ln.split() for ln in gcode.read_text().splitlines() if ln.startswith("G00")]
    assert len(rapids) == len(want)  # one pen-up travel per stroke
    # In order, in mm, Y flipped by the profile: the page is the image's frame.
    k = 50 / w
    got = np.array([[float(x[1:]), float(y[1:])] for _, x, y in rapids])
    starts = np.array([s[0] for s in want]) * k
    np.testing.assert_allclose(got, np.c_[starts[:, 0], h * k - starts[:, 1]], atol=1e-3)


def test_real_planner_matches_plan_image(word):
    want = jdraw.plan_image(str(word), progress=False).strokes
    doc = vpype_cli.execute(f"jdraw {word}")
    assert_same_lines(layer_lines(doc), want)


def test_dots_and_errors(tmp_path):
    lc = vpype_plugin.strokes_to_lines([np.array([[2.0, 3.0]]), np.zeros((0, 2))], 2.0)
    assert len(lc) == 1 and list(lc[0]) == [4 + 6j, 4 + 6j]
    cv2.imwrite(str(tmp_path / "blank.png"), np.full((40, 40), 250, np.uint8))
    with pytest.raises(Exception, match="blank"):
        vpype_cli.execute(f"jdraw {tmp_path / 'blank.png'}")
