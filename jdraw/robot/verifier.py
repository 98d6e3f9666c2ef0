"""``verify``: plan -> IK -> MJX rollout -> what the pen actually drew."""

from __future__ import annotations

import dataclasses
import functools
import time

import jax
import jax.numpy as jnp
import mujoco
import numpy as np
from mujoco import mjx

from jdraw import plans as types
from jdraw.evaluation import metrics
from jdraw.robot import faults as F
from jdraw.robot import ik, rollout, scene, trajectory
from jdraw.robot.options import RobotOptions


@dataclasses.dataclass
class Report:
    """Per-image outcome of drawing a plan with the simulated arm.

    Attributes:
      reachable: ``[B]`` bool, every waypoint solved within ``ik_tol_mm`` and
        ``ik_tol_deg`` and inside the joint limits.
      max_ik_error_mm: ``[B]`` worst tip error of the IK solution over the path.
      max_tilt_deg: ``[B]`` worst pen tilt from vertical of the IK solution.
      within_limits: ``[B]`` bool, all IK joint angles inside the limits.
      offending: per image, ``[k, 3]`` (x, y canvas, height mm) waypoints whose
        IK missed the tolerances (empty when reachable).
      offending_steps: per image, ``[k]`` int control-step indices of those.
      drawn: ``bool [B, 100, 100]`` pixels whose centre the simulated nib
        passed within ``nib_radius_px`` of while touching the paper.
      planned: ``bool [B, 100, 100]`` ``jdraw.render(plan)``.
      iou: ``[B]`` intersection over union of ``drawn`` and ``planned`` (1 when
        both are empty).
      drawn_cover: ``bool [B, 100, 100]`` every pixel any contact point fell
        in (a stricter, supercover rasterisation of the same trace).
      iou_cover: ``[B]`` IoU of ``drawn_cover`` and ``planned``.
      pen_lifts: ``[B]`` int, times the nib left the paper in the rollout.
      planned_pen_lifts: ``[B]`` int, strokes in the plan (each ends in a lift).
      drawing_time_s: ``[B]`` s from the first descent to the end of the last lift.
      max_track_error_mm: ``[B]`` worst in-plane distance between the simulated
        nib and its target while the pen is meant to be down.
      t: ``[T]`` s time of each control step.
      valid: ``[B, T]`` bool, steps inside each image's motion.
      q_ref: ``[B, T, 7]`` rad IK joint trajectory (the actuator targets).
      q_sim: ``[B, T, 7]`` rad simulated joint angles.
      tip: ``[B, T, 3]`` m simulated nib position.
      touch: ``[B, T]`` bool nib-paper contact.
      wall_time_s: s spent in IK and simulation (compilation included on the
        first call of a shape).
      faults: the :class:`jdraw.robot.faults.Faults` the arm drew under (all
        off by default); ``drawn`` is in the frame of the real sheet.
      fault_log: per image, what the faults did (joint bias drawn, mm of ink
        lost to skips and early lifts).
    """

    reachable: np.ndarray
    max_ik_error_mm: np.ndarray
    max_tilt_deg: np.ndarray
    within_limits: np.ndarray
    offending: list[np.ndarray]
    offending_steps: list[np.ndarray]
    drawn: np.ndarray
    planned: np.ndarray
    iou: np.ndarray
    drawn_cover: np.ndarray
    iou_cover: np.ndarray
    pen_lifts: np.ndarray
    planned_pen_lifts: np.ndarray
    drawing_time_s: np.ndarray
    max_track_error_mm: np.ndarray
    t: np.ndarray
    valid: np.ndarray
    q_ref: np.ndarray
    q_sim: np.ndarray
    tip: np.ndarray
    touch: np.ndarray
    wall_time_s: float
    faults: F.Faults = dataclasses.field(default_factory=F.Faults)
    fault_log: list = dataclasses.field(default_factory=list)


@dataclasses.dataclass(frozen=True)
class Arm:
    """A compiled arm for one sheet placement (MuJoCo C model, MJX model, ids)."""

    m: mujoco.MjModel
    mx: mjx.Model
    d: mjx.Data
    ids: dict
    lo: np.ndarray
    hi: np.ndarray
    ff_gain: np.ndarray
    n_sub: int


@functools.lru_cache(maxsize=8)
def arm(options: RobotOptions | None = None) -> Arm:
    """Loads and uploads the arm for ``options``' sheet placement (cached)."""
    options = options or RobotOptions()
    m = scene.load(options)
    mx = mjx.put_model(m)
    d = mjx.make_data(mx)
    lim = m.jnt_limited[: scene.N_ARM].astype(bool)
    lo = np.where(lim, m.jnt_range[: scene.N_ARM, 0], -np.inf).astype(np.float32)
    hi = np.where(lim, m.jnt_range[: scene.N_ARM, 1], np.inf).astype(np.float32)
    # Position actuators give kp (q* - q) - kv qdot; shifting the target by
    # (kv / kp) qdot_ref turns the damping into velocity tracking.
    kp, kv = m.actuator_gainprm[:, 0], -m.actuator_biasprm[:, 2]
    n_sub = int(round(options.control_dt / m.opt.timestep))
    if not np.isclose(n_sub * m.opt.timestep, options.control_dt):
        raise ValueError(f"control_dt must be a multiple of the {m.opt.timestep} s timestep")
    return Arm(m, mx, d, scene.ids(m), lo, hi, (kv / kp).astype(np.float32), n_sub)


# XLA's newer CPU fusion emitters make MJX kinematics ~100x slower on CPU
# (80 ms vs 0.4 ms per call measured with jaxlib 0.10.2); the classic emitters
# are used for the robot code only.
COMPILER_OPTIONS = {"xla_cpu_use_fusion_emitters": False}


@functools.partial(
    jax.jit,
    static_argnames=("n_sub", "iters_first", "iters", "ids_key"),
    compiler_options=COMPILER_OPTIONS,  # a CPU flag; other backends ignore it
)
def _run(
    mx,
    d,
    seed,
    targets,
    valid,
    ctrl_offset,
    pen_ok,
    sheet,
    lo,
    hi,
    damping,
    ff_gain,
    dt,
    nib,
    *,
    n_sub,
    iters_first,
    iters,
    ids_key,
):
    tip_site, tip_geom, paper_geom = ids_key

    def one(targets, valid, ctrl_offset, pen_ok):
        q, err, tilt = ik.solve_path(
            mx, d, seed, targets, tip_site, lo, hi, damping, iters_first, iters
        )
        qd = (jnp.concatenate([q[1:], q[-1:]]) - jnp.concatenate([q[:1], q[:-1]])) / (2 * dt)
        qd = jnp.where(valid[:, None], qd, 0.0)
        # Joint faults move the servo targets; the arm starts at rest on the first.
        ctrl = q + ff_gain * qd + ctrl_offset
        q0 = q[0] + ctrl_offset[0]
        qpos0 = jnp.concatenate([q0, jnp.zeros(mx.nq - scene.N_ARM, q.dtype)])
        d0 = d.replace(qpos=qpos0, qvel=jnp.zeros_like(d.qvel), ctrl=q0)
        out = rollout.rollout(
            mx, d0, ctrl, valid & pen_ok, n_sub, tip_geom, paper_geom, tip_site, sheet, nib
        )
        out.update(q_ref=q, err=err, tilt=tilt)
        return out

    return jax.vmap(one)(targets, valid, ctrl_offset, pen_ok)


def _iou(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``[B]`` pixel IoU of image pairs ``a[i]``, ``b[i]``."""
    return np.array([metrics.pixel_accuracy(x, y) for x, y in zip(a, b)], np.float64)


def verify(
    plan: types.Plan,
    options: RobotOptions | None = None,
    *,
    faults: F.Faults | None = None,
    pass_index: int = 0,
    **overrides,
) -> Report:
    """Draws each image of ``plan`` with the simulated arm and compares with the plan.

    Args:
      plan: a batch of plans; only ``plan.strokes`` is used.
      options: a :class:`RobotOptions`; keyword ``overrides`` replace its
        fields, e.g. ``verify(plan, sheet_center=(0.5, 0.1), draw_speed_mm_s=40)``.
        With ``faults``, this is where the planner *believes* the sheet is.
      faults: a :class:`jdraw.robot.faults.Faults` (default: none); the arm is
        commanded for ``options`` and simulated with the real sheet and errors.
      pass_index: the drawing pass on this sheet (new joint noise and skips).

    Returns:
      A :class:`Report` with ``[B]`` leading dimensions.
    """
    options = dataclasses.replace(options or RobotOptions(), **overrides)
    faults = faults or F.Faults()
    paths = [trajectory.tip_path(s, options) for s in plan.strokes]
    targets, valid = trajectory.batch(paths, options.pad_steps)
    real, sim_targets, ctrl_offset, pen_ok, log = F.apply(
        paths, targets, options, faults, pass_index
    )
    a = arm(real)
    start = time.perf_counter()
    out = _run(
        a.mx,
        a.d,
        jnp.asarray(scene.SEED),
        jnp.asarray(sim_targets),
        jnp.asarray(valid),
        jnp.asarray(ctrl_offset, jnp.float32),
        jnp.asarray(pen_ok),
        jnp.asarray(scene.sheet_params(real)),
        jnp.asarray(a.lo),
        jnp.asarray(a.hi),
        jnp.float32(options.ik_damping),
        jnp.asarray(a.ff_gain),
        jnp.float32(options.control_dt),
        jnp.float32(options.nib_radius_px),
        n_sub=a.n_sub,
        iters_first=options.ik_iters_first,
        iters=options.ik_iters,
        ids_key=(a.ids["tip_site"], a.ids["tip_geom"], a.ids["paper"]),
    )
    out = jax.tree.map(np.asarray, jax.block_until_ready(out))
    wall = time.perf_counter() - start

    err = np.where(valid, out["err"], 0.0)
    tilt = np.where(valid, out["tilt"], 0.0)
    inside = np.all((out["q_ref"] >= a.lo - 1e-6) & (out["q_ref"] <= a.hi + 1e-6), axis=-1)
    ok = (err <= options.ik_tol_mm) & (tilt <= options.ik_tol_deg) & inside
    bad = valid & ~ok
    offending, offending_steps = [], []
    for i, p in enumerate(paths):
        steps = np.flatnonzero(bad[i])
        heights = (targets[i, steps, 2] - scene.PAPER_THICKNESS) * 1000
        offending.append(
            np.concatenate([p.canvas[steps], heights[:, None]], -1)
            if len(steps)
            else np.zeros((0, 3))
        )
        offending_steps.append(steps)

    touch = out["touch"] & valid
    lifts = np.sum(touch[:, :-1] & ~touch[:, 1:], axis=1)
    down = np.stack([np.pad(p.down, (0, valid.shape[1] - p.n_steps)) for p in paths])
    target_xy = targets[..., :2]
    track = np.linalg.norm(out["tip"][..., :2] - target_xy, axis=-1) * 1000
    planned = types.render(plan)
    drawn, cover = out["drawn"], out["drawn_cover"]
    return Report(
        reachable=~np.any(bad, axis=1),
        max_ik_error_mm=err.max(axis=1),
        max_tilt_deg=tilt.max(axis=1),
        within_limits=np.all(inside | ~valid, axis=1),
        offending=offending,
        offending_steps=offending_steps,
        drawn=drawn,
        planned=planned,
        iou=_iou(drawn, planned),
        drawn_cover=cover,
        iou_cover=_iou(cover, planned),
        pen_lifts=lifts.astype(np.int32),
        planned_pen_lifts=np.array([p.n_strokes for p in paths], np.int32),
        drawing_time_s=np.array([p.drawing_time_s for p in paths]),
        max_track_error_mm=np.where(down, track, 0.0).max(axis=1),
        t=np.arange(valid.shape[1]) * options.control_dt,
        valid=valid,
        q_ref=out["q_ref"],
        q_sim=out["qpos"],
        tip=out["tip"],
        touch=touch,
        wall_time_s=wall,
        faults=faults,
        fault_log=log,
    )
