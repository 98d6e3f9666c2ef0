"""Plan to tip motion: canvas strokes become a timed 3-D path over the sheet."""

from __future__ import annotations

import dataclasses

import numpy as np

from jdraw import geometry
from jdraw.robot import scene
from jdraw.robot.options import RobotOptions


@dataclasses.dataclass
class TipPath:
    """Timed pen-tip targets for one image, sampled every ``control_dt``.

    Attributes:
      targets: ``[T, 3]`` m world tip positions.
      canvas: ``[T, 2]`` (x, y) canvas coordinates of the targets.
      down: ``[T]`` bool, the target is on (pressed into) the paper.
      n_steps: number of samples before padding (the rest hold the last one).
      drawing_time_s: s from the first descent to the end of the last lift.
      n_strokes: strokes in the plan.
    """

    targets: np.ndarray
    canvas: np.ndarray
    down: np.ndarray
    n_steps: int
    drawing_time_s: float
    n_strokes: int


def _waypoints(strokes, options: RobotOptions):
    """Vertices ``[K, 3]`` (x, y canvas, height mm), segment speeds (mm/s), pen-down flags."""
    up, down = options.clearance_mm, -options.press_mm
    # The pen follows the pixel centres that the plan inks under the shared line
    # rule, so a (2, 1) move goes through the same middle pixel as jdraw.render.
    strokes = [np.asarray(s, np.float64).reshape(-1, 2) for s in strokes]
    strokes = [
        geometry.polyline_pixels(np.floor(s + 0.5)).astype(np.float64) for s in strokes if len(s)
    ]
    pts: list = []
    speed: list = []  # speed of the segment that ends at this vertex (0: a hold)
    is_down: list = []
    if not strokes:
        pts.append((*np.full(2, 49.5), up))
        return np.array(pts), np.array([0.0]), np.array([False])
    first = strokes[0][0]
    pts.append((*first, up))
    speed.append(0.0)
    is_down.append(False)
    for s in strokes:
        pts.append((*s[0], up))  # pen-up travel to the stroke start
        speed.append(options.travel_speed_mm_s)
        is_down.append(False)
        pts.append((*s[0], down))
        speed.append(options.lift_speed_mm_s)
        is_down.append(True)
        for p in s[1:]:
            pts.append((*p, down))
            speed.append(options.draw_speed_mm_s)
            is_down.append(True)
        pts.append((*s[-1], up))
        speed.append(options.lift_speed_mm_s)
        is_down.append(False)
    return np.array(pts), np.array(speed), np.array(is_down)


def tip_path(strokes, options: RobotOptions | None = None) -> TipPath:
    """Times one image's strokes at the configured speeds.

    Pen down means the target is ``press_mm`` into the paper; pen up means
    ``clearance_mm`` above it. Travel between strokes is a straight pen-up line;
    lifts and descents are vertical.

    Args:
      strokes: list of ``[n, 2]`` (x, y) canvas points drawn with the pen down.
      options: speeds, heights, sheet placement and ``control_dt``.
    """
    options = options or RobotOptions()
    pts, speed, is_down = _waypoints(strokes, options)
    mm = np.asarray(options.sheet_size_mm, np.float64) / 100  # mm per pixel
    metric = pts * np.array([mm[0], mm[1], 1.0])
    seg = np.linalg.norm(np.diff(metric, axis=0), axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        dur = np.where(speed[1:] > 0, seg / np.maximum(speed[1:], 1e-9), 0.0)
    keep = np.concatenate([[True], dur > 0])  # drop zero-length moves
    pts, is_down = pts[keep], is_down[keep]
    t = np.concatenate([[0.0], np.cumsum(dur[dur > 0])]) + options.settle_s
    t = np.concatenate([[0.0], t])
    pts = np.concatenate([pts[:1], pts])
    is_down = np.concatenate([[False], is_down])
    t_end = t[-1] + options.hold_s
    n = int(np.ceil(t_end / options.control_dt)) + 1
    ts = np.arange(n) * options.control_dt
    samples = np.stack([np.interp(ts, t, pts[:, k]) for k in range(3)], -1)
    # A sample is pen-down when it lies between two pen-down vertices.
    seg_idx = np.clip(np.searchsorted(t, ts, side="right"), 1, len(t) - 1)
    down = is_down[seg_idx] & is_down[seg_idx - 1]
    targets = scene.canvas_to_world(samples[:, :2], samples[:, 2], options)
    n_strokes = sum(1 for s in strokes if np.asarray(s).size)
    drawing = t[-1] - options.settle_s if len(t) > 2 else 0.0
    return TipPath(targets, samples[:, :2], down, n, float(drawing), n_strokes)


def batch(paths: list[TipPath], pad_steps: int):
    """Stacks paths, padding with the last sample to a multiple of ``pad_steps``.

    Returns:
      ``targets [B, T, 3]`` float32 m, ``valid [B, T]`` bool.
    """
    n = max(p.n_steps for p in paths)
    t = int(np.ceil(n / pad_steps) * pad_steps)
    targets = np.stack(
        [np.concatenate([p.targets, np.repeat(p.targets[-1:], t - p.n_steps, 0)]) for p in paths]
    ).astype(np.float32)
    valid = np.arange(t)[None] < np.array([p.n_steps for p in paths])[:, None]
    return targets, valid
