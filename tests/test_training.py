"""Training with the tiny config: the loss falls, resuming equals not stopping, data parallel."""

import json
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from configs import tiny
from jdraw.model import bundle, checkpoints
from jdraw.train import loop as training
from jdraw.train.step import create_state, model_of

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _cfg(steps):
    c = tiny.get_config()
    c.train.num_steps = steps
    c.train.checkpoint_every = 100
    c.train.log_every = 1
    return c


@pytest.fixture(scope="module")
def straight_run(tmp_path_factory):
    wd = tmp_path_factory.mktemp("straight")
    training.train(_cfg(16), wd, progress=False)
    return wd


def _final_arrays(wd):
    return bundle.state_arrays(bundle.load(wd / "bundle")[0])


def _assert_trained(wd, arrays: dict):
    """``arrays`` are the run's trained weights: its last checkpoint's, not the initial ones."""
    restored = bundle.state_arrays(checkpoints.restore(wd).model)
    assert arrays.keys() == restored.keys()
    for k in arrays:
        np.testing.assert_array_equal(arrays[k], restored[k], err_msg=k)
    g, _, st = create_state(checkpoints.read_config(wd))
    initial = bundle.state_arrays(model_of(g, st))
    still = [k for k in initial if np.array_equal(initial[k], arrays[k])]
    assert not still, f"arrays left at their initial values: {still}"


def test_loss_falls(straight_run):
    logs = [json.loads(x) for x in (straight_run / "metrics.jsonl").read_text().splitlines()]
    losses = [r["loss"] for r in logs if "loss" in r]
    assert len(losses) == 16
    assert np.mean(losses[-4:]) < 0.8 * np.mean(losses[:4]), losses


def test_resume_equals_uninterrupted(straight_run, tmp_path):
    cfg = _cfg(16)
    r1 = training.train(cfg, tmp_path, progress=False, stop_after=7)
    assert r1["step"] == 7 and not r1["done"]
    assert not (tmp_path / "bundle").exists()  # written when the run is done
    _plan_reads_the_workdir(tmp_path)
    r2 = training.train(cfg, tmp_path, progress=False)
    assert r2["step"] == 16 and r2["done"]
    a, b = _final_arrays(straight_run), _final_arrays(tmp_path)
    _assert_trained(straight_run, a)
    _assert_trained(tmp_path, b)
    assert a.keys() == b.keys()
    for k in a:
        np.testing.assert_allclose(a[k], b[k], rtol=0, atol=1e-6, err_msg=k)
    assert (
        r2["strokes_seen"]
        == json.loads((straight_run / "metrics.jsonl").read_text().splitlines()[-2])["strokes_seen"]
    )


def _plan_reads_the_workdir(wd):
    """``plan(checkpoint=workdir)`` plans with the latest checkpoint and writes nothing there."""
    import jdraw

    before = {p: p.stat().st_mtime_ns for p in wd.rglob("*")}
    img = np.zeros((100, 100), bool)
    img[40, 20:70] = True
    img[30:60, 45] = True
    p = jdraw.plan(img, checkpoint=wd, max_steps=100)
    assert {p: p.stat().st_mtime_ns for p in wd.rglob("*")} == before
    _assert_trained(wd, bundle.state_arrays(jdraw.load_model(wd)))
    q = jdraw.plan(img, checkpoint=jdraw.export(wd, wd.parent / f"{wd.name}_bundle"), max_steps=100)
    np.testing.assert_array_equal(p.actions, q.actions)


def test_export_bundle_loads_and_plans(straight_run, tmp_path):
    import jdraw

    out = jdraw.export(straight_run, tmp_path / "b")
    _assert_trained(straight_run, bundle.state_arrays(bundle.load(out)[0]))
    meta = json.loads((out / "bundle.json").read_text())
    assert meta["format_version"] == bundle.FORMAT_VERSION and meta["model"]["hidden"] == 16
    img = np.zeros((100, 100), bool)
    img[50, 20:80] = True
    p = jdraw.plan(img, checkpoint=out, max_steps=200)
    assert jdraw.pixel_accuracy(img, jdraw.render(p)[0]) == 1.0


def test_two_devices_step_equals_one_device():
    """One training step (gradients, batch-norm statistics) on a 2-device mesh equals one device."""
    script = textwrap.dedent(
        """
        import numpy as np, jax, optax
        from jax.sharding import Mesh, NamedSharding, PartitionSpec as P
        from configs import tiny
        from jdraw.data import kanji
        from jdraw.train import feed
        from jdraw.train.step import create_state, make_step
        assert len(jax.devices()) == 2
        cfg = tiny.get_config()
        ks = kanji.load(progress=False)
        pool = kanji.split_indices(ks, "train")
        batch, _ = feed.make_batch(ks, pool, cfg, 0)
        out = []
        for devs in (jax.devices()[:1], jax.devices()):
            # Adam's first step is sign(g): ill-conditioned to compare
            g, tx, state = create_state(cfg, tx=optax.sgd(0.1))
            mesh = Mesh(np.asarray(devs), ("data",))
            state = jax.device_put(state, NamedSharding(mesh, P()))
            step = make_step(g, tx, 1.0)
            b = feed.shard_batch(batch, mesh)
            if len(devs) == 2:
                assert len(b["local"]["target"].sharding.device_set) == 2
            state, logs = step(state, b)
            leaves = jax.tree.leaves(state.params) + jax.tree.leaves(state.rest)
            out.append((leaves, float(logs["loss"])))
        (p1, l1), (p2, l2) = out
        err = max(float(np.max(np.abs(np.asarray(a) - np.asarray(b)))) for a, b in zip(p1, p2))
        print("loss", l1, l2, "max param diff", err)
        assert abs(l1 - l2) < 1e-4 and err < 1e-5, (l1, l2, err)
        """
    )
    env = dict(
        os.environ, XLA_FLAGS="--xla_force_host_platform_device_count=2", JAX_PLATFORMS="cpu"
    )
    r = subprocess.run(
        [sys.executable, "-c", script], cwd=ROOT, env=env, capture_output=True, text=True
    )
    assert r.returncode == 0, r.stdout + r.stderr[-3000:]


_KILLER = textwrap.dedent(
    """
    import os, signal, sys
    from configs import tiny
    from jdraw.train import loop as training
    from jdraw.train import records

    mode, n, workdir = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    cfg = tiny.get_config()
    cfg.train.update(num_steps=16, checkpoint_every=5, log_every=1)
    if mode == "step":  # SIGKILL as the n-th step of this process starts
        make = training.make_step

        def make_step(*a, **k):
            step, calls = make(*a, **k), [0]

            def killing_step(*b):
                calls[0] += 1
                if calls[0] == n:
                    os.kill(os.getpid(), signal.SIGKILL)
                return step(*b)

            return killing_step

        training.make_step = make_step
    else:  # SIGKILL while the checkpoint of step n is being written (Orbax saves async)
        save = records.save

        def killing_save(mgr, step, *a):
            save(mgr, step, *a)
            if step == n:
                os.kill(os.getpid(), signal.SIGKILL)

        records.save = killing_save
    training.train(cfg, workdir, progress=False)
    """
)


def test_crash_recovery_logs_each_step_once_and_matches(straight_run, tmp_path):
    """kill -9 at a step and during a checkpoint save; the resumed run equals a straight one."""
    env = dict(os.environ, JAX_PLATFORMS="cpu")
    for mode, n in (("step", 13), ("save", 15)):
        r = subprocess.run(
            [sys.executable, "-c", _KILLER, mode, str(n), str(tmp_path)],
            cwd=ROOT,
            env=env,
            capture_output=True,
            text=True,
        )
        assert r.returncode == -9, r.stderr[-3000:]
    logged = [json.loads(x)["step"] for x in (tmp_path / "metrics.jsonl").read_text().splitlines()]
    assert logged == list(range(1, 16))  # killed after logging 15, before its save finished
    cfg = _cfg(16)
    cfg.train.checkpoint_every = 5
    r = training.train(cfg, tmp_path, progress=False)
    assert r["done"]
    recs = [json.loads(x) for x in (tmp_path / "metrics.jsonl").read_text().splitlines()]
    assert [x["step"] for x in recs if "loss" in x] == list(range(1, 17))
    a, b = _final_arrays(straight_run), _final_arrays(tmp_path)
    for k in a:
        np.testing.assert_allclose(a[k], b[k], rtol=0, atol=1e-6, err_msg=k)


def test_export_keeps_the_training_config(straight_run, tmp_path):
    import jdraw

    out = jdraw.export(straight_run, tmp_path / "b")
    want = json.loads((straight_run / "config.json").read_text())
    assert json.loads((out / "training_config.json").read_text()) == want
    again = jdraw.export(out, tmp_path / "c")  # copying a bundle keeps it too
    assert json.loads((again / "training_config.json").read_text()) == want


def test_cosine_decay_lowers_the_step_size_to_its_final_fraction():
    import jax
    import jax.numpy as jnp

    from jdraw.train.step import create_state

    cfg = tiny.get_config()
    cfg.train.update(learning_rate=1e-2, final_lr_fraction=0.1, num_steps=10)
    _, tx, _ = create_state(cfg)
    p = {"w": jnp.zeros(3)}
    g = {"w": jnp.ones(3)}  # a constant gradient: Adam's step is the learning rate
    opt = tx.init(p)
    sizes = []
    for _ in range(11):
        u, opt = tx.update(g, opt, p)
        sizes.append(float(jnp.abs(jax.tree.leaves(u)[0]).max()))
    np.testing.assert_allclose(sizes[0], 1e-2, rtol=1e-3)
    np.testing.assert_allclose(sizes[10], 1e-3, rtol=1e-3)  # decayed to a tenth
    assert sizes[5] < sizes[0]
