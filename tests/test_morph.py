"""jdraw.images.morph gives scikit-image's results without importing scipy.ndimage."""

import pathlib
import subprocess
import sys

import cv2
import numpy as np
import pytest
from skimage.filters import threshold_otsu
from skimage.morphology import remove_small_holes, skeletonize

from jdraw.images import morph
from jdraw.images.ink import background
from jdraw.images.load import load_image, to_gray

ROOT = pathlib.Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples" / "images").glob("*"))


def _drawing(rng) -> np.ndarray:
    h, w = (int(v) for v in rng.integers(8, 120, 2))
    img = np.zeros((h, w), np.uint8)
    for _ in range(int(rng.integers(1, 7))):
        p = tuple(int(v) for v in rng.integers(0, (w, h)))
        q = tuple(int(v) for v in rng.integers(0, (w, h)))
        cv2.line(img, p, q, 1, int(rng.integers(1, 12)))
    img |= (rng.random((h, w)) < rng.random() * 0.2).astype(np.uint8)  # specks and pinholes
    return img.astype(bool)


def test_thinning_and_hole_filling_match_scikit_image(rng):
    for _ in range(150):
        ink = _drawing(rng)
        np.testing.assert_array_equal(morph.skeletonize(ink), skeletonize(ink))
        size = int(rng.integers(0, 60))
        np.testing.assert_array_equal(
            morph.fill_small_holes(ink, size), remove_small_holes(ink, max_size=size)
        )
    assert morph.fill_small_holes(np.ones((4, 4), bool), 9).all()


def test_otsu_matches_scikit_image(rng):
    for k in range(150):
        shape = tuple(int(v) for v in rng.integers(2, 90, 2))
        x = (rng.random(shape) ** rng.uniform(0.3, 3)).astype(np.float32) * rng.uniform(0.1, 5)
        if k % 3 == 0:  # few distinct values: ties between bins
            x = np.round(x * 20) / 20
        assert morph.otsu(x) == threshold_otsu(x)
    assert morph.otsu(np.full((3, 3), 0.25, np.float32)) == 0.25


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_real_images_match_scikit_image(path):
    gray = to_gray(load_image(path))
    g = cv2.GaussianBlur(np.asarray(gray, np.float32), (0, 0), 1.0)
    contrast = 1.0 - g / np.maximum(background(g, "dark"), 0.02)  # as ink.binarize sees it
    assert morph.otsu(contrast) == threshold_otsu(contrast)
    ink = contrast > threshold_otsu(contrast)
    np.testing.assert_array_equal(morph.skeletonize(ink), skeletonize(ink))


def test_fallback_is_scikit_images_own(monkeypatch, rng):
    monkeypatch.setattr(morph, "_zhang_kernel", lambda: None)
    ink = _drawing(rng)
    np.testing.assert_array_equal(morph.skeletonize(ink), skeletonize(ink))
    with pytest.raises(ValueError, match="2-D"):
        morph.skeletonize(np.zeros((2, 2, 2), bool))


def test_planning_imports_neither_scipy_ndimage_nor_skimage():
    code = (
        "import sys, jdraw.tiling.plan_image, jdraw.images.prepare as p, numpy as np\n"
        "img = np.full((60, 60), 255, np.uint8); img[10:50, 28:33] = 0\n"
        "p.prepare(img)\n"
        "print(sorted(m for m in sys.modules if m.startswith(('scipy.ndimage', 'skimage.'))))\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=120, cwd=ROOT
    )
    assert out.returncode == 0, out.stderr[-2000:]
    # The thinning kernel is loaded on its own; no scikit-image package module comes with it.
    assert out.stdout.strip() == "['skimage.morphology._skeletonize_various_cy']"


FIT_TOL = 1e-9  # relative: the normal equations against lstsq on a well-posed cubic fit


def test_ground_fit_on_the_grid_is_least_squares_over_the_kept_pixels(rng):
    """The grid's sums of powers give the same fit as the explicit terms of every kept pixel."""
    from jdraw.images.ink import _grid_fit, _poly_powers

    sh, sw = 24, 37
    powers = _poly_powers(3, sw, sh)
    xp = np.linspace(-1, 1, sw)[:, None] ** np.arange(7)
    yp = np.linspace(-1, 1, sh)[:, None] ** np.arange(7)
    v = rng.random((sh, sw))
    keep = rng.random((sh, sw)) > 0.3
    terms = np.stack([np.outer(yp[:, j], xp[:, i]) for i, j in powers], -1)
    want = np.linalg.lstsq(terms[keep], v[keep], rcond=None)[0]
    np.testing.assert_allclose(_grid_fit(v, keep, xp, yp, powers), want, rtol=FIT_TOL, atol=FIT_TOL)
    few = np.zeros((sh, sw), bool)
    few[0, :5] = True  # five points, ten terms: lstsq's minimum-norm answer
    want = np.linalg.lstsq(terms[few], v[few], rcond=None)[0]
    np.testing.assert_allclose(_grid_fit(v, few, xp, yp, powers), want, rtol=FIT_TOL, atol=FIT_TOL)


def test_ground_fit_is_least_squares_and_takes_tiny_images(rng):
    from jdraw.images.ink import _fit

    t = rng.uniform(-1, 1, (500, 10))
    v = t @ rng.normal(size=10) + 0.01 * rng.normal(size=500)
    want = np.linalg.lstsq(t, v, rcond=None)[0]
    np.testing.assert_allclose(_fit(t, v), want, rtol=FIT_TOL, atol=FIT_TOL)
    # A 2 x 2 image: four points, ten terms (the normal equations are singular).
    for shape in [(2, 2), (2, 3), (1, 6), (40, 2)]:
        g = rng.random(shape).astype(np.float32)
        assert np.isfinite(background(g, "dark")).all(), shape
