"""Real images in: binarisation, polarity, skeleton and canvas fit, on photo-like inputs."""

import cv2
import numpy as np
import pytest
from skimage import morphology

from jdraw.images.canvas import CHAR_EXTENT, to_canvas
from jdraw.images.load import BlankImageError, ImageError, load_image, to_gray
from jdraw.images.prepare import prepare
from jdraw.images.skeleton import simplify, skeleton_polylines
from tests.synthetic import centreline_scores, photo_like, text_centrelines

TOL_PX = 4.0  # the acceptance distance to the centreline, input pixels
MIN_SCORE = 0.95


@pytest.mark.parametrize("light", [False, True])
@pytest.mark.parametrize(
    "text,font_scale,width",
    [("hello", 2.0, 4), ("minimum", 6.0, 13), ("quick fox", 1.6, 3)],
)
def test_prepare_centrelines_on_photos(text, font_scale, width, light):
    lines, shape = text_centrelines(text, font_scale)
    img = photo_like(lines, shape, width=width, light_ink=light, gradient=0.6, noise=0.08)
    prep = prepare(img)
    assert prep.polarity == ("light" if light else "dark")
    assert prep.shape == shape
    precision, recall = centreline_scores(prep.polylines, lines, TOL_PX)
    assert precision >= MIN_SCORE and recall >= MIN_SCORE, (precision, recall)
    # Thinned to one pixel: thinning again changes nothing.
    assert np.array_equal(morphology.skeletonize(prep.skeleton), prep.skeleton)


def test_lighting_gradient_does_not_become_ink():
    lines = [np.array([[20.0, 50.0], [180.0, 60.0]])]
    img = photo_like(lines, (120, 200), width=5, gradient=0.8, noise=0.03, seed=4)
    prep = prepare(img)
    truth = cv2.polylines(np.zeros((120, 200), np.uint8), [np.int32(lines[0])], False, 1, 15)
    assert not (prep.ink & ~truth.astype(bool)).any()


def test_heavy_ink_is_found_where_it_covers_much_of_the_image():
    # A bold font's word: thick bars over 42% of the image (UKIJ Chechek's Arabic was
    # "blank": the ground's first fit ran so close through the ink that none stood out).
    img = np.full((116, 240), 255, np.uint8)
    for x0, y0, x1, y1 in (
        (8, 82, 232, 108),
        (85, 14, 124, 108),
        (189, 27, 210, 108),
        (119, 17, 156, 108),
        (181, 36, 214, 108),
    ):
        img[y0:y1, x0:x1] = 0
    truth = img < 128
    assert 0.35 < truth.mean() < 0.45
    prep = prepare(img)
    assert (prep.ink == truth).mean() > 0.98  # all but a pixel's edge


def test_to_gray_accepts_common_layouts():
    rgb = np.full((10, 12, 3), 255, np.uint8)
    rgb[2, 3] = 0
    assert to_gray(rgb)[2, 3] == 0.0 and to_gray(rgb)[0, 0] == pytest.approx(1.0)
    rgba = np.zeros((10, 12, 4), np.uint8)  # fully transparent -> white
    rgba[4, 5] = (0, 0, 0, 255)
    g = to_gray(rgba)
    assert g[0, 0] == pytest.approx(1.0) and g[4, 5] == 0.0
    assert to_gray(np.eye(4, dtype=bool))[0, 0] == 0.0
    assert to_gray(np.full((3, 3), 65535, np.uint16))[0, 0] == pytest.approx(1.0)
    with pytest.raises(ImageError):
        to_gray(np.zeros((4, 4, 2)))


def test_blank_images_are_rejected():
    with pytest.raises(BlankImageError):
        prepare(np.full((80, 90), 200, np.uint8))
    noise = np.random.default_rng(0).normal(0.8, 0.05, (120, 160)).clip(0, 1)
    with pytest.raises(BlankImageError):
        prepare(noise)


def test_load_image_errors(tmp_path):
    with pytest.raises(ImageError, match="no such file"):
        load_image(tmp_path / "missing.png")
    (tmp_path / "notes.txt").write_text("hello")
    with pytest.raises(ImageError, match="unsupported"):
        load_image(tmp_path / "notes.txt")
    (tmp_path / "broken.png").write_bytes(b"\x89PNG\r\n\x1a\n" + b"junk" * 10)
    with pytest.raises(ImageError):
        load_image(tmp_path / "broken.png")
    good = tmp_path / "ok.png"
    cv2.imwrite(str(good), np.zeros((5, 6, 3), np.uint8))
    assert load_image(good).shape == (5, 6, 3)


def test_to_canvas_keeps_aspect_and_maps_back():
    lines, shape = text_centrelines("a", 3.0)
    img = photo_like(lines, shape, width=6, noise=0.04)
    canvas, tf, prep = to_canvas(img)
    assert canvas.shape == (100, 100) and canvas.dtype == bool
    assert np.array_equal(morphology.skeletonize(canvas), canvas)
    ys, xs = np.nonzero(canvas)
    assert max(xs.max() - xs.min(), ys.max() - ys.min()) == pytest.approx(CHAR_EXTENT, abs=2)
    # Every canvas pixel maps back near the centreline: one canvas pixel of
    # rounding plus the skeleton's own 2-pixel error on a 6-pixel-wide stroke.
    back = tf.to_input(np.stack([xs, ys], 1))
    tol = 1.0 / tf.scale + 2.0
    precision, _ = centreline_scores([back[i : i + 1] for i in range(len(back))], lines, tol)
    assert precision == 1.0
    np.testing.assert_allclose(tf.to_canvas(tf.to_input([[3.0, 4.0]])), [[3.0, 4.0]])


def test_skeleton_polylines_split_at_junctions():
    t = np.zeros((20, 20), bool)
    t[10, 2:18] = True  # horizontal bar
    t[2:10, 10] = True  # stem meeting it: a T
    chains = skeleton_polylines(t)
    assert sorted(len(c) for c in chains) == [8, 9, 9]
    covered = np.zeros_like(t)
    for c in chains:
        covered[c[:, 1], c[:, 0]] = True
    assert np.array_equal(covered, t)
    ring = cv2.circle(np.zeros((30, 30), np.uint8), (15, 15), 9, 1, 1).astype(bool)
    ring = morphology.skeletonize(ring)
    (loop,) = skeleton_polylines(ring)
    assert len(loop) == ring.sum() + 1 and np.array_equal(loop[0], loop[-1])  # closed


def test_simplify_stays_within_tolerance():
    x = np.linspace(0, 50, 200)
    p = np.stack([x, 5 * np.sin(x / 4)], 1)
    q = simplify(p, 0.5)
    assert len(q) < len(p) / 4
    precision, recall = centreline_scores([q], [p], 0.5 + 1e-6)
    assert recall == 1.0 and precision == 1.0


def _rdp_reference(p, tol):
    """Ramer-Douglas-Peucker with distances to the kept segments, written out (numpy)."""
    keep = np.zeros(len(p), bool)
    keep[[0, -1]] = True
    stack = [(0, len(p) - 1)]
    while stack:
        i, j = stack.pop()
        if j <= i + 1:
            continue
        a, b, q = p[i], p[j], p[i + 1 : j]
        ab = b - a
        t = np.clip((q - a) @ ab / max(ab @ ab, 1e-300), 0.0, 1.0)
        d = np.linalg.norm(q - (a + t[:, None] * ab), axis=1)
        # at the ends of the segment, the nearer end point (as skimage)
        inside = ((q - a) @ ab > 0) & ((q - b) @ -ab > 0)
        d = np.where(
            inside, d, np.minimum(np.linalg.norm(q - a, axis=1), np.linalg.norm(q - b, axis=1))
        )
        k = int(np.argmax(d))
        if d[k] > tol:
            keep[i + 1 + k] = True
            stack += [(i + 1 + k, j), (i, i + 1 + k)]
    return p[keep]


def test_simplify_is_rdp_and_keeps_turns(rng):
    for n in rng.integers(3, 80, 200):
        p = np.cumsum(rng.normal(size=(n, 2)), 0)
        np.testing.assert_array_equal(simplify(p, 0.8), _rdp_reference(p, 0.8))
    # A stroke that doubles back along itself keeps its turning point.
    p = np.array([[0.0, 0.0], [5.0, 0.0], [10.0, 0.0], [4.0, 0.0]])
    np.testing.assert_array_equal(simplify(p, 0.5), p[[0, 2, 3]])
