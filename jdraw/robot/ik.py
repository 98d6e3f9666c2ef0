"""Inverse kinematics of the pen tip: damped least squares on MJX kinematics.

The Jacobian is the geometric one read off MJX's joint frames (for a hinge,
``axis x (tip - anchor)``), so one :func:`mujoco.mjx.kinematics` call gives
both the residual and its Jacobian. The pen is asked to point straight down.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
from mujoco import mjx

from jdraw.robot.scene import N_ARM

_DOWN = jnp.array([0.0, 0.0, -1.0])
_ROT_WEIGHT = 0.1  # m per rad: 1 deg of pen tilt weighs like 1.7 mm of tip error


def fk(mx: mjx.Model, d: mjx.Data, q: jax.Array, tip_site: int):
    """Tip position ``[3]`` m, pen axis ``[3]``, joint anchors and axes ``[7, 3]``."""
    qpos = jnp.concatenate([q, jnp.zeros(mx.nq - N_ARM, q.dtype)])
    d = mjx.kinematics(mx, d.replace(qpos=qpos))
    return (d.site_xpos[tip_site], d.site_xmat[tip_site][:, 2], d.xanchor[:N_ARM], d.xaxis[:N_ARM])


def errors(mx: mjx.Model, d: mjx.Data, q: jax.Array, target: jax.Array, tip_site: int):
    """Tip error (mm) and pen tilt from vertical (deg) at joint angles ``q`` ``[7]``."""
    tip, axis, _, _ = fk(mx, d, q, tip_site)
    tilt = jnp.degrees(jnp.arccos(jnp.clip(jnp.dot(axis, _DOWN), -1.0, 1.0)))
    return 1000 * jnp.linalg.norm(target - tip), tilt


def dls_step(mx, d, q, target, tip_site: int, lo, hi, damping):
    """One damped least-squares step toward ``target`` ``[3]`` m, clipped to limits."""
    tip, axis, anchor, jaxis = fk(mx, d, q, tip_site)
    e = jnp.concatenate([target - tip, -_ROT_WEIGHT * jnp.cross(axis, _DOWN)])
    jp = jnp.cross(jaxis, tip - anchor).T  # [3, 7]
    # d(axis x down)/dq_i = (jaxis_i x axis) x down
    jr = jnp.cross(jnp.cross(jaxis, axis), _DOWN).T
    jac = jnp.concatenate([jp, _ROT_WEIGHT * jr])  # [6, 7]
    a = jac @ jac.T + damping**2 * jnp.eye(6, dtype=q.dtype)
    dq = jac.T @ jnp.linalg.solve(a, e)
    return jnp.clip(q + dq, lo, hi)


def solve_path(mx, d, seed, targets, tip_site: int, lo, hi, damping, iters_first: int, iters: int):
    """Joint angles along a tip path, each waypoint warm-started from the last.

    Args:
      mx, d: MJX model and a data buffer (only kinematics is used).
      seed: ``[7]`` rad start posture for the first waypoint.
      targets: ``[T, 3]`` m tip positions.
      tip_site: site id of the pen tip.
      lo, hi: ``[7]`` rad joint limits (``-inf, inf`` for unlimited joints).
      damping: m, least-squares damping.
      iters_first, iters: iterations for waypoint 0 and for each later one.

    Returns:
      ``q [T, 7]`` rad, ``err_mm [T]`` tip error, ``tilt_deg [T]`` pen tilt.
    """

    def solve(q, target, n):
        return jax.lax.fori_loop(
            0, n, lambda _, q: dls_step(mx, d, q, target, tip_site, lo, hi, damping), q
        )

    q0 = solve(seed, targets[0], iters_first)

    def body(q, target):
        q = solve(q, target, iters)
        err, tilt = errors(mx, d, q, target, tip_site)
        return q, (q, err, tilt)

    _, (q, err, tilt) = jax.lax.scan(body, q0, targets)
    return q, err, tilt
