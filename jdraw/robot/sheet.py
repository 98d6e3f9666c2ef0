"""Drawings of any size on the arm's sheet: fitting strokes to it, and the joint path.

``jdraw draw --trajectory`` uses :func:`image_trajectory`.
"""

from __future__ import annotations

import numpy as np

from jdraw import geometry
from jdraw import plans as types
from jdraw.images.canvas import fit_transform
from jdraw.robot.options import RobotOptions
from jdraw.robot.ros import joint_trajectory_from_report
from jdraw.robot.verifier import Report, verify


def to_sheet(strokes, shape: tuple[int, int], fill: float = 0.9) -> list[np.ndarray]:
    """Maps input-pixel strokes onto the robot's 100 x 100 sheet canvas, aspect kept.

    Args:
      strokes: ``[n, 2]`` (x, y) polylines in the pixel frame of an ``(H, W)`` image.
      shape: ``(H, W)``.
      fill: fraction of the canvas the image's longer side spans, centred.

    Returns:
      The strokes in canvas pixels (floats); :class:`RobotOptions.sheet_size_mm`
      sets how many mm a canvas pixel is.
    """
    h, w = shape
    if h < 1 or w < 1:
        raise ValueError(f"image shape must be positive, got {shape}")
    if not 0 < fill <= 1:
        raise ValueError(f"fill must be in (0, 1], got {fill}")
    tf = fit_transform((0.0, 0.0, w - 1.0, h - 1.0), extent=fill * (geometry.CANVAS - 1))
    return [tf.to_canvas(np.asarray(s, np.float64).reshape(-1, 2)) for s in strokes]


def image_trajectory(
    strokes, shape: tuple[int, int], options: RobotOptions | None = None, fill: float = 0.9
) -> tuple[Report, dict]:
    """Draws an image's strokes with the simulated arm; returns the check and joint path.

    The strokes are fitted onto the sheet (:func:`to_sheet`; 1 mm per canvas
    pixel on the default 100 mm sheet, so finer detail than that is lost),
    timed, solved by IK and rolled out in MJX by :func:`jdraw.robot.verify`.

    Returns:
      ``(report, trajectory)``: the one-image :class:`Report` (``reachable``,
      ``iou`` of what the nib drew against the plan, ``drawing_time_s``, ...)
      and the IK joint targets as a dict shaped like ROS
      ``trajectory_msgs/JointTrajectory``
      (:func:`jdraw.robot.ros.joint_trajectory_from_report`).
    """
    sheet = to_sheet(strokes, shape, fill)
    plan = types.Plan(
        [sheet], np.zeros((1, 0, 3), np.int32), np.zeros(1, np.int32), np.zeros(1, bool)
    )
    report = verify(plan, options)
    return report, joint_trajectory_from_report(report, 0)
