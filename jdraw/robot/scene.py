"""The arm's MJCF model and the geometry of the sheet on the table."""

from __future__ import annotations

import functools
import importlib.resources

import mujoco
import numpy as np

from jdraw import geometry
from jdraw.robot.options import RobotOptions

ARM_XML = "assets/robot/arm.xml"
N_ARM = 7  # arm joints; qpos[7] is the pen's spring-loaded tip
PAPER_THICKNESS = 1e-4  # m, as in the MJCF
# A pen-down, elbow-up posture above the default sheet; IK for a plan starts here.
SEED = np.array([0.0, 0.8, np.pi, -1.85, 0.0, -0.48, np.pi / 2], np.float32)


@functools.lru_cache(maxsize=1)
def _xml() -> str:
    return importlib.resources.files("jdraw").joinpath(ARM_XML).read_text()


def load(options: RobotOptions | None = None) -> mujoco.MjModel:
    """Compiles the arm with the paper moved to ``options``' sheet placement."""
    options = options or RobotOptions()
    m = mujoco.MjModel.from_xml_string(_xml())
    g = m.geom("paper").id
    m.geom_pos[g] = (*options.sheet_center, PAPER_THICKNESS / 2)
    m.geom_size[g] = (
        options.sheet_size_mm[0] / 2000,
        options.sheet_size_mm[1] / 2000,
        PAPER_THICKNESS / 2,
    )
    c, s = np.cos(options.sheet_yaw / 2), np.sin(options.sheet_yaw / 2)
    m.geom_quat[g] = (c, 0.0, 0.0, s)
    # The compiler marked the unrotated paper as sharing the world frame, which
    # makes C MuJoCo (rendering) ignore the new quat; MJX always applies it.
    m.geom_sameframe[g] = 0
    # Broadphase bounds follow the size.
    m.geom_rbound[g] = float(np.linalg.norm(m.geom_size[g]))
    m.geom_aabb[g] = np.concatenate([np.zeros(3), m.geom_size[g]])
    return m


def ids(m: mujoco.MjModel) -> dict[str, int]:
    return {
        "tip_site": m.site("tip").id,
        "tip_geom": m.geom("pen_tip").id,
        "paper": m.geom("paper").id,
        "tip_body": m.body("pen_tip").id,
    }


def _frame(options: RobotOptions):
    c, s = np.cos(options.sheet_yaw), np.sin(options.sheet_yaw)
    rot = np.array([[c, -s], [s, c]])
    return np.asarray(options.sheet_center, np.float64), rot


def pixel_size_m(options: RobotOptions) -> np.ndarray:
    """``[2]`` m per canvas pixel along x (columns) and y (rows)."""
    return np.asarray(options.sheet_size_mm, np.float64) / 1000 / geometry.CANVAS


def canvas_to_world(points, height_mm, options: RobotOptions) -> np.ndarray:
    """Canvas points to world positions of the pen tip.

    Args:
      points: ``[N, 2]`` (x, y) canvas coordinates; pixel ``(i, j)`` has its
        centre at ``(i, j)`` and canvas rows run away from the robot's left.
      height_mm: ``[N]`` or scalar, mm of the tip above the paper surface.
      options: sheet placement.

    Returns:
      ``[N, 3]`` m in the world frame.
    """
    p = np.asarray(points, np.float64).reshape(-1, 2)
    size = np.asarray(options.sheet_size_mm, np.float64) / 1000
    px = pixel_size_m(options)
    u = (p[:, 0] + 0.5) * px[0] - size[0] / 2
    v = size[1] / 2 - (p[:, 1] + 0.5) * px[1]
    center, rot = _frame(options)
    xy = center + np.stack([u, v], -1) @ rot.T
    z = PAPER_THICKNESS + np.broadcast_to(np.asarray(height_mm, np.float64), len(p)) / 1000
    return np.concatenate([xy, z[:, None]], -1)


def world_to_canvas(xyz, options: RobotOptions) -> np.ndarray:
    """Inverse of :func:`canvas_to_world` in the plane: ``[N, 3]`` m -> ``[N, 2]`` canvas."""
    xyz = np.asarray(xyz, np.float64).reshape(-1, 3)
    center, rot = _frame(options)
    uv = (xyz[:, :2] - center) @ rot
    size = np.asarray(options.sheet_size_mm, np.float64) / 1000
    px = pixel_size_m(options)
    return np.stack(
        [(uv[:, 0] + size[0] / 2) / px[0] - 0.5, (size[1] / 2 - uv[:, 1]) / px[1] - 0.5], -1
    )


def sheet_params(options: RobotOptions) -> np.ndarray:
    """``[8]`` float32 ``(cx, cy, cos, sin, half_w, half_h, pixel_w, pixel_h)`` (m) for jit code."""
    size = np.asarray(options.sheet_size_mm, np.float64) / 1000
    px = pixel_size_m(options)
    return np.array(
        [
            *options.sheet_center,
            np.cos(options.sheet_yaw),
            np.sin(options.sheet_yaw),
            size[0] / 2,
            size[1] / 2,
            px[0],
            px[1],
        ],
        np.float32,
    )
