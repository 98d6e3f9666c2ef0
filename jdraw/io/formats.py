"""Outputs: SVG, pen-plotter G-code, JSON, and ROS ``JointTrajectory``-shaped JSON.

Strokes are ``[n, 2]`` float (x, y) polylines in input pixels (x the column,
y the row, pixel centres at integers) in drawing order, as
:func:`jdraw.plan_image` returns them.
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
from collections.abc import Sequence
from xml.sax.saxutils import quoteattr

import numpy as np

from jdraw import validate

Strokes = Sequence[np.ndarray]


def _fmt(v: float, digits: int) -> str:
    s = f"{v:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _as_strokes(strokes: Strokes) -> list[np.ndarray]:
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


# ----------------------------------------------------------------------------- SVG


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
        size = f'width="{_fmt(wm, 3)}mm" height="{_fmt(hm, 3)}mm"'
    lines = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" {size} viewBox="0 0 {w} {h}">',
        f'  <g fill="none" stroke={quoteattr(colour)} stroke-width="{_fmt(stroke_width, 3)}" '
        'stroke-linecap="round" stroke-linejoin="round">',
    ]
    for i, p in enumerate(_as_strokes(strokes)):
        if len(p) == 1:
            p = np.concatenate([p, p])
        pts = " ".join(f"{_fmt(x, digits)},{_fmt(y, digits)}" for x, y in p)
        lines.append(f'    <polyline id="stroke{i}" points="{pts}"/>')
    lines += ["  </g>", "</svg>", ""]
    return "\n".join(lines)


# ----------------------------------------------------------------------------- G-code


@dataclasses.dataclass(frozen=True)
class PlotterPreset:
    """How a pen plotter lifts and lowers its pen, and how fast it moves.

    Templates are :meth:`str.format` strings over this preset's fields
    (``{z_up}``, ``{z_down}``, ``{servo_up}``, ``{servo_down}``, ``{dwell_s}``,
    ``{feed}``, ``{travel_feed}``, ``{z_feed}``); several lines are separated by ``\\n``.

    Attributes:
      name: preset name.
      pen_up, pen_down: G-code that lifts / lowers the pen.
      header, footer: G-code before the first and after the last move.
      feed: drawing speed, mm/min.
      travel_feed: pen-up speed, mm/min (``G1`` moves at this feed; ``G0`` if ``None``).
      z_up, z_down, z_feed: pen heights (mm) and plunge speed (mm/min) for Z-axis machines.
      servo_up, servo_down: ``S`` values for servo pen lifts (``M3 S..``).
      dwell_s: pause after a pen lift or drop, seconds (lets a servo settle).
    """

    name: str
    pen_up: str
    pen_down: str
    header: str = "G21 ; millimetres\nG90 ; absolute coordinates"
    footer: str = "G0 X0 Y0\nM2"
    feed: float = 1500.0
    travel_feed: float | None = None
    z_up: float = 5.0
    z_down: float = 0.0
    z_feed: float = 600.0
    servo_up: float = 0.0
    servo_down: float = 90.0
    dwell_s: float = 0.0

    def render(self, template: str) -> list[str]:
        """The template's lines with this preset's values filled in."""
        values = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        values = {k: _fmt(v, 3) if isinstance(v, float) else v for k, v in values.items()}
        text = validate.gcode_template("G-code template", template).format(**values)
        return [ln.strip() for ln in text.replace("\\n", "\n").splitlines() if ln.strip()]


PRESETS: dict[str, PlotterPreset] = {
    # A Z axis carries the pen (CNC routers, 3D printers with a pen holder).
    "zaxis": PlotterPreset(
        name="zaxis",
        pen_up="G0 Z{z_up}",
        pen_down="G1 Z{z_down} F{z_feed}",
    ),
    # A hobby servo lifts the pen, driven through the spindle commands
    # (GRBL servo builds, EleksDraw-style plotters): M3 S<angle> lowers, M5 lifts.
    "servo": PlotterPreset(
        name="servo",
        pen_up="M5\nG4 P{dwell_s}",
        pen_down="M3 S{servo_down}\nG4 P{dwell_s}",
        footer="M5\nG0 X0 Y0\nM2",
        dwell_s=0.15,
    ),
    # As "servo", for machines that hold the lifted pen with a second S value.
    "servo-s": PlotterPreset(
        name="servo-s",
        pen_up="M3 S{servo_up}\nG4 P{dwell_s}",
        pen_down="M3 S{servo_down}\nG4 P{dwell_s}",
        footer="M3 S{servo_up}\nG0 X0 Y0\nM5\nM2",
        servo_up=30.0,
        servo_down=90.0,
        dwell_s=0.15,
    ),
}


def to_gcode(
    strokes: Strokes,
    shape: tuple[int, int],
    *,
    preset: str | PlotterPreset = "zaxis",
    width_mm: float | None = None,
    height_mm: float | None = None,
    origin_mm: tuple[float, float] = (0.0, 0.0),
    flip_y: bool = True,
    digits: int = 3,
    **overrides,
) -> str:
    """Pen-plotter G-code in millimetres.

    The image's pixel frame is scaled to the physical size (default: 100 mm
    wide) with its top-left corner at ``origin_mm`` plus the height when
    ``flip_y`` (machine Y points up, image rows down), so the drawing is not
    mirrored. Each stroke is a pen-up travel to its start, the pen-down
    template, ``G1`` moves at the drawing feed, and the pen-up template.

    Args:
      strokes: ``[n, 2]`` (x, y) input-pixel polylines in drawing order.
      shape: ``(H, W)`` of the input image.
      preset: a name in :data:`PRESETS` or a :class:`PlotterPreset`.
      width_mm, height_mm: physical size of the image frame.
      origin_mm: machine position of the frame's bottom-left (``flip_y``) or top-left corner.
      overrides: preset fields to change, e.g. ``feed=3000``, ``pen_down="M3 S40"``.
    """
    p = PRESETS[preset] if isinstance(preset, str) else preset
    if overrides:
        p = dataclasses.replace(p, **{k: v for k, v in overrides.items() if v is not None})
    validate.positive("feed", p.feed)
    validate.positive("travel_feed", p.travel_feed, optional=True)
    if width_mm is None and height_mm is None:
        width_mm = 100.0
    wm, hm = physical_size(shape, width_mm, height_mm)
    h, w = shape
    k = wm / w

    def xy(pt) -> str:
        # Pixel centres at integers; the frame runs from -0.5 to W - 0.5.
        x = origin_mm[0] + (pt[0] + 0.5) * k
        y = origin_mm[1] + ((h - 0.5 - pt[1]) if flip_y else (pt[1] + 0.5)) * k
        return f"X{_fmt(x, digits)} Y{_fmt(y, digits)}"

    travel = "G0 {}" if p.travel_feed is None else "G1 {} F" + _fmt(p.travel_feed, 1)
    draw_feed = f" F{_fmt(p.feed, 1)}"
    out = [f"; jdraw: {len(strokes)} strokes, {_fmt(wm, 2)} x {_fmt(hm, 2)} mm, preset {p.name}"]
    out += p.render(p.header)
    out += p.render(p.pen_up)
    for s in _as_strokes(strokes):
        out.append(travel.format(xy(s[0])))
        out += p.render(p.pen_down)
        rest = s[1:] if len(s) > 1 else s
        for i, pt in enumerate(rest):
            out.append("G1 " + xy(pt) + (draw_feed if i == 0 else ""))
        out += p.render(p.pen_up)
    out += p.render(p.footer)
    return "\n".join(out) + "\n"


# ----------------------------------------------------------------------------- JSON


def to_json(strokes: Strokes, shape: tuple[int, int]) -> dict:
    """Strokes and the pen-up moves between them, as a JSON-ready dict.

    ``{"width", "height", "units": "px", "strokes": [[[x, y], ...], ...],
    "moves": [{"pen": "up" | "down", ...}], "pen_down_length", "pen_up_length"}``;
    ``moves`` alternates a pen-up travel ``{"from", "to", "length"}`` (the
    first from the first stroke's start, length 0) with a pen-down stroke
    ``{"stroke": index, "length"}``.
    """
    h, w = shape
    ss = _as_strokes(strokes)
    moves = []
    down = up = 0.0
    prev = ss[0][0] if ss else None
    for i, s in enumerate(ss):
        jump = float(np.hypot(*(s[0] - prev)))
        moves.append({"pen": "up", "from": _pt(prev), "to": _pt(s[0]), "length": round(jump, 3)})
        length = float(np.hypot(*np.diff(s, axis=0).T).sum()) if len(s) > 1 else 0.0
        moves.append({"pen": "down", "stroke": i, "length": round(length, 3)})
        down += length
        up += jump
        prev = s[-1]
    return {
        "width": w,
        "height": h,
        "units": "px",
        "strokes": [[_pt(p) for p in s] for s in ss],
        "moves": moves,
        "pen_down_length": round(down, 3),
        "pen_up_length": round(up, 3),
    }


def _pt(p) -> list[float]:
    return [round(float(p[0]), 3), round(float(p[1]), 3)]


def joint_trajectory(
    joint_names: Sequence[str],
    times_s: np.ndarray,
    positions: np.ndarray,
    velocities: np.ndarray | None = None,
) -> dict:
    """A dict shaped like ROS ``trajectory_msgs/JointTrajectory`` (no header).

    Args:
      joint_names: ``J`` names.
      times_s: ``[T]`` seconds from the start, non-decreasing, non-negative.
      positions: ``[T, J]`` joint positions (rad or m).
      velocities: optional ``[T, J]`` (rad/s or m/s).

    Returns:
      ``{"joint_names": [...], "points": [{"positions", "velocities",
      "time_from_start": {"sec", "nanosec"}}, ...]}``; ``velocities`` is an
      empty list when not given, as ROS leaves it.
    """
    names = [str(n) for n in joint_names]
    t = np.asarray(times_s, np.float64).reshape(-1)
    q = np.asarray(positions, np.float64)
    if q.ndim != 2 or q.shape != (len(t), len(names)):
        raise ValueError(f"positions must be [T={len(t)}, J={len(names)}], got {q.shape}")
    if velocities is not None:
        v = np.asarray(velocities, np.float64)
        if v.shape != q.shape:
            raise ValueError(f"velocities must be {q.shape}, got {v.shape}")
    if len(t) and (np.any(np.diff(t) < 0) or t[0] < 0 or not np.all(np.isfinite(t))):
        raise ValueError("times_s must be finite, non-negative and non-decreasing")
    points = []
    for i, ti in enumerate(t):
        ns_total = int(round(ti * 1e9))
        sec, nanosec = divmod(ns_total, 1_000_000_000)
        points.append(
            {
                "positions": q[i].tolist(),
                "velocities": v[i].tolist() if velocities is not None else [],
                "time_from_start": {"sec": int(sec), "nanosec": int(nanosec)},
            }
        )
    return {"joint_names": names, "points": points}


def joint_trajectory_from_report(
    report, index: int = 0, joint_names: Sequence[str] | None = None, velocities: bool = True
) -> dict:
    """:func:`joint_trajectory` for image ``index`` of a ``jdraw.robot`` report.

    Reads the report's ``t`` ``[T]`` (s), ``q_ref`` ``[B, T, J]`` (rad) and, when
    present, ``valid`` ``[B, T]`` and ``joint_names``; times restart at 0 on the
    first valid step. Velocities are finite differences of the positions.
    """
    t = np.asarray(report.t, np.float64)
    q = np.asarray(report.q_ref, np.float64)[index]
    keep = np.asarray(getattr(report, "valid", np.ones((index + 1, len(t)), bool)))[index]
    t, q = t[keep], q[keep]
    t = t - (t[0] if len(t) else 0.0)
    names = joint_names or getattr(report, "joint_names", None)
    names = list(names) if names is not None else [f"joint{i + 1}" for i in range(q.shape[1])]
    v = np.gradient(q, t, axis=0) if velocities and len(t) > 1 else None
    return joint_trajectory(names, t, q, v)


def write_text(text: str, path: str | os.PathLike) -> None:
    """Writes ``text`` to ``path`` (UTF-8)."""
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def write_json(obj: dict, path: str | os.PathLike) -> None:
    """Writes ``obj`` as JSON."""
    write_text(json.dumps(obj, separators=(",", ":")) + "\n", path)
