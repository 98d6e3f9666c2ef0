"""Plot statistics: strokes, pen-down length, pen-up travel and plotting time.

``plot_stats(result.strokes, result.shape, width_mm=150)`` answers what a
plotter owner asks before sending a drawing: how much is drawn, how far the
pen travels lifted, and how long the G-code of :func:`jdraw.io.gcode.to_gcode`
with the same preset and feeds will take.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np

from jdraw.io import gcode
from jdraw.io.frame import physical_size


@dataclasses.dataclass(frozen=True)
class PlotStats:
    """What a plan asks of a plotter.

    Attributes:
      strokes: pen-down motions (one pen drop and lift each).
      pen_down: length drawn, in ``units``.
      pen_up: pen-up travel between strokes (first pen drop to last lift), in ``units``.
      units: ``"mm"`` when a physical size was given, else ``"px"`` (input pixels).
      mm_per_unit: millimetres per unit of the G-code the time is estimated for.
      time_s: estimated plotting time of that G-code, seconds: drawing at the
        drawing feed, pen-up travel at the travel feed (``G0`` moves at
        ``rapid_mm_min``), pen drops and lifts (Z moves or servo dwells).
        Acceleration and the moves from and back to the machine origin are left out.
      draw_s, travel_s, lift_s: the three parts of ``time_s``.
    """

    strokes: int
    pen_down: float
    pen_up: float
    units: str
    mm_per_unit: float
    time_s: float
    draw_s: float
    travel_s: float
    lift_s: float

    def as_dict(self) -> dict:
        """JSON-ready, lengths rounded to 0.001 and times to 0.01 s."""
        d = dataclasses.asdict(self)
        for k in ("pen_down", "pen_up", "mm_per_unit"):
            d[k] = round(d[k], 3)
        for k in ("time_s", "draw_s", "travel_s", "lift_s"):
            d[k] = round(d[k], 2)
        return d

    def summary(self) -> str:
        """One line: ``12 strokes, pen-down 843.2 mm, pen-up 310.0 mm, plotting ~47 s``."""
        return (
            f"{self.strokes} strokes, pen-down {self.pen_down:.1f} {self.units}, "
            f"pen-up {self.pen_up:.1f} {self.units}, plotting ~{_duration(self.time_s)}"
        )


def _duration(s: float) -> str:
    if s < 60:
        return f"{s:.0f} s"
    m, s = divmod(round(s), 60)
    return f"{m} min {s:02d} s" if m < 60 else f"{m // 60} h {m % 60:02d} min"


def lengths(strokes: Sequence[np.ndarray]) -> tuple[float, float]:
    """``(pen-down length, pen-up travel between strokes)`` of ``[n, 2]`` polylines."""
    ss = [np.asarray(s, np.float64).reshape(-1, 2) for s in strokes]
    ss = [s for s in ss if len(s)]
    down = sum(float(np.hypot(*np.diff(s, axis=0).T).sum()) for s in ss if len(s) > 1)
    up = sum(float(np.hypot(*(b[0] - a[-1]))) for a, b in zip(ss[:-1], ss[1:]))
    return down, up


def plot_stats(
    strokes: Sequence[np.ndarray],
    shape: tuple[int, int],
    *,
    width_mm: float | None = None,
    height_mm: float | None = None,
    preset: str | gcode.PlotterPreset = "zaxis",
    rapid_mm_min: float = 3000.0,
    **overrides,
) -> PlotStats:
    """Counts, lengths and estimated plotting time of ``strokes``.

    Args:
      strokes: ``[n, 2]`` (x, y) input-pixel polylines in drawing order.
      shape: ``(H, W)`` of the input image.
      width_mm, height_mm: physical size (as :func:`jdraw.io.gcode.to_gcode`);
        lengths are then in mm. Without either, lengths are in input pixels
        and the time is for G-code's default size, 100 mm wide.
      preset, overrides: the G-code preset and its changed fields (``feed``,
        ``travel_feed``, ``z_up``, ``z_down``, ``z_feed``, ``dwell_s``), as
        :func:`jdraw.io.gcode.to_gcode` takes them.
      rapid_mm_min: speed of ``G0`` moves, which G-code leaves to the machine
        (an assumption; pass your machine's).
    """
    p = gcode.PRESETS[preset] if isinstance(preset, str) else preset
    changes = {k: v for k, v in overrides.items() if v is not None}
    if changes:
        p = dataclasses.replace(p, **changes)
    sized = width_mm is not None or height_mm is not None
    wm, _ = physical_size(shape, width_mm, height_mm) if sized else (100.0, 0.0)
    k = wm / shape[1]  # mm per input pixel in the G-code
    down_px, up_px = lengths(strokes)
    n = sum(1 for s in strokes if len(np.asarray(s).reshape(-1, 2)))
    draw_s = down_px * k / p.feed * 60
    travel_s = up_px * k / (p.travel_feed or rapid_mm_min) * 60
    # Each stroke drops and lifts the pen once, by the templates: a Z drop is a G1 at
    # z_feed (zaxis), a Z lift a G0; a servo waits dwell_s after each.
    z = abs(p.z_up - p.z_down)
    drop = (z / p.z_feed * 60 if "{z_down}" in p.pen_down else 0.0) + (
        p.dwell_s if "{dwell_s}" in p.pen_down else 0.0
    )
    lift = (z / rapid_mm_min * 60 if "{z_up}" in p.pen_up else 0.0) + (
        p.dwell_s if "{dwell_s}" in p.pen_up else 0.0
    )
    lift_s = n * (drop + lift)
    unit = k if sized else 1.0
    return PlotStats(
        strokes=n,
        pen_down=down_px * unit,
        pen_up=up_px * unit,
        units="mm" if sized else "px",
        mm_per_unit=k / unit,
        time_s=draw_s + travel_s + lift_s,
        draw_s=draw_s,
        travel_s=travel_s,
        lift_s=lift_s,
    )
