"""Fitting centrelines to the planner's canvas, with the map back to input pixels.

Polylines in input pixels, not a resized bitmap, are drawn onto a canvas (with
:func:`jdraw.geometry.render_strokes`, the one line rule), so the scale can be
chosen freely and every canvas point maps back to input pixels through a kept
:class:`CanvasTransform`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np

from jdraw import geometry
from jdraw.images import morph
from jdraw.images.prepare import Prepared, prepare
from jdraw.images.skeleton import simplify

CANVAS = geometry.CANVAS
# A KanjiVG character spans about this many canvas pixels.
CHAR_EXTENT = 80


@dataclasses.dataclass(frozen=True)
class CanvasTransform:
    """Uniform scale and shift from input pixels to canvas pixels: ``c = scale * p + offset``."""

    scale: float
    offset: tuple[float, float] = (0.0, 0.0)

    def to_canvas(self, points: np.ndarray) -> np.ndarray:
        """``[..., 2]`` (x, y) input pixels to canvas pixels."""
        return np.asarray(points, np.float64) * self.scale + np.asarray(self.offset)

    def to_input(self, points: np.ndarray) -> np.ndarray:
        """``[..., 2]`` (x, y) canvas pixels to input pixels."""
        return (np.asarray(points, np.float64) - np.asarray(self.offset)) / self.scale

    def shifted(self, dx: float, dy: float) -> CanvasTransform:
        """The same map followed by ``c -> c - (dx, dy)`` (a crop at ``(dx, dy)``)."""
        return CanvasTransform(self.scale, (self.offset[0] - dx, self.offset[1] - dy))

    @property
    def matrix(self) -> np.ndarray:
        """``[2, 3]`` affine matrix (input -> canvas), as ``cv2.warpAffine`` takes."""
        s = self.scale
        return np.array([[s, 0.0, self.offset[0]], [0.0, s, self.offset[1]]])


def render_polylines(
    polylines: Sequence[np.ndarray], transform: CanvasTransform, shape: tuple[int, int]
) -> np.ndarray:
    """Draws input-pixel polylines onto a canvas of ``shape`` as thin 8-connected lines.

    The lines are rasterised with :func:`jdraw.geometry.render_strokes` and the
    staircase corners this leaves are thinned away, so the result is what the
    planner is trained on. Returns ``bool [H, W]``.
    """
    tol = 0.35 / transform.scale
    canvas_lines = [transform.to_canvas(simplify(p, tol)) for p in polylines]
    img = geometry.render_strokes(canvas_lines, shape)
    return morph.skeletonize(img) if img.any() else img


def fit_transform(
    bbox: tuple[float, float, float, float], extent: float = CHAR_EXTENT, size: int = CANVAS
) -> CanvasTransform:
    """Scale and shift putting ``bbox = (x0, y0, x1, y1)`` centred in a ``size`` canvas,
    its longer side ``extent`` pixels long (aspect kept)."""
    x0, y0, x1, y1 = bbox
    s = extent / max(x1 - x0, y1 - y0, 1.0)
    c = (size - 1) / 2.0
    return CanvasTransform(s, (c - s * (x0 + x1) / 2.0, c - s * (y0 + y1) / 2.0))


def ink_bbox(polylines: Sequence[np.ndarray]) -> tuple[float, float, float, float]:
    """``(x0, y0, x1, y1)`` of all points."""
    allp = np.concatenate([np.asarray(p, np.float64).reshape(-1, 2) for p in polylines])
    return (*allp.min(0), *allp.max(0))


def to_canvas(
    image: np.ndarray, *, polarity: str = "auto", extent: float = CHAR_EXTENT
) -> tuple[np.ndarray, CanvasTransform, Prepared]:
    """A character-sized image as the planner's input, with the transform kept.

    Returns:
      ``(bool [100, 100] canvas, transform input -> canvas, Prepared)``.
    """
    prep = prepare(image, polarity=polarity)
    tf = fit_transform(ink_bbox(prep.polylines), extent)
    return render_polylines(prep.polylines, tf, (CANVAS, CANVAS)), tf, prep
