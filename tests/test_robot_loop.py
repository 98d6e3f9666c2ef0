"""Faults, looking and the closed drawing loop (one short character, one compile)."""

import dataclasses

import numpy as np
import pytest

import jdraw
from jdraw import geometry
from jdraw.robot import closed_loop, faults, look, redraw, scene, trajectory
from jdraw.robot.options import RobotOptions

POSE_TOL_MM = 0.5  # registered sheet offset vs the simulated one
POSE_TOL_DEG = 0.3
REG_TOL_PX = 0.25  # registration of a synthetic shift and rotation
TOL_PX = 1.2  # the loop's default tolerance (1 mm per canvas pixel)


def _plan(strokes):
    return jdraw.Plan(
        strokes=[strokes],
        actions=np.zeros((1, 1, 3), np.int32),
        lengths=np.zeros(1, np.int32),
        truncated=np.zeros(1, bool),
    )


# A short character: a cross and a slash (about 2.3 s of motion: one 256-step shape).
PLAN = _plan(
    [
        np.array([[25.0, 30.0], [75.0, 30.0]]),
        np.array([[50.0, 15.0], [50.0, 80.0]]),
        np.array([[30.0, 60.0], [70.0, 75.0]]),
    ]
)
FAULTY = faults.Faults(
    sheet_offset_mm=(3.0, -2.0),
    sheet_rotation_deg=2.0,
    pen_skip_per_mm=0.03,
    early_lift_mm=3.0,
    seed=1,
)


def test_parse_and_presets():
    f = faults.Faults.parse("moderate,seed=3,sheet_offset_mm=1:2")
    assert f.seed == 3 and f.sheet_offset_mm == (1.0, 2.0)
    assert f.early_lift_mm == faults.MODERATE.early_lift_mm
    assert faults.Faults.parse("") == faults.Faults() and not faults.Faults().any
    assert faults.only("early lift").active() == {"early_lift_mm": 3.0}
    with pytest.raises(ValueError, match="unknown fault"):
        faults.Faults.parse("pen_wobble=1")
    with pytest.raises(ValueError, match="bad value"):
        faults.Faults.parse("sheet_offset_mm=1")


def test_pen_gate_cuts_early_lift_and_skips_in_mm():
    """A 40 mm stroke loses exactly its last early_lift_mm; skips eat skip_length_mm."""
    opts = RobotOptions()
    p = trajectory.tip_path([np.array([[10.0, 50.0], [50.0, 50.0]])], opts)
    mm = np.ones(2)
    step = np.zeros(p.n_steps)
    step[1:] = np.linalg.norm(np.diff(p.canvas, axis=0), axis=1)
    rng = np.random.default_rng(0)
    ok = faults.pen_gate(p.canvas, p.down, mm, faults.Faults(early_lift_mm=5.0), rng)
    lost = float(np.sum(step * (p.down & ~ok)))
    assert abs(lost - 5.0) <= 0.6 + 1e-9  # one 10 ms step at 60 mm/s
    assert faults.pen_gate(p.canvas, p.down, mm, faults.Faults(), rng).all()
    ok = faults.pen_gate(p.canvas, p.down, mm, faults.Faults(pen_skip_per_mm=10.0), rng)
    assert (p.down & ~ok).sum() > 0.5 * p.down.sum()  # near-certain skips, back to back


def test_register_recovers_shift_and_rotation():
    target = geometry.render_strokes(
        [
            np.array([[20.0, 20.0], [80.0, 25.0], [70.0, 80.0]]),
            np.array([[30.0, 60.0], [55.0, 40.0]]),
        ]
    )
    th = np.radians(2.0)
    a_true = np.array([[np.cos(th), -np.sin(th), 3.0], [np.sin(th), np.cos(th), -2.0]])
    c = np.array([49.5, 49.5])
    a_true[:, 2] += c - a_true[:, :2] @ c  # rotate about the centre, then shift
    pts = np.argwhere(target)[:, ::-1]
    dense = np.concatenate([pts + d for d in np.linspace(-0.4, 0.4, 5)[:, None]])
    moved = np.floor(look.apply_affine(a_true, dense) + 0.5).astype(int)
    seen = np.zeros_like(target)
    seen[moved[:, 1], moved[:, 0]] = True
    seen = look.see(look.ink_photo(seen))
    a = look.register(target, seen)
    err = np.abs(look.apply_affine(a, pts) - look.apply_affine(a_true, pts)).max()
    assert err <= REG_TOL_PX * 4, (err, a)  # seen is re-thinned: about a pixel at worst
    assert abs(np.degrees(np.arctan2(a[1, 0], a[0, 0])) - 2.0) <= POSE_TOL_DEG


def test_clip_never_leaves_allowed_pixels():
    allowed = geometry.render_strokes([np.array([[10.0, 10.0], [60.0, 10.0]])])
    strokes = redraw.clip_to([np.array([[0.0, 10.0], [90.0, 10.0], [90.0, 50.0]])], allowed)
    drawn = geometry.render_strokes(strokes)
    assert drawn.any() and not (drawn & ~allowed).any()


def test_render_look_finds_the_ink_on_a_moved_sheet():
    if not look.can_render():
        pytest.skip("no OpenGL context (set MUJOCO_GL=egl where EGL exists); ink picture used")
    opts = RobotOptions()
    real = faults.true_options(opts, FAULTY)
    drawn = jdraw.render(PLAN)[0]
    photo, source = look.photograph(drawn, real, opts, "render")
    assert source == "render"
    seen = look.see(photo)
    # the paper is cut out of the picture: the ink is where it is on the paper
    assert look.distance_to(seen)[drawn].max() <= TOL_PX
    assert look.distance_to(drawn)[seen].max() <= TOL_PX


@pytest.fixture(scope="module")
def clean():
    return closed_loop.draw_closed_loop(PLAN, faults.Faults(), rounds=2, look_with="ink")


@pytest.fixture(scope="module")
def faulty():
    return closed_loop.draw_closed_loop(PLAN, FAULTY, rounds=2, look_with="ink")


def test_no_faults_no_redraw(clean):
    assert clean.rounds == 1 and len(clean.redrawn[0]) == 1
    assert not clean.missing.any()
    assert clean.iou[0, 0] >= 0.95
    assert clean.reports[0].faults == faults.Faults()
    np.testing.assert_allclose(clean.offset_mm[0], 0.0, atol=POSE_TOL_MM)


def test_loop_redraws_and_never_lowers_iou(faulty):
    iou = faulty.iou[0]
    assert faulty.rounds >= 2 and sum(len(s) for s in faulty.redrawn[0][1:]) > 0
    assert np.all(np.diff(iou) >= 0), iou
    assert iou[-1] > iou[0], iou
    rep = faulty.reports[0]
    assert rep.faults == FAULTY and rep.fault_log[0]["dry_mm"] > 0


def test_loop_never_draws_where_the_target_has_no_ink(faulty):
    target = faulty.target[0]
    for strokes in faulty.redrawn[0][1:]:
        assert not (geometry.render_strokes(strokes) & ~target).any()
    # and on the paper, new ink lands near the target's registered place
    a = faulty.transform[0, -1]
    inv = np.vstack([a, [0, 0, 1]])
    inv = np.linalg.inv(inv)[:2]
    for r in range(1, faulty.rounds):
        new = faulty.sheets[0, r] & ~faulty.sheets[0, r - 1]
        pts = look.apply_affine(inv, np.argwhere(new)[:, ::-1])
        assert (look.sample(look.distance_to(target), pts) <= TOL_PX).all()


def test_registration_finds_the_sheet_offset(faulty):
    np.testing.assert_allclose(faulty.offset_mm[0], FAULTY.sheet_offset_mm, atol=POSE_TOL_MM)
    assert abs(faulty.rotation_deg[0] - FAULTY.sheet_rotation_deg) <= POSE_TOL_DEG


def test_faults_off_draws_like_verify(clean):
    plain = jdraw.robot.verify(PLAN)
    np.testing.assert_array_equal(plain.drawn, clean.reports[0].drawn)
    assert dataclasses.asdict(plain.faults) == dataclasses.asdict(faults.Faults())
    assert scene.N_ARM == len(plain.fault_log[0]["joint_bias_rad"])


def test_cli_rejects_bad_faults(capsys):
    from jdraw import cli

    assert cli.main(["draw", "examples/images/hello.jpg", "--robot", "--faults", "pen=1"]) == 2
    assert "unknown fault" in capsys.readouterr().err
