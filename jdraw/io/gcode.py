"""Pen-plotter G-code in millimetres, with presets for how the pen is lifted."""

from __future__ import annotations

import dataclasses

from jdraw import validate
from jdraw.io.frame import Strokes, as_strokes, decimal, physical_size


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
        values = {k: decimal(v, 3) if isinstance(v, float) else v for k, v in values.items()}
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
        return f"X{decimal(x, digits)} Y{decimal(y, digits)}"

    travel = "G0 {}" if p.travel_feed is None else "G1 {} F" + decimal(p.travel_feed, 1)
    draw_feed = f" F{decimal(p.feed, 1)}"
    out = [
        f"; jdraw: {len(strokes)} strokes, {decimal(wm, 2)} x {decimal(hm, 2)} mm, preset {p.name}"
    ]
    out += p.render(p.header)
    out += p.render(p.pen_up)
    for s in as_strokes(strokes):
        out.append(travel.format(xy(s[0])))
        out += p.render(p.pen_down)
        rest = s[1:] if len(s) > 1 else s
        for i, pt in enumerate(rest):
            out.append("G1 " + xy(pt) + (draw_feed if i == 0 else ""))
        out += p.render(p.pen_up)
    out += p.render(p.footer)
    return "\n".join(out) + "\n"
