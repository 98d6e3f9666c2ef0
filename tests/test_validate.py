"""Nothing false, nothing cryptic: one test per item found by trying bad input on purpose."""

import shutil

import cv2
import numpy as np
import pytest

import jdraw
from jdraw import cli, validate
from jdraw.images.prepare import prepare
from jdraw.io.gcode import to_gcode
from jdraw.model import bundle
from jdraw.plans import render
from jdraw.tiling import plan_image as tiling
from tests.doubles import trace_planner


def _no_planner(*a, **k):
    raise AssertionError("planning started before the arguments were checked")


# 1. `truncated` means exactly "ink the plan does not draw remains".


@pytest.mark.parametrize("n, max_steps", [(1, 1), (3, 5), (5, 9)])
def test_truncated_after_a_jump_onto_an_isolated_pixel(n, max_steps):
    t = np.zeros((100, 100), bool)
    for k in range(n):
        t[10 + 20 * k, 10 + 15 * k] = True
    p = jdraw.plan(t, max_steps=max_steps)
    undrawn = (t & ~render(p)[0]).any()
    assert undrawn and p.truncated[0]


def test_truncated_false_when_everything_is_drawn():
    t = np.zeros((100, 100), bool)
    t[50, 20:60] = True
    p = jdraw.plan(t, max_steps=400)
    assert not (t & ~render(p)[0]).any() and not p.truncated[0]


# 2. Long thin images are not blank.


@pytest.mark.parametrize("h, w", [(20, 4000), (20, 2000), (200, 20000), (20000, 200)])
def test_long_thin_image_has_ink(h, w):
    g = np.ones((h, w), np.float32)
    if w > h:
        g[h // 2 - 1 : h // 2 + 2, w // 10 : w - w // 10] = 0.0
    else:
        g[h // 10 : h - h // 10, w // 2 - 1 : w // 2 + 2] = 0.0
    prep = prepare(g)
    assert prep.ink.sum() >= 0.9 * (g == 0).sum()
    assert len(prep.polylines) == 1


def test_long_thin_image_plans_end_to_end():
    g = np.full((20, 4000), 255, np.uint8)
    cv2.line(g, (100, 10), (3900, 10), 0, 3)
    r = tiling.plan_image(g, planner=trace_planner, progress=False)
    xs = np.concatenate([s[:, 0] for s in r.strokes])
    assert xs.min() < 150 and xs.max() > 3850


# 3. plan_image rejects what plan rejects, and bad knobs.


_G = np.ones((40, 40))
_G[20, 5:35] = 0


@pytest.mark.parametrize(
    "image, kwargs, match",
    [
        (np.where(_G == 1, np.nan, 0.0), {}, "NaN"),
        (np.where(np.arange(40) == 3, np.inf, _G), {}, "NaN or inf"),
        (_G.astype(complex), {}, "complex"),
        (_G.astype(str), {}, "dtype"),
        (_G.astype(object), {}, "object"),
        (_G, {"batch_size": 0}, "batch_size"),
        (_G, {"min_gap": 0}, "min_gap"),
        (_G, {"min_gap": -1.0}, "min_gap"),
        (_G, {"min_gap": float("nan")}, "min_gap"),
        (_G, {"max_steps": 0}, "max_steps"),
        (_G, {"polarity": "bright"}, "polarity"),
    ],
)
def test_plan_image_rejects(image, kwargs, match):
    with pytest.raises(validate.InputError, match=match):
        tiling.plan_image(image, planner=_no_planner, progress=False, **kwargs)


def test_plan_image_rejects_a_bad_checkpoint_before_planning(monkeypatch):
    monkeypatch.setattr(tiling, "default_planner", _no_planner)
    with pytest.raises(validate.InputError, match="no such file"):
        tiling.plan_image(_G, checkpoint="/no/such/bundle", progress=False)


# 4. The command line: one line, distinct exit codes, options checked first.


@pytest.fixture
def line_png(tmp_path):
    g = np.full((60, 120), 255, np.uint8)
    cv2.line(g, (10, 30), (110, 30), 0, 3)
    path = tmp_path / "line.png"
    cv2.imwrite(str(path), g)
    return str(path)


def _one_line_error(capsys, code, rc, match):
    err = capsys.readouterr().err
    assert rc == code, err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    assert match in err, err


@pytest.mark.parametrize(
    "extra, match",
    [
        (["--checkpoint", "MISSING"], "no such file"),
        (["--checkpoint", "FILE"], "is a file"),
        (["--checkpoint", "EMPTYDIR"], "no bundle.json"),
        (["--svg", "DIR"], "is a directory"),
        (["--svg", "OUT.svg", "--width-mm", "-3"], "--width-mm"),
        (["--svg", "OUT.svg", "--width-mm", "nan"], "--width-mm"),
        (["--gcode", "OUT.gcode", "--pen-up", "{z_up.__class__}"], "unknown field"),
        (["--gcode", "OUT.gcode", "--pen-down", "M3 {"], "--pen-down"),
        (["--gcode", "OUT.gcode", "--feed", "-1"], "--feed"),
        (["--gcode", "OUT.gcode", "--travel-feed", "0"], "--travel-feed"),
        (["--max-steps", "0"], "--max-steps"),
    ],
)
def test_cli_user_errors_are_one_line_exit_2_before_planning(
    line_png, tmp_path, monkeypatch, capsys, extra, match
):
    monkeypatch.setattr(tiling, "plan_image", _no_planner)
    (tmp_path / "FILE").write_text("x")
    (tmp_path / "EMPTYDIR").mkdir()
    (tmp_path / "DIR").mkdir()
    names = {"MISSING", "FILE", "EMPTYDIR", "DIR", "OUT.svg", "OUT.gcode"}
    extra = [str(tmp_path / a) if a in names else a for a in extra]
    rc = cli.main(["draw", line_png, "--no-progress", *extra])
    _one_line_error(capsys, 2, rc, match)


def test_cli_internal_error_is_exit_3_and_debug_shows_the_traceback(line_png, monkeypatch, capsys):
    def broken(*a, **k):
        raise RuntimeError("boom")

    monkeypatch.setattr(tiling, "plan_image", broken)
    rc = cli.main(["draw", line_png, "--no-progress"])
    _one_line_error(capsys, 3, rc, "internal error: RuntimeError: boom")
    assert cli.main(["draw", line_png, "--no-progress", "--debug"]) == 3
    assert "Traceback" in capsys.readouterr().err
    assert cli.main(["draw", line_png, "--max-steps", "0", "--debug"]) == 2
    assert "Traceback" in capsys.readouterr().err


def test_exit_codes_are_documented(capsys):
    with pytest.raises(SystemExit):
        cli.main(["draw", "--help"])
    text = capsys.readouterr().out
    for code in ("0  success", "1  --trajectory", "2  user error", "3  internal error"):
        assert code in text


def test_gcode_templates_take_only_documented_fields():
    s = [np.array([[0.0, 0.0], [5.0, 5.0]])]
    with pytest.raises(ValueError, match="unknown field"):
        to_gcode(s, (10, 10), pen_up="G0 Z{z_up.__class__}")
    with pytest.raises(ValueError, match="feed"):
        to_gcode(s, (10, 10), feed=-1.0)
    code = to_gcode(s, (10, 10), pen_up="G0 Z{z_up} ; {{lift}}")
    assert "G0 Z5 ; {lift}" in code


# 5. Bundles: wrong dtype, NaN weights, a folder that is not a bundle.


@pytest.mark.parametrize("kind, match", [("float16", "dtype"), ("int32", "dtype"), ("nan", "NaN")])
def test_bad_bundle_weights(tmp_path, kind, match):
    out = tmp_path / kind
    shutil.copytree(bundle.DEFAULT_BUNDLE, out)
    with np.load(out / "params.npz") as z:
        arrays = {k: z[k] for k in z.files}
    if kind == "nan":
        arrays = {k: np.full_like(v, np.nan) for k, v in arrays.items()}
    else:
        arrays = {k: v.astype(kind) for k, v in arrays.items()}
    np.savez(out / "params.npz", **arrays)
    with pytest.raises(bundle.BundleError, match=match):
        bundle.load(out)


def test_folder_without_bundle_json(tmp_path):
    with pytest.raises(ValueError, match="no bundle.json"):
        jdraw.plan(np.zeros((100, 100)), checkpoint=tmp_path)


# 6. plan's messages.


@pytest.mark.parametrize(
    "images, kwargs, match",
    [
        (np.zeros((0, 100, 100)), {}, "empty batch"),
        (np.zeros((1, 1, 100, 100)), {}, "channels first"),
        ([[0, 1], [1]], {}, "ragged"),
        (np.zeros((100, 100)), {"max_steps": 0}, "max_steps"),
        (np.zeros((100, 100)), {"max_steps": 2.5}, "max_steps"),
        (np.zeros((100, 100), complex), {}, "complex"),
        (np.zeros((100, 100)), {"checkpoint": 42}, "checkpoint must be"),
    ],
)
def test_plan_messages(images, kwargs, match):
    with pytest.raises(validate.InputError, match=match) as e:
        jdraw.plan(images, **kwargs)
    assert "\n" not in str(e.value)
