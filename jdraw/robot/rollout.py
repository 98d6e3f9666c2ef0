"""MJX rollout of the arm tracking joint targets, with ink where the nib touches paper."""

from __future__ import annotations

import jax
import jax.numpy as jnp
from mujoco import mjx

from jdraw import geometry
from jdraw.robot.scene import N_ARM


def contact_point(d: mjx.Data, tip_geom: int, paper_geom: int, sheet: jax.Array):
    """Whether the nib touches the paper, and where on the canvas.

    Ink is decided by the collision detector (penetration of the nib sphere into
    the paper box), not by the tip's height.

    Args:
      d: MJX data after a step.
      tip_geom, paper_geom: geom ids.
      sheet: ``[8]`` sheet parameters from :func:`jdraw.robot.scene.sheet_params`.

    Returns:
      ``touch`` bool, ``xy`` ``[2]`` float canvas coordinates of the contact
      point (pixel ``(i, j)`` centred on ``(i, j)``).
    """
    con = d._impl.contact
    pair = ((con.geom[:, 0] == tip_geom) & (con.geom[:, 1] == paper_geom)) | (
        (con.geom[:, 0] == paper_geom) & (con.geom[:, 1] == tip_geom)
    )
    dist = jnp.where(pair, con.dist, jnp.inf)
    i = jnp.argmin(dist)
    rel = con.pos[i, :2] - sheet[:2]
    c, s = sheet[2], sheet[3]
    u = c * rel[0] + s * rel[1]
    v = -s * rel[0] + c * rel[1]
    xy = jnp.stack([(u + sheet[4]) / sheet[6], (sheet[5] - v) / sheet[7]]) - 0.5
    return dist[i] < 0, xy


def rollout(
    mx: mjx.Model,
    d0: mjx.Data,
    ctrl: jax.Array,
    valid: jax.Array,
    n_sub: int,
    tip_geom: int,
    paper_geom: int,
    tip_site: int,
    sheet: jax.Array,
    nib_radius: jax.Array,
):
    """Simulates one image's motion.

    Joint targets are held by the arm's position (PD) actuators; between control
    steps the target is interpolated linearly over the ``n_sub`` physics steps.

    Args:
      mx: MJX model.
      d0: initial data (arm at ``ctrl[0]``, at rest).
      ctrl: ``[T, 7]`` rad actuator targets, one per control step.
      valid: ``[T]`` bool, steps that belong to the plan (ink after is ignored).
      n_sub: physics steps per control step.
      tip_geom, paper_geom, tip_site: ids.
      sheet: ``[8]`` sheet parameters.
      nib_radius: pixels, half the width of the line the nib lays.

    Returns:
      dict with ``qpos [T, 7]`` rad, ``tip [T, 3]`` m (nib site), ``touch [T]``
      bool (contact at any physics step of the control step), ``spring [T]`` m
      (tip compression, negative when pushed in), ``ink [T, n_sub]`` bool and
      ``ink_xy [T, n_sub, 2]`` canvas contact points at every physics step, and
      ``drawn`` bool ``[100, 100]``: pixels whose centre the nib passed within
      ``nib_radius`` of, and ``drawn_cover``: every pixel a contact point fell in.
    """
    nxt = jnp.concatenate([ctrl[1:], ctrl[-1:]])
    alphas = (jnp.arange(n_sub, dtype=ctrl.dtype) + 1) / n_sub

    def control_step(d, x):
        c0, c1 = x

        def physics_step(d, a):
            d = mjx.step(mx, d.replace(ctrl=c0 + a * (c1 - c0)))
            touch, xy = contact_point(d, tip_geom, paper_geom, sheet)
            return d, (touch, xy)

        d, (touch, xy) = jax.lax.scan(physics_step, d, alphas)
        out = dict(qpos=d.qpos[:N_ARM], tip=d.site_xpos[tip_site], spring=d.qpos[N_ARM])
        return d, (out, touch, xy)

    _, (out, touch, xy) = jax.lax.scan(control_step, d0, (ctrl, nxt))
    ink = touch & valid[:, None]
    out["touch"] = jnp.any(touch, axis=1)
    out["drawn"] = _stamp(ink, xy, nib_radius)
    out["drawn_cover"] = _stamp(ink, xy, None)
    return out


def _stamp(ink: jax.Array, xy: jax.Array, radius) -> jax.Array:
    """Canvas ``bool [100, 100]`` of pixels inked by contact points ``xy [..., 2]``.

    With ``radius``, a pixel is inked when a contact point lies within it of the
    pixel centre (a round nib swept along the dense trace); with ``None``, the
    pixel containing each contact point is inked.
    """
    base = jnp.floor(xy + 0.5).astype(jnp.int32)[..., None, :]
    if radius is None:
        cells, hit = base, ink[..., None]
    else:
        off = jnp.stack(jnp.meshgrid(jnp.arange(-1, 2), jnp.arange(-1, 2)), -1).reshape(-1, 2)
        cells = base + off
        near = jnp.sum((cells - xy[..., None, :]) ** 2, axis=-1) <= radius**2
        hit = ink[..., None] & near
    inside = jnp.all((cells >= 0) & (cells < geometry.CANVAS), axis=-1)
    cells = jnp.clip(cells, 0, geometry.CANVAS - 1)
    canvas = jnp.zeros((geometry.CANVAS, geometry.CANVAS), bool)
    return canvas.at[cells[..., 1], cells[..., 0]].max(hit & inside)
