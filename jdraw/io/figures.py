"""Panels for figures of many characters: the paper's Fig. 3 rows and grids of them.

Each panel is an RGB array of one ``100 x 100`` canvas (target, pen path, strokes
by order); :func:`fig3_row` puts three side by side, :func:`save_png` writes a
stack of rows. One plan's own PNG and GIF are :mod:`jdraw.io.pictures`.
"""

from __future__ import annotations

import cv2
import numpy as np

from jdraw.io import pictures


def _canvas(shape, scale):
    return np.full((shape[0] * scale, shape[1] * scale, 3), 255, np.uint8)


def _pt(p, scale):
    return (int(round((p[0] + 0.5) * scale)), int(round((p[1] + 0.5) * scale)))


def strokes_panel(strokes, shape=(100, 100), scale: int = 4, target=None) -> np.ndarray:
    """RGB picture of strokes coloured by order (blue first, red last), each start dotted.

    Args:
      strokes: list of ``[n, 2]`` (x, y) points.
      target: optional ``bool [H, W]`` drawn in light grey underneath.
    """
    return pictures.draw_strokes_png(target, strokes, None, scale=scale, shape=shape)


def trace_panel(strokes, shape=(100, 100), scale: int = 4) -> np.ndarray:
    """The pen's whole path: pen-down in black, pen-up jumps as thin red lines."""
    img = _canvas(shape, scale)
    prev = None
    for s in strokes:
        if prev is not None:
            cv2.line(img, _pt(prev, scale), _pt(s[0], scale), (230, 60, 60), 1, cv2.LINE_AA)
        pts = np.array([_pt(p, scale) for p in s], np.int32).reshape(-1, 1, 2)
        cv2.polylines(img, [pts], False, (0, 0, 0), max(1, scale // 2), cv2.LINE_AA)
        prev = s[-1]
    return img


def target_panel(target, scale: int = 4) -> np.ndarray:
    t = np.asarray(target, bool)
    img = _canvas(t.shape, scale)
    big = cv2.resize(
        t.astype(np.uint8),
        (t.shape[1] * scale, t.shape[0] * scale),
        interpolation=cv2.INTER_NEAREST,
    ).astype(bool)
    img[big] = 0
    return img


def fig3_row(target, strokes, scale: int = 3) -> np.ndarray:
    """Target | trace | strokes coloured by order (the paper's Fig. 3)."""
    sep = np.full((target.shape[0] * scale, 4, 3), 160, np.uint8)
    return np.concatenate(
        [
            target_panel(target, scale),
            sep,
            trace_panel(strokes, target.shape, scale),
            sep,
            strokes_panel(strokes, target.shape, scale),
        ],
        1,
    )


def save_png(path, rgb: np.ndarray) -> None:
    if not cv2.imwrite(str(path), cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR)):
        raise OSError(f"could not write {path}")
