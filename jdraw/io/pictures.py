"""One plan as a picture: its strokes coloured by drawing order (PNG) or being drawn (GIF).

What ``jdraw draw --png`` and ``--gif`` write, at the input's own size (cropped
to the ink). Grids of many canvas-sized plans for figures are :mod:`jdraw.io.figures`.
"""

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
    crop: tuple[int, int, int, int] | None = None,
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
      crop: ``(x0, y0, x1, y1)`` target pixels to show (see :func:`ink_box`); the
        picture is then ``(y1 - y0) x (x1 - x0)`` target pixels.

    Returns:
      ``uint8 [round(H * scale), round(W * scale), 3]`` RGB.
    """
    if crop is not None:
        x0, y0, x1, y1 = crop
        if target is not None:
            target = np.asarray(target)[y0:y1, x0:x1]
        shape = (y1 - y0, x1 - x0)
        strokes = [np.asarray(p, np.float64).reshape(-1, 2) - (x0, y0) for p in strokes]
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


def ink_box(
    ink: np.ndarray | None,
    strokes: Sequence[np.ndarray] = (),
    margin: float = 0.05,
    shape: tuple[int, int] | None = None,
) -> tuple[int, int, int, int]:
    """``(x0, y0, x1, y1)``, the pixels holding ink and strokes plus a margin, inside the frame.

    Args:
      ink: ``[H, W]`` nonzero = ink, or ``None`` (then ``shape`` is the frame).
      strokes: ``[n, 2]`` (x, y) polylines also kept in view.
      margin: fraction of the box's longer side added on every side (at least 2 px).
    """
    h, w = np.asarray(ink).shape[:2] if ink is not None else shape
    pts = [np.asarray(p, np.float64).reshape(-1, 2) for p in strokes]
    if ink is not None and np.any(ink):
        ys, xs = np.nonzero(
            np.asarray(ink) if np.asarray(ink).ndim == 2 else np.asarray(ink)[..., 0]
        )
        pts.append(np.array([[xs.min(), ys.min()], [xs.max(), ys.max()]], np.float64))
    pts = [p for p in pts if len(p)]
    if not pts:
        return 0, 0, w, h
    allp = np.concatenate(pts)
    lo, hi = allp.min(0), allp.max(0)
    pad = max(2.0, margin * float(np.max(hi - lo)))
    x0, y0 = np.maximum(np.floor(lo - pad), 0).astype(int)
    x1, y1 = np.minimum(np.ceil(hi + pad) + 1, (w, h)).astype(int)
    return int(x0), int(y0), int(x1), int(y1)


def _as_drawing(plan, index: int, target):
    """Strokes and a background for ``animate``, from an ImagePlan, a Plan or strokes."""
    if hasattr(plan, "prepared"):  # jdraw.ImagePlan: input pixels
        return list(plan.strokes), plan.prepared.ink if target is None else target
    if hasattr(plan, "actions"):  # jdraw.Plan: one image of a batch, canvas pixels
        strokes = plan.strokes[index]
        if target is None:
            from jdraw import geometry

            target = geometry.render_strokes(strokes, (geometry.CANVAS, geometry.CANVAS))
        return list(strokes), target
    return [np.asarray(p, np.float64).reshape(-1, 2) for p in plan], target


def animation_frames(
    plan,
    *,
    index: int = 0,
    target: np.ndarray | None = None,
    frames: int | None = None,
    travel_speed: float = 3.0,
    max_side: int = 640,
    shape: tuple[int, int] | None = None,
) -> list[np.ndarray]:
    """Frames of the plan being drawn, the pen moving at constant speed.

    Each frame advances the pen by the same time: drawing runs at one speed,
    pen-up travel ``travel_speed`` times faster. Finished strokes take their
    order colour (blue first, red last, as :func:`draw_strokes_png`); the
    stroke being drawn is black and thicker, with the pen as a red dot;
    pen-up moves are faint grey lines; the input is light grey behind. The
    picture is cropped to the ink (:func:`ink_box`) and scaled so its longer
    side is ``max_side`` pixels.

    Args:
      plan: a :class:`jdraw.ImagePlan`, a :class:`jdraw.Plan` (image ``index``), or
        a sequence of ``[n, 2]`` (x, y) strokes (then give ``target`` or ``shape``).
      target: ``[H, W]`` background ink (default: the plan's input).
      frames: how many frames the drawing takes (one per group of steps; default
        3 a stroke, from 60 to 240); a last frame shows the finished drawing.
      travel_speed: pen-up speed over drawing speed.
      max_side: output pixels of the longer side.

    Returns:
      ``uint8 [h, w, 3]`` RGB frames, all the same size.
    """
    strokes, target = _as_drawing(plan, index, target)
    strokes = [s for s in strokes if len(s)]
    if target is not None:
        shape = np.asarray(target).shape[:2]
    if shape is None:
        raise ValueError("give target or shape with bare strokes")
    x0, y0, x1, y1 = ink_box(target, strokes, shape=shape)
    scale = max_side / max(x1 - x0, y1 - y0)
    base = draw_strokes_png(target, [], scale=scale, shape=shape, crop=(x0, y0, x1, y1))
    lw = max(2, round(max_side / 240))
    shift = 4

    def pix(p):
        q = (np.asarray(p, np.float64).reshape(-1, 2) - (x0, y0) + 0.5) * scale * (1 << shift)
        return np.round(q).astype(np.int32).reshape(-1, 1, 2)

    def line(img, p, colour, width):
        if len(p) > 1:
            cv2.polylines(img, [pix(p)], False, colour, width, cv2.LINE_AA, shift)
        else:
            c = tuple(int(v) for v in pix(p)[0, 0])
            cv2.circle(img, c, max(1, width // 2) << shift, colour, -1, cv2.LINE_AA, shift)

    # The motion: (start time, end time, points, stroke index or -1 for a pen-up move).
    moves, t, prev = [], 0.0, None
    for i, s in enumerate(strokes):
        if prev is not None:
            d = float(np.hypot(*(s[0] - prev))) / travel_speed
            moves.append((t, t + d, np.stack([prev, s[0]]), -1))
            t += d
        seg = np.hypot(*np.diff(s, axis=0).T) if len(s) > 1 else np.zeros(0)
        moves.append((t, t + max(float(seg.sum()), 1.0), s, i))
        t, prev = moves[-1][1], s[-1]
    total = t
    colours = [tuple(int(v) for v in c) for c in order_colours(len(strokes))]
    faint, ink_now, pen = (170, 170, 170), (20, 20, 20), (230, 30, 30)

    def partial(points, t0, t1, at):
        """The part of ``points`` drawn by time ``at`` (constant speed over ``[t0, t1]``)."""
        if len(points) < 2:
            return points
        cum = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(points, axis=0).T))])
        d = (at - t0) / (t1 - t0) * cum[-1]
        k = int(np.searchsorted(cum, d, side="right"))
        if k >= len(points):
            return points
        f = (d - cum[k - 1]) / max(cum[k] - cum[k - 1], 1e-9)
        return np.concatenate([points[:k], points[k - 1] + f * (points[k] - points[k - 1])[None]])

    done = base.copy()  # finished moves, drawn once
    out, m = [], 0
    n = int(frames) if frames is not None else int(np.clip(3 * len(strokes), 60, 240))
    n = max(n, 1)
    for f in range(1, n + 1):
        at = total * f / n
        while m < len(moves) and moves[m][1] <= at + 1e-9:
            _, _, p, i = moves[m]
            line(done, p, faint if i < 0 else colours[i], 1 if i < 0 else lw)
            m += 1
        img = done.copy()
        if m < len(moves):
            t0, t1, p, i = moves[m]
            q = partial(p, t0, t1, at)
            line(img, q, faint if i < 0 else ink_now, 1 if i < 0 else lw + 2)
            tip = q[-1]
        else:
            tip = strokes[-1][-1] if strokes else None
        if tip is not None:
            c = tuple(int(v) for v in pix(tip)[0, 0])
            cv2.circle(img, c, (lw + 3) << shift, pen, -1, cv2.LINE_AA, shift)
        out.append(img)
    final = base.copy()
    for _, _, p, i in moves:
        line(final, p, faint if i < 0 else colours[i], 1 if i < 0 else lw)
    out.append(final)
    return out


def animate(
    plan,
    path: str | os.PathLike | None = None,
    *,
    frame_ms: int = 60,
    hold_ms: int = 2000,
    **kwargs,
) -> list[np.ndarray]:
    """Animates a plan (see :func:`animation_frames`) and writes it as a looping GIF.

    Args:
      plan: a :class:`jdraw.ImagePlan`, :class:`jdraw.Plan` or strokes.
      path: the GIF to write, or ``None`` for the frames only.
      frame_ms: time each frame shows; the finished drawing shows ``hold_ms``.
      kwargs: passed to :func:`animation_frames` (``frames``, ``max_side``, ...).

    Returns:
      The frames, ``uint8 [h, w, 3]`` RGB.
    """
    frames = animation_frames(plan, **kwargs)
    if path is not None:
        from PIL import Image

        # One palette for every frame (taken from the finished drawing, which holds
        # every colour), so colours do not flicker between frames.
        last = Image.fromarray(frames[-1])
        marks = Image.fromarray(
            np.array([[[20, 20, 20], [230, 30, 30], [170, 170, 170]]], np.uint8)
        )
        sample = Image.new("RGB", (last.width, last.height + 1))
        sample.paste(last)
        sample.paste(marks, (0, last.height))
        palette = sample.quantize(colors=256, method=Image.Quantize.FASTOCTREE)
        images = [
            Image.fromarray(f).quantize(palette=palette, dither=Image.Dither.NONE) for f in frames
        ]
        durations = [frame_ms] * (len(images) - 1) + [hold_ms]
        images[0].save(
            os.fspath(path),
            save_all=True,
            append_images=images[1:],
            duration=durations,
            loop=0,
            optimize=False,
            disposal=1,
        )
    return frames
