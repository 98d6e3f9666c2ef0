"""End-to-end robot check on small hand-made plans (one compile for the module)."""

import mujoco
import numpy as np
import pytest

import jdraw
from jdraw import robot
from jdraw.robot import scene, verifier

IOU_MIN = 0.9  # acceptance: drawn vs planned
IK_TOL_MM = 1.0  # acceptance: IK error
FK_AGREE_M = 1e-5  # IK solution re-evaluated with C MuJoCo (float32 JAX vs float64 C)


def _plan(strokes_per_image):
    b = len(strokes_per_image)
    return jdraw.Plan(
        strokes=strokes_per_image,
        actions=np.zeros((b, 1, 3), np.int32),
        lengths=np.zeros(b, np.int32),
        truncated=np.zeros(b, bool),
    )


def _square(x0, y0, n):
    corners = np.array([[x0, y0], [x0, y0 + n], [x0 + n, y0 + n], [x0 + n, y0], [x0, y0]], float)
    return jdraw.geometry.polyline_pixels(corners).astype(float)


def _circle(cx, cy, r, k=48):
    th = np.linspace(0, 2 * np.pi, k)
    return np.round(np.stack([cx + r * np.cos(th), cy + r * np.sin(th)], -1))


PLAN = _plan(
    [
        [_square(20, 20, 25), np.array([[30.0, 70.0], [45.0, 85.0]]), np.array([[80.0, 20.0]])],
        [_circle(60, 60, 12), np.array([[10.0, 90.0], [40.0, 90.0]])],
        [],  # nothing to draw
    ]
)


@pytest.fixture(scope="module")
def report():
    return robot.verify(PLAN)


def test_draws_what_was_planned(report):
    np.testing.assert_array_equal(report.planned, jdraw.render(PLAN))
    assert report.reachable.all()
    assert (report.max_ik_error_mm <= IK_TOL_MM).all()
    assert report.within_limits.all()
    assert (report.iou >= IOU_MIN).all(), report.iou
    np.testing.assert_array_equal(report.pen_lifts, report.planned_pen_lifts)
    assert report.drawn.shape == (3, 100, 100) and report.q_ref.shape[-1] == 7
    np.testing.assert_array_equal(report.drawing_time_s > 0, [True, True, False])
    assert not report.drawn[2].any() and report.iou[2] == 1.0


def test_ik_solution_checked_with_c_mujoco(report):
    """The IK joint angles put the C MuJoCo tip on the target (an FK residual)."""
    options = robot.RobotOptions()
    paths = [robot.tip_path(s, options) for s in PLAN.strokes]
    m = scene.load(options)
    d = mujoco.MjData(m)
    for i, p in enumerate(paths):
        for k in np.linspace(0, p.n_steps - 1, 25).astype(int):
            d.qpos[:] = 0
            d.qpos[: scene.N_ARM] = report.q_ref[i, k]
            mujoco.mj_kinematics(m, d)
            err = np.linalg.norm(d.site("tip").xpos - p.targets[k])
            assert err <= FK_AGREE_M + report.max_ik_error_mm[i] / 1000, (i, k, err)


def test_sheet_out_of_reach_is_reported(report):
    n_compiled = verifier._run._cache_size()
    far = robot.verify(PLAN, sheet_center=(1.3, 0.0))
    assert verifier._run._cache_size() == n_compiled  # moving the sheet does not recompile
    assert (far.max_ik_error_mm[:2] > IK_TOL_MM).all()
    assert not far.reachable[:2].any()
    for off, steps in zip(far.offending[:2], far.offending_steps[:2]):
        assert len(off) == len(steps) > 0
        assert off.shape[1] == 3 and np.isfinite(off).all()


def test_second_call_does_not_recompile(report):
    n_compiled = verifier._run._cache_size()
    again = robot.verify(PLAN)
    assert verifier._run._cache_size() == n_compiled
    np.testing.assert_array_equal(again.drawn, report.drawn)
