"""Property-based tests of ``jdraw.plan`` and ``jdraw.plan_image`` (hypothesis).

Valid images of every kind (noise of any density, single pixels, borders,
checkerboards, lines) plan to a result whose strokes lie on ink and whose
``truncated`` is exactly "ink left undrawn"; invalid inputs raise a
``ValueError`` naming the problem. CI runs 285 cases (derandomized);
``HYPOTHESIS_SCALE=20`` multiplies that, and ``bench/fuzz.py`` runs >= 5,000
in batches.
"""

import os

import cv2
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import jdraw
from jdraw import validate
from jdraw.images.load import BlankImageError
from jdraw.plans import render
from jdraw.tiling import plan_image as tiling

settings.register_profile(
    "ci",
    max_examples=60,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
# Scales every test's case count: HYPOTHESIS_SCALE=20 for a long local run.
SCALE = int(os.environ.get("HYPOTHESIS_SCALE", "1"))
settings.load_profile("ci")

# One bound (each is a compile of the planner): dots, short lines and blanks finish
# within it, noise, borders and checkerboards are cut (at any point, jumps included).
MAX_STEPS = 120


@st.composite
def canvases(draw):
    """``bool [100, 100]`` images of one kind."""
    kind = draw(st.sampled_from(["noise", "pixels", "border", "checker", "lines", "blank"]))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    img = np.zeros((100, 100), bool)
    if kind == "noise":
        img = rng.random((100, 100)) < draw(st.sampled_from([0.001, 0.01, 0.1, 0.5, 0.9, 1.0]))
    elif kind == "pixels":
        pts = draw(st.lists(st.tuples(st.integers(0, 99), st.integers(0, 99)), max_size=6))
        for y, x in pts:
            img[y, x] = True
    elif kind == "border":
        w = draw(st.integers(1, 3))
        img[:w], img[-w:], img[:, :w], img[:, -w:] = True, True, True, True
    elif kind == "checker":
        k = draw(st.integers(1, 8))
        yy, xx = np.mgrid[:100, :100]
        img = ((yy // k + xx // k) % 2 == 0) & (rng.random() < 0.5 or yy < 50)
    elif kind == "lines":
        for _ in range(draw(st.integers(1, 4))):
            a, b = rng.integers(0, 100, 2), rng.integers(0, 100, 2)
            u8 = img.astype(np.uint8)
            cv2.line(u8, tuple(map(int, a)), tuple(map(int, b)), 1, 1)
            img = u8.astype(bool)
    return img


@settings(max_examples=60 * SCALE)
@given(target=canvases(), canon=st.booleans())
def test_plan_valid_images(target, canon):
    from jdraw.images import canonical

    p = jdraw.plan(target, max_steps=MAX_STEPS, canonicalise=canon)
    assert p.lengths[0] <= MAX_STEPS
    drawn = render(p)[0]
    # The ink planned: the input, or its canonical lines (within 1 px of the input).
    ink = canonical.canonicalise(target) if canon else target
    near = cv2.dilate(target.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)
    assert not (ink & ~near).any(), "canonical lines left the input's ink"
    assert not (drawn & ~ink).any(), "a stroke left the ink"
    assert bool(p.truncated[0]) == bool((ink & ~drawn).any()), "truncated is not honest"


def _bad_arrays():
    ok = np.zeros((100, 100))
    nan = ok.copy()
    nan[3, 4] = np.nan
    return st.one_of(
        st.builds(
            lambda shape: np.zeros(shape),
            st.lists(st.integers(0, 120), min_size=0, max_size=4).filter(
                lambda s: (
                    np.prod(s) <= 2_000_000
                    and tuple(s) not in ((100, 100), (100, 100, 1))
                    and not (len(s) in (3, 4) and tuple(s[1:3]) == (100, 100) and s[0] > 0)
                )
            ),
        ),
        st.sampled_from(
            [
                nan,
                np.full((2, 100, 100), np.inf),
                ok.astype(complex),
                ok.astype(str),
                ok.astype(object),
                np.zeros((0, 100, 100)),
                np.zeros((1, 1, 100, 100)),
                [[0.0] * 100] * 99 + [[0.0] * 98],
                None,
                "image.png",
            ]
        ),
    )


@settings(max_examples=150 * SCALE)
@given(bad=_bad_arrays())
def test_plan_invalid_inputs_raise_value_error(bad):
    with pytest.raises(ValueError) as e:
        jdraw.plan(bad, max_steps=MAX_STEPS)
    msg = str(e.value)
    assert msg and "\n" not in msg


@st.composite
def photos(draw):
    """Small images of any dtype and a few kinds, ``[H, W]`` or RGB."""
    h, w = draw(st.integers(2, 90)), draw(st.integers(2, 90))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    kind = draw(st.sampled_from(["lines", "noise", "blank", "checker"]))
    g = np.full((h, w), 255, np.uint8)
    if kind == "lines":
        for _ in range(draw(st.integers(1, 3))):
            a, b = rng.integers(0, (w, h), 2), rng.integers(0, (w, h), 2)
            cv2.line(g, tuple(map(int, a)), tuple(map(int, b)), 0, draw(st.integers(1, 4)))
    elif kind == "noise":
        g = (rng.random((h, w)) * 255).astype(np.uint8)
    elif kind == "checker":
        yy, xx = np.mgrid[:h, :w]
        g = np.where((yy // 4 + xx // 4) % 2, 255, 0).astype(np.uint8)
    dtype = draw(st.sampled_from(["uint8", "float", "bool", "rgb"]))
    if dtype == "float":
        return g / 255.0
    if dtype == "bool":
        return g < 128
    if dtype == "rgb":
        return np.repeat(g[..., None], 3, axis=2)
    return g


@settings(max_examples=15 * SCALE)
@given(image=photos())
def test_plan_image_valid(image):
    try:
        r = tiling.plan_image(image, max_steps=MAX_STEPS, progress=False)
    except BlankImageError:
        return
    h, w = image.shape[:2]
    reach = int(np.ceil(0.75 / r.scale + 2))
    near_ink = cv2.dilate(r.prepared.ink.astype(np.uint8), np.ones((2 * reach + 1,) * 2, np.uint8))
    for s in r.strokes:
        x, y = np.floor(s[:, 0] + 0.5).astype(int), np.floor(s[:, 1] + 0.5).astype(int)
        assert ((x >= 0) & (x < w) & (y >= 0) & (y < h)).all()
        assert near_ink[y, x].all(), "a stroke left the ink"
    assert (r.truncated > 0) == (r.completed_pixels > 0), "truncated is not honest"


@given(
    kwargs=st.sampled_from(
        [
            {"image": np.full((30, 30), np.nan)},
            {"image": np.zeros((30, 30), complex)},
            {"image": np.zeros((30, 30)).astype(str)},
            {"image": np.zeros((30, 30, 2))},
            {"image": np.zeros((1, 30))},
            {"batch_size": 0},
            {"batch_size": 2.0},
            {"min_gap": 0.0},
            {"min_gap": -3},
            {"min_gap": float("inf")},
            {"max_steps": -1},
            {"polarity": "grey"},
            {"checkpoint": 3.5},
        ]
    )
)
def test_plan_image_invalid_inputs_raise_value_error(kwargs):
    kwargs = {"image": np.eye(30), **kwargs}
    with pytest.raises(validate.InputError):
        tiling.plan_image(progress=False, **kwargs)
