"""Pictures and animations of plans."""

import numpy as np
import pytest
from PIL import Image

from jdraw.io import pictures

BLACK = np.array([20, 20, 20])
PEN = np.array([230, 30, 30])


def near(img, colour, tol=12):
    return np.all(np.abs(img.astype(int) - colour) <= tol, axis=-1)


def test_animation_draws_in_order_at_pen_speed():
    # Two equal horizontal strokes far apart on a big frame; a pen-up move between them.
    a = np.array([[1000.0, 1000.0], [1100.0, 1000.0]])
    b = np.array([[1100.0, 1060.0], [1000.0, 1060.0]])
    ink = np.zeros((3000, 3000), bool)
    ink[1000, 1000:1101] = ink[1060, 1000:1101] = True
    frames = pictures.animation_frames(
        [a, b], target=ink, frames=40, travel_speed=3.0, max_side=300
    )
    assert len(frames) == 41 and all(f.shape == frames[0].shape for f in frames)
    assert max(frames[0].shape[:2]) == 300  # cropped to the ink, not a speck in 3000 px
    colours = pictures.order_colours(2)
    # Time: 100 px drawn, 60/3 = 20 travelled, 100 drawn: 220 units over 40 frames.
    # Frame 9 (t = 55): half of the first stroke, black, pen at x ~ 1055.
    f = frames[9]
    assert near(f, BLACK).any() and not near(f, colours[0]).any()
    ys, xs = np.nonzero(near(f, PEN))
    x0, _, x1, _ = pictures.ink_box(ink, [a, b])
    scale = 300 / max(x1 - x0, 1)
    assert (xs.mean() / scale + x0) == pytest.approx(1055.5, abs=4)
    # Frame 29 (t = 165): first stroke finished in its colour, second half drawn in black.
    f = frames[29]
    assert near(f, colours[0]).sum() > 50 and not near(f, colours[1]).any()
    assert near(f, BLACK).any()
    # The last frame: both in their colours, nothing highlighted, no pen.
    f = frames[-1]
    assert near(f, colours[1]).sum() > 50 and not near(f, BLACK).any() and not near(f, PEN).any()


def test_gif_has_every_frame(tmp_path):
    strokes = [np.array([[10.0, 10.0], [80.0, 20.0], [50.0, 90.0]]), np.array([[20.0, 70.0]])]
    path = tmp_path / "plan.gif"
    frames = pictures.animate(strokes, path, shape=(100, 100), frames=12, frame_ms=50, hold_ms=900)
    with Image.open(path) as gif:
        assert gif.n_frames == len(frames) == 13
        assert gif.info["loop"] == 0
        gif.seek(gif.n_frames - 1)
        assert gif.info["duration"] == 900
        last = np.asarray(gif.convert("RGB"))
    assert last.shape == frames[-1].shape
    assert np.abs(last.astype(int) - frames[-1]).mean() < 3  # one shared palette


def test_png_crop_keeps_the_drawing_big():
    ink = np.zeros((2000, 3000), bool)
    ink[100:140, 2500] = True
    box = pictures.ink_box(ink, margin=0.1)
    assert box == (2496, 96, 2505, 144)
    img = pictures.draw_strokes_png(ink, [np.array([[2500.0, 100.0], [2500.0, 139.0]])], crop=box)
    assert img.shape == (48 * 4, 9 * 4, 3)
