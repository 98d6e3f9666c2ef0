"""Test doubles: a planner that needs no model."""

from __future__ import annotations

import numpy as np

from jdraw import geometry
from jdraw.images.skeleton import skeleton_polylines
from jdraw.plans import Plan


def trace_planner(images, *, checkpoint=None, max_steps=None, direction="ltr", retrace=None):
    """A stand-in for :func:`jdraw.plan` without a model: every skeleton chain is one stroke.

    Same signature and output type as :func:`jdraw.plan`; ``images`` is
    ``[B, 100, 100]`` or ``[100, 100]``; ``checkpoint``, ``max_steps``,
    ``direction`` (``plan_image`` passes ``"rtl"`` for an image read right to
    left) and ``retrace`` (passed for joined-up writing) are ignored.
    """
    imgs = np.asarray(images)
    if imgs.ndim == 2:
        imgs = imgs[None]
    c = geometry.CANVAS
    if imgs.ndim != 3 or imgs.shape[1:] != (c, c):
        raise ValueError(f"expected [B, {c}, {c}] images, got {imgs.shape}")
    strokes = [[p.astype(np.float64) for p in skeleton_polylines(x != 0)] for x in imgs]
    b = len(imgs)
    return Plan(strokes, np.zeros((b, 0, 3), np.int32), np.zeros(b, np.int32), np.zeros(b, bool))
