"""Settings for turning a plan into arm motion and checking it in simulation."""

from __future__ import annotations

import dataclasses


@dataclasses.dataclass(frozen=True)
class RobotOptions:
    """Where the sheet lies, how the pen moves, and how strictly IK is judged.

    Attributes:
      sheet_center: ``(x, y)`` m, centre of the paper on the table (world frame,
        robot base at the origin, table top at ``z = 0``).
      sheet_yaw: rad, rotation of the sheet about the vertical axis.
      sheet_size_mm: ``(width, height)`` mm of the paper; the 100x100 canvas is
        stretched over it (default 1 mm per pixel).
      clearance_mm: mm, pen-up height of the tip above the paper.
      press_mm: mm, how far below the paper surface the pen-down target is; the
        spring-loaded tip takes it up, so contact holds despite tracking error.
      draw_speed_mm_s: mm/s, tip speed with the pen down.
      travel_speed_mm_s: mm/s, tip speed of pen-up moves between strokes.
      lift_speed_mm_s: mm/s, vertical speed of pen lifts and descents.
      control_dt: s, period of the joint targets (the IK waypoints).
      settle_s: s, hold at the first hover point before moving.
      hold_s: s, hold at the last point after the final lift.
      pad_steps: control steps are padded to a multiple of this so batches of
        different lengths share one compiled rollout.
      nib_radius_px: half the width of the inked line, in pixels: a pixel is
        drawn when the nib's contact point passes this close to its centre.
      ik_iters_first: damped-least-squares iterations for the first waypoint,
        started from the arm's seed posture.
      ik_iters: iterations per later waypoint, warm-started from the previous.
      ik_damping: damping of the least-squares step (m).
      ik_tol_mm: a waypoint counts as solved when the tip is within this of it.
      ik_tol_deg: ... and the pen axis within this of vertical.
    """

    sheet_center: tuple[float, float] = (0.45, 0.0)
    sheet_yaw: float = 0.0
    sheet_size_mm: tuple[float, float] = (100.0, 100.0)
    clearance_mm: float = 8.0
    press_mm: float = 1.5
    draw_speed_mm_s: float = 60.0
    travel_speed_mm_s: float = 150.0
    lift_speed_mm_s: float = 60.0
    control_dt: float = 0.01
    settle_s: float = 0.2
    hold_s: float = 0.1
    pad_steps: int = 256
    nib_radius_px: float = 0.5
    ik_iters_first: int = 300
    ik_iters: int = 3
    ik_damping: float = 0.005
    ik_tol_mm: float = 1.0
    ik_tol_deg: float = 2.0
