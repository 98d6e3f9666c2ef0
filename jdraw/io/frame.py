"""Strokes in an image's pixel frame, and that frame's size on paper.

Strokes are ``[n, 2]`` float (x, y) polylines in input pixels (x the column,
y the row, pixel centres at integers) in drawing order, as
:func:`jdraw.plan_image` returns them; every writer in :mod:`jdraw.io` takes them so.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

Strokes = Sequence[np.ndarray]


def decimal(v: float, digits: int) -> str:
    """``v`` with at most ``digits`` decimals and no trailing zeros (``-0`` is ``0``)."""
    s = f"{v:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def as_strokes(strokes: Strokes) -> list[np.ndarray]:
    """``[n, 2]`` float64 arrays, empty strokes dropped."""
    out = []
    for s in strokes:
        p = np.asarray(s, np.float64).reshape(-1, 2)
        if len(p):
            out.append(p)
    return out


def physical_size(
    shape: tuple[int, int], width_mm: float | None = None, height_mm: float | None = None
):
    """``(width_mm, height_mm)`` of an ``(H, W)`` pixel frame, aspect kept.

    Give one of the two; with both, the image fits inside that box.
    """
    h, w = shape
    if width_mm is None and height_mm is None:
        raise ValueError("give width_mm or height_mm")
    sx = width_mm / w if width_mm is not None else math.inf
    sy = height_mm / h if height_mm is not None else math.inf
    s = min(sx, sy)
    if not s > 0 or not math.isfinite(s):
        raise ValueError(f"the physical size must be positive, got {width_mm} x {height_mm} mm")
    return w * s, h * s
