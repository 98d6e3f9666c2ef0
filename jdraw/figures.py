"""Pictures of plans: strokes coloured by order, and the paper's Fig. 3 layout."""

from __future__ import annotations

import colorsys

import cv2
import numpy as np


def order_colours(n: int) -> np.ndarray:
    """``uint8 [n, 3]`` RGB colours running through the hues in drawing order."""
    return np.asarray(
        [
            [int(255 * c) for c in colorsys.hsv_to_rgb(0.8 * i / max(n - 1, 1), 0.85, 0.9)]
            for i in range(n)
        ],
        np.uint8,
    ).reshape(-1, 3)


def _canvas(shape, scale):
    return np.full((shape[0] * scale, shape[1] * scale, 3), 255, np.uint8)


def _pt(p, scale):
    return (int(round((p[0] + 0.5) * scale)), int(round((p[1] + 0.5) * scale)))


def strokes_panel(strokes, shape=(100, 100), scale: int = 4, target=None) -> np.ndarray:
    """RGB picture of strokes, coloured by order, each start marked by a dot.

    Args:
      strokes: list of ``[n, 2]`` (x, y) points.
      target: optional ``bool [H, W]`` drawn in light grey underneath.
    """
    img = _canvas(shape, scale)
    if target is not None:
        t = cv2.resize(
            np.asarray(target, np.uint8),
            (shape[1] * scale, shape[0] * scale),
            interpolation=cv2.INTER_NEAREST,
        ).astype(bool)
        img[t] = (225, 225, 225)
    cols = order_colours(len(strokes))
    for s, c in zip(strokes, cols):
        c = tuple(int(v) for v in c)
        pts = np.array([_pt(p, scale) for p in s], np.int32).reshape(-1, 1, 2)
        cv2.polylines(img, [pts], False, c, max(1, scale // 2), cv2.LINE_AA)
        cv2.circle(img, tuple(pts[0, 0]), max(2, scale), c, -1, cv2.LINE_AA)
    return img


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
