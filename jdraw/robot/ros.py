"""The arm's joint path as a ROS ``trajectory_msgs/JointTrajectory``-shaped dict.

``jdraw draw --trajectory`` writes it as JSON (:func:`jdraw.robot.image_trajectory`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np


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
