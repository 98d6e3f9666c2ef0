"""Pictures of plans: strokes coloured by drawing order, each start marked."""

from __future__ import annotations

import os
from collections.abc import Sequence

import cv2
import numpy as np


def order_colours(n: int) -> np.ndarray:
    """``uint8 [n, 3]`` RGB colours running from blue (first) through green to red (last)."""
    if n <= 0:
        return np.zeros((0, 3), np.uint8)
    ramp = np.linspace(30, 225, n).round().astype(np.uint8)[:, None]
    bgr = cv2.applyColorMap(ramp, cv2.COLORMAP_TURBO)[:, 0]
    return bgr[:, ::-1].copy()


def draw_strokes_png(
    target: np.ndarray | None,
    strokes: Sequence[np.ndarray],
    path: str | os.PathLike | None = None,
    *,
    scale: float = 4.0,
    shape: tuple[int, int] | None = None,
    line_width: float | None = None,
    start_marks: bool = True,
) -> np.ndarray:
    """Draws strokes over a faint copy of the target, coloured by drawing order.

    Args:
      target: ``bool`` or 0/1 ``[H, W]`` ink (shown light grey), or a grayscale
        ``[H, W]`` / RGB ``[H, W, 3]`` picture (``uint8``, or float in ``[0, 1]``)
        shown faded; ``None`` for a white background of ``shape``.
      strokes: ``[n, 2]`` (x, y) polylines in the target's pixel coordinates, in order.
      path: where to write the PNG, or ``None``.
      scale: output pixels per target pixel (may be below 1 for big inputs).
      shape: ``(H, W)`` when ``target`` is ``None``.
      line_width: output pixels (default: about ``scale``, at least 1).
      start_marks: a filled circle at each stroke's first point.

    Returns:
      ``uint8 [round(H * scale), round(W * scale), 3]`` RGB.
    """
    if target is None:
        if shape is None:
            raise ValueError("give target or shape")
        h, w = shape
        base = np.full((h, w, 3), 255, np.uint8)
    else:
        t = np.asarray(target)
        h, w = t.shape[:2]
        if t.dtype == bool or (t.ndim == 2 and np.isin(t, (0, 1)).all()):
            base = np.where((t != 0)[..., None], np.uint8(215), np.uint8(255)).repeat(3, 2)
        else:
            u8 = t if t.dtype == np.uint8 else (np.clip(t, 0, 1) * 255).astype(np.uint8)
            rgb = u8[..., :3] if u8.ndim == 3 else np.repeat(u8[..., None], 3, 2)
            base = (255 - (255 - rgb.astype(np.float32)) * 0.35).astype(np.uint8)
    oh, ow = max(1, round(h * scale)), max(1, round(w * scale))
    interp = cv2.INTER_NEAREST if scale >= 1 else cv2.INTER_AREA
    img = cv2.resize(base, (ow, oh), interpolation=interp)
    lw = max(1, round(line_width if line_width is not None else max(1.0, scale * 0.8)))
    radius = max(2, round(1.6 * lw))
    shift = 4
    colours = order_colours(len(strokes))
    for s, c in zip(strokes, colours, strict=True):
        p = np.asarray(s, np.float64).reshape(-1, 2)
        if not len(p):
            continue
        # Pixel centres sit at (i + 0.5) * scale in the enlarged picture.
        q = np.round((p + 0.5) * scale * (1 << shift)).astype(np.int32)
        colour = tuple(int(v) for v in c)
        if len(q) > 1:
            cv2.polylines(img, [q.reshape(-1, 1, 2)], False, colour, lw, cv2.LINE_AA, shift)
        if start_marks or len(q) == 1:
            cv2.circle(
                img, tuple(int(v) for v in q[0]), radius << shift, colour, -1, cv2.LINE_AA, shift
            )
    if path is not None:
        cv2.imwrite(os.fspath(path), cv2.cvtColor(img, cv2.COLOR_RGB2BGR))
    return img
