"""Writing a plan out: every file ``jdraw draw`` can write, from one call.

::

    result = jdraw.plan_image("hello.jpg")
    written = write_outputs(result, svg="hello.svg", gcode="hello.gcode", gif="hello.gif")
    print(written.stats.summary())

is what the command line does with ``--svg``, ``--gcode``, ``--json``, ``--png``
and ``--gif``; :func:`write_trajectory` is ``--trajectory``.
"""

from __future__ import annotations

import dataclasses
import json as jsonlib
import os
from typing import TYPE_CHECKING

from jdraw.io import gcode as gcode_format
from jdraw.io import pictures
from jdraw.io.plan_json import to_json
from jdraw.io.stats import PlotStats, plot_stats
from jdraw.io.svg import to_svg

if TYPE_CHECKING:
    from jdraw.tiling.plan_image import ImagePlan

Path = str | os.PathLike


@dataclasses.dataclass(frozen=True)
class Written:
    """What :func:`write_outputs` measured and wrote.

    Attributes:
      stats: strokes, lengths and plotting time (with the G-code's preset and feeds).
      paths: ``{"svg": path, ...}`` for each file written.
    """

    stats: PlotStats
    paths: dict[str, str]


def write_text(text: str, path: Path) -> None:
    """Writes ``text`` to ``path`` (UTF-8)."""
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def write_json(obj: dict, path: Path) -> None:
    """Writes ``obj`` as compact JSON."""
    write_text(jsonlib.dumps(obj, separators=(",", ":")) + "\n", path)


def write_outputs(
    plan: ImagePlan,
    *,
    svg: Path | None = None,
    gcode: Path | None = None,
    json: Path | None = None,
    png: Path | None = None,
    gif: Path | None = None,
    width_mm: float | None = None,
    height_mm: float | None = None,
    preset: str | gcode_format.PlotterPreset = "zaxis",
    origin_mm: tuple[float, float] = (0.0, 0.0),
    **overrides,
) -> Written:
    """Writes the files asked for (any combination) for an image's plan.

    Args:
      plan: a :class:`jdraw.ImagePlan` (strokes in input pixels).
      svg: SVG, one polyline per stroke (:func:`jdraw.io.svg.to_svg`).
      gcode: pen-plotter G-code (:func:`jdraw.io.gcode.to_gcode`).
      json: strokes, pen-up moves and ``stats`` (:func:`jdraw.io.plan_json.to_json`).
      png: strokes coloured by order over the ink, cropped to it, at most 800 px
        on the longer side (4 px per input pixel at most).
      gif: the plan being drawn (:func:`jdraw.io.pictures.animate`).
      width_mm, height_mm: physical size for the SVG and the G-code (G-code default:
        100 mm wide).
      preset, origin_mm, overrides: the G-code's (``feed``, ``travel_feed``,
        ``pen_up``, ``pen_down``, ``z_up``, ``z_down``; ``None`` keeps the preset's).

    Raises:
      ValueError, KeyError, IndexError: a bad size or G-code template;
      OSError: a file cannot be written.
    """
    strokes, shape = plan.strokes, plan.shape
    size = {"width_mm": width_mm, "height_mm": height_mm}
    stats = plot_stats(strokes, shape, preset=preset, **size, **overrides)
    paths: dict[str, str] = {}
    if svg:
        write_text(to_svg(strokes, shape, **size), svg)
        paths["svg"] = os.fspath(svg)
    if gcode:
        code = gcode_format.to_gcode(
            strokes, shape, preset=preset, origin_mm=tuple(origin_mm), **size, **overrides
        )
        write_text(code, gcode)
        paths["gcode"] = os.fspath(gcode)
    if json:
        data = to_json(strokes, shape)
        data["stats"] = stats.as_dict()
        write_json(data, json)
        paths["json"] = os.fspath(json)
    if png:
        ink = plan.prepared.ink
        box = pictures.ink_box(ink, strokes)
        scale = min(4.0, 800.0 / max(box[2] - box[0], box[3] - box[1]))
        pictures.draw_strokes_png(ink, strokes, png, scale=scale, crop=box)
        paths["png"] = os.fspath(png)
    if gif:
        pictures.animate(plan, gif)
        paths["gif"] = os.fspath(gif)
    return Written(stats, paths)


def write_trajectory(plan: ImagePlan, path: Path, sheet_mm: float = 100.0):
    """The simulated arm draws the plan on a ``sheet_mm`` square sheet; writes its joint path.

    The strokes are fitted onto the sheet and rolled out in MJX
    (:func:`jdraw.robot.image_trajectory`, tens of seconds of compiling); the
    joint path is written as JSON shaped like ROS ``trajectory_msgs/JointTrajectory``,
    also when a waypoint is out of reach (check the report's ``reachable``).

    Returns:
      ``(report, trajectory)``: the one-image :class:`jdraw.robot.Report` and the dict written.
    """
    from jdraw import robot

    options = robot.RobotOptions(sheet_size_mm=(sheet_mm, sheet_mm))
    report, trajectory = robot.image_trajectory(plan.strokes, plan.shape, options)
    write_json(trajectory, path)
    return report, trajectory
