"""A real image reduced to centrelines in input pixels: the first step of ``jdraw.plan_image``.

The planner sees 1-pixel, 8-connected lines on a ``100 x 100`` canvas (paper
§IV-C). :func:`prepare` turns a photo into an ink mask and a centreline
skeleton in *input* pixels (:mod:`jdraw.images.ink`, :mod:`jdraw.images.skeleton`)
and the skeleton into polylines; :mod:`jdraw.images.canvas` then draws those
polylines onto a canvas at a freely chosen scale.
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np

from jdraw.images import gaps, morph
from jdraw.images.ink import binarize, denoise, ink_distance, stroke_width
from jdraw.images.load import BlankImageError, to_gray
from jdraw.images.skeleton import extend_ends, prune_spurs, simplify, skeleton_polylines


@dataclasses.dataclass
class Prepared:
    """A real image reduced to centrelines, in input pixels.

    Attributes:
      shape: ``(H, W)`` of the input.
      ink: ``bool [H, W]`` binarised, denoised ink.
      skeleton: ``bool [H, W]`` 1-pixel centrelines of ``ink``.
      polylines: skeleton chains, ``[n, 2]`` float (x, y), lightly simplified.
      width: typical stroke width, pixels.
      polarity: ``"dark"`` or ``"light"`` ink.
      gap: how close its separate lines come, centreline to centreline, pixels
        (:func:`jdraw.images.gaps.line_gap`; measured when first asked for).
    """

    shape: tuple[int, int]
    ink: np.ndarray
    skeleton: np.ndarray
    polylines: list[np.ndarray]
    width: float
    polarity: str

    @functools.cached_property
    def gap(self) -> float:
        return gaps.line_gap(self.ink, self.skeleton, self.width)


def prepare(image: np.ndarray, *, polarity: str = "auto") -> Prepared:
    """Grayscale, binarise, denoise and skeletonise an image of any size.

    Args:
      image: anything :func:`to_gray` accepts.
      polarity: ``"auto"``, ``"dark"`` or ``"light"`` ink.

    Raises:
      ImageError: bad shape; BlankImageError: no ink.
    """
    gray = to_gray(image)
    ink, polarity = binarize(gray, polarity)
    shape = gray.shape
    del gray  # the largest array of a big scan: not held while thinning
    width = stroke_width(ink)
    ink = denoise(ink, width)
    if not ink.any():
        raise BlankImageError("no ink found (only specks of noise)")
    skel = morph.skeletonize(ink)
    width = stroke_width(ink, skel)
    polylines = skeleton_polylines(skel)
    if width > 2:
        dist = ink_distance(ink)
        skel = prune_spurs(skel, dist, width)
        polylines = extend_ends(skeleton_polylines(skel), skel, dist, width)
    polylines = [simplify(p, 0.5) for p in polylines]
    return Prepared(shape, ink, skel, polylines, width, polarity)
