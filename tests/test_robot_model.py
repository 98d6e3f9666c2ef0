"""The arm model: Gen3 kinematics, sheet geometry, and MJX against MuJoCo C."""

import jax
import jax.numpy as jnp
import mujoco
import numpy as np
import pytest
from mujoco import mjx

from jdraw import robot
from jdraw.robot import scene, verifier

FK_TOL_M = 1e-6  # MJCF (angles written to 8 digits) vs the published joint frames
MJX_QPOS_TOL = 1e-4  # rad, after 100 steps (float32 MJX vs float64 C)
MJX_TIP_TOL_M = 1e-5  # nib position after 100 steps
MJX_SPRING_TOL_M = 1e-5  # compression of the spring-loaded tip
N_STEPS = 100

# Kinova Gen3 7-DoF joint frames (xyz m, rpy rad) from the public kinematic
# description, then the tool frame and this package's 0.12 m pen.
_FRAMES = [
    ((0, 0, 0.15643), (np.pi, 0, 0)),
    ((0, 0.005375, -0.12838), (np.pi / 2, 0, 0)),
    ((0, -0.21038, -0.006375), (-np.pi / 2, 0, 0)),
    ((0, 0.006375, -0.21038), (np.pi / 2, 0, 0)),
    ((0, -0.20843, -0.006375), (-np.pi / 2, 0, 0)),
    ((0, 0.00017505, -0.10593), (np.pi / 2, 0, 0)),
    ((0, -0.10593, -0.00017505), (-np.pi / 2, 0, 0)),
]
_TOOL = ((0, 0, -0.061525), (np.pi, 0, 0))
_PEN = 0.12 + 0.0008  # pen length to the tip body, plus the nib ball's radius


def _rot(rpy):
    r, p, y = rpy
    rx = np.array([[1, 0, 0], [0, np.cos(r), -np.sin(r)], [0, np.sin(r), np.cos(r)]])
    ry = np.array([[np.cos(p), 0, np.sin(p)], [0, 1, 0], [-np.sin(p), 0, np.cos(p)]])
    rz = np.array([[np.cos(y), -np.sin(y), 0], [np.sin(y), np.cos(y), 0], [0, 0, 1]])
    return rz @ ry @ rx


def _reference_tip(q):
    t = np.eye(4)
    for (xyz, rpy), qi in zip(_FRAMES, q):
        step = np.eye(4)
        step[:3, :3] = _rot(rpy) @ _rot((0, 0, qi))
        step[:3, 3] = xyz
        t = t @ step
    tool = np.eye(4)
    tool[:3, :3], tool[:3, 3] = _rot(_TOOL[1]), _TOOL[0]
    t = t @ tool
    return t[:3, :3] @ np.array([0, 0, _PEN]) + t[:3, 3]


def test_kinematics_match_gen3_frames():
    m = scene.load()
    d = mujoco.MjData(m)
    rng = np.random.default_rng(0)
    for _ in range(20):
        q = rng.uniform(-2.2, 2.2, 7)
        d.qpos[:7], d.qpos[7] = q, 0
        mujoco.mj_kinematics(m, d)
        np.testing.assert_allclose(d.site("tip").xpos, _reference_tip(q), atol=FK_TOL_M)


def test_sheet_mapping_round_trip():
    opts = robot.RobotOptions(sheet_center=(0.5, 0.1), sheet_yaw=0.3, sheet_size_mm=(80, 120))
    pts = np.array([[0, 0], [99, 0], [0, 99], [37.5, 60.25]])
    xyz = scene.canvas_to_world(pts, 2.0, opts)
    np.testing.assert_allclose(scene.world_to_canvas(xyz, opts), pts, atol=1e-9)
    np.testing.assert_allclose(xyz[:, 2], scene.PAPER_THICKNESS + 0.002)
    # pixel (0, 0) and (99, 0) are 99 pixels of 0.8 mm apart
    np.testing.assert_allclose(np.linalg.norm(xyz[1] - xyz[0]), 0.0792, atol=1e-9)


def _pressed_state(m):
    """Joint angles putting the nib 0.5 mm into the paper at the sheet centre (C DLS)."""
    d = mujoco.MjData(m)
    d.qpos[:7] = scene.SEED
    target = scene.canvas_to_world([[49.5, 49.5]], -0.5, robot.RobotOptions())[0]
    jac = np.zeros((3, m.nv))
    for _ in range(100):
        mujoco.mj_kinematics(m, d)
        mujoco.mj_comPos(m, d)
        mujoco.mj_jacSite(m, d, jac, None, m.site("tip").id)
        j = jac[:, :7]
        d.qpos[:7] += j.T @ np.linalg.solve(j @ j.T + 1e-6 * np.eye(3), target - d.site("tip").xpos)
    return d.qpos.copy()


@pytest.fixture(scope="module")
def pressed():
    m = scene.load()
    qpos = _pressed_state(m)
    ctrl = qpos[:7] + np.array([0.004, 0, 0, 0, 0, 0, 0])  # swing the base: drag the pen ~2 mm
    return m, qpos, ctrl


def test_mjx_matches_mujoco_c(pressed):
    m, qpos, ctrl = pressed
    d = mujoco.MjData(m)
    d.qpos[:], d.ctrl[:] = qpos, ctrl
    touched = []
    for _ in range(N_STEPS):
        mujoco.mj_step(m, d)
        touched.append(
            any(
                {c.geom1, c.geom2} == {m.geom("pen_tip").id, m.geom("paper").id} and c.dist < 0
                for c in d.contact[: d.ncon]
            )
        )
    assert all(touched)  # the pen really presses on the paper
    assert d.qpos[7] < -1e-4  # and the spring is compressed

    mx = mjx.put_model(m)
    dx = mjx.make_data(mx).replace(
        qpos=jnp.asarray(qpos, jnp.float32), ctrl=jnp.asarray(ctrl, jnp.float32)
    )
    step = jax.jit(
        lambda dx: jax.lax.fori_loop(0, N_STEPS, lambda _, x: mjx.step(mx, x), dx),
        compiler_options=verifier.COMPILER_OPTIONS,
    )
    dx = step(dx)
    np.testing.assert_allclose(np.asarray(dx.qpos[:7]), d.qpos[:7], atol=MJX_QPOS_TOL)
    np.testing.assert_allclose(np.asarray(dx.site_xpos[0]), d.site("tip").xpos, atol=MJX_TIP_TOL_M)
    np.testing.assert_allclose(float(dx.qpos[7]), d.qpos[7], atol=MJX_SPRING_TOL_M)


def test_load_model_is_a_deprecated_name_of_load_scene():
    with pytest.warns(DeprecationWarning, match="load_scene"):
        old = robot.load_model()
    new = robot.load_scene()
    assert (old.nq, old.ngeom, old.nbody) == (new.nq, new.ngeom, new.nbody)
    np.testing.assert_array_equal(old.geom_size, new.geom_size)
