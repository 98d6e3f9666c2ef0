"""SVG: one ``<polyline>`` per stroke, in drawing order, in the image's pixel frame."""

from __future__ import annotations

from xml.sax.saxutils import quoteattr

import numpy as np

from jdraw.io.frame import Strokes, as_strokes, decimal, physical_size


def to_svg(
    strokes: Strokes,
    shape: tuple[int, int],
    *,
    width_mm: float | None = None,
    height_mm: float | None = None,
    stroke_width: float = 1.0,
    colour: str = "black",
    digits: int = 2,
) -> str:
    """An SVG with one ``<polyline>`` per stroke, in drawing order.

    The ``viewBox`` is the input image's pixel frame ``0 0 W H``, so the
    points are input pixel coordinates; the document is ``W x H`` px unless a
    physical size in mm is given. A one-point stroke (a dot) is written as a
    zero-length polyline, which round caps draw as a dot.

    Args:
      strokes: ``[n, 2]`` (x, y) input-pixel polylines.
      shape: ``(H, W)`` of the input image.
      width_mm, height_mm: physical size (aspect kept; see :func:`physical_size`).
      stroke_width: line width in input pixels.
    """
    h, w = shape
    if width_mm is None and height_mm is None:
        size = f'width="{w}" height="{h}"'
    else:
        wm, hm = physical_size(shape, width_mm, height_mm)
        size = f'width="{decimal(wm, 3)}mm" height="{decimal(hm, 3)}mm"'
    lines = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" {size} viewBox="0 0 {w} {h}">',
        f'  <g fill="none" stroke={quoteattr(colour)} stroke-width="{decimal(stroke_width, 3)}" '
        'stroke-linecap="round" stroke-linejoin="round">',
    ]
    for i, p in enumerate(as_strokes(strokes)):
        if len(p) == 1:
            p = np.concatenate([p, p])
        pts = " ".join(f"{decimal(x, digits)},{decimal(y, digits)}" for x, y in p)
        lines.append(f'    <polyline id="stroke{i}" points="{pts}"/>')
    lines += ["  </g>", "</svg>", ""]
    return "\n".join(lines)
