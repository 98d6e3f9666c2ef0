"""The slot planner plans exactly as the old loop does one image at a time."""

import os
import re
import subprocess
import sys
import textwrap

import jax
import numpy as np
import pytest
from flax import nnx
from ml_collections import ConfigDict

import jdraw
from jdraw import state
from jdraw.data import demos as demo
from jdraw.data import kanji
from jdraw.model import bundle
from jdraw.model import network as M
from jdraw.planner import loop as planner
from jdraw.planner import plan as api

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


@pytest.fixture(scope="module")
def targets(kanji_set):
    idx = kanji.split_indices(kanji_set, "test")[:30]
    chars = [demo.sample(kanji_set, int(i)).target for i in idx]
    blank, full = np.zeros((100, 100), bool), np.zeros((100, 100), bool)
    full[20:40, 20:40] = True  # a blob: strokes over drawn ink, idle and stalled rules
    return np.stack(chars[:10] + [blank] + chars[10:20] + [full] + chars[20:])


def _one_at_a_time(model, targets, limits):
    """The old vmap loop on one image per call."""
    graphdef, st = nnx.split(model)
    fn = api._planner(graphdef, limits, "window")
    out = []
    for t in targets:
        o = fn(st, t[None], state.component_labels(t)[None])
        out.append((np.asarray(o.actions[0]), int(o.length[0]), bool(o.truncated[0])))
    return out


def _assert_same(stream, ref):
    for i, (a, n, trunc) in enumerate(ref):
        assert int(stream.length[i]) == n, i
        np.testing.assert_array_equal(np.asarray(stream.actions[i]), a, err_msg=str(i))
        assert bool(stream.truncated[i]) == trunc, i


def test_bundled_model_plans_as_one_at_a_time(targets):
    model = api.load_model(bundle.DEFAULT_BUNDLE)
    limits = planner.Limits(max_steps=400)
    ref = _one_at_a_time(model, targets, limits)
    labels = np.stack([state.component_labels(t) for t in targets])
    # 32 images through 8 slots: slots refill; the global sub-batch is full or waits.
    out = api.stream_plan(model, targets, labels, limits, width=8, global_batch=3)
    _assert_same(out, ref)
    assert int(out.global_calls.sum()) == sum(int((a[:n, 2] == 0).sum()) for a, n, _ in ref)
    assert int(out.global_batches.sum()) < int(out.global_calls.sum())  # starts are batched
    assert any(n == 0 for _, n, _ in ref) and any(t for *_, t in ref)


def test_random_model_with_tight_limits_plans_as_one_at_a_time(targets):
    cfg = ConfigDict(dict(bundle.DEFAULT_MODEL, hidden=32))
    model = M.build(cfg, seed=3)
    model.eval()
    # Short strokes, quick idle cut-off: every way a stroke or a plan ends.
    limits = planner.Limits(max_steps=90, max_stroke_steps=7, max_idle_steps=2)
    sub = targets[8:20]
    ref = _one_at_a_time(model, sub, limits)
    labels = np.stack([state.component_labels(t) for t in sub])
    _assert_same(api.stream_plan(model, sub, labels, limits, width=4, global_batch=2), ref)
    dots = sum(int(np.any(np.all(a[:n] == [0, 0, 1], axis=1))) for a, n, _ in ref)
    assert dots > 0  # strokes with no move are drawn as dots


def test_plan_streams_and_does_not_recompile_for_a_new_batch_size(targets):
    five = jdraw.plan(targets[:5], batch_size=4, max_steps=300)
    before = api._TRACES["plan"]
    seven = jdraw.plan(targets[:7], batch_size=4, max_steps=300)  # same bucket (8)
    assert api._TRACES["plan"] == before
    np.testing.assert_array_equal(five.actions, seven.actions[:5])
    old = jdraw.plan(targets[:7], loop="vmap", max_steps=300)
    np.testing.assert_array_equal(old.actions, seven.actions)
    np.testing.assert_array_equal(old.truncated, seven.truncated)


def test_two_devices_plan_as_one():
    script = textwrap.dedent(
        """
        import jax, numpy as np
        import jdraw
        from jdraw.planner import plan as api
        from jdraw.data import demos as demo
        from jdraw.data import kanji
        assert len(jax.devices()) == 2
        ks = kanji.load(progress=False)
        t = np.stack([demo.sample(ks, int(i)).target for i in kanji.split_indices(ks, "test")[:7]])
        one = jdraw.plan(t, devices=jax.devices()[:1], batch_size=2, max_steps=300)
        two = jdraw.plan(t, batch_size=2, max_steps=300)
        np.testing.assert_array_equal(one.actions, two.actions)
        np.testing.assert_array_equal(one.lengths, two.lengths)
        assert one.lengths.min() > 0
        m = api.load_model()
        labels = np.stack([api.state.component_labels(x) for x in t])
        out = api.stream_plan(m, t, labels, api.planner.Limits(max_steps=300), width=2)
        assert out.global_calls.shape == (2,) and out.global_calls.min() > 0  # both devices work
        print("ok")
        """
    )
    env = dict(
        os.environ, XLA_FLAGS="--xla_force_host_platform_device_count=2", JAX_PLATFORMS="cpu"
    )
    r = subprocess.run(
        [sys.executable, "-c", script], cwd=ROOT, env=env, capture_output=True, text=True
    )
    assert r.returncode == 0, r.stdout + r.stderr[-3000:]


def test_a_step_never_copies_the_slot_batch(targets):
    # The slot arrays ([slots, H, W] images, [slots, T, 3] actions) are updated
    # in place: no copy of them inside the compiled loop, only outside it.
    model = api.load_model(bundle.DEFAULT_BUNDLE)
    graphdef, st = nnx.split(model)
    limits = planner.Limits(max_steps=300)
    fn = api._streamer(graphdef, limits, "window", 8, 2, (jax.devices()[0],))
    t = targets[:16]
    labels = np.stack([state.component_labels(x) for x in t])
    hlo = fn.lower(st, t, labels, np.array([16], np.int32)).compile().as_text()
    big = re.compile(r"= \w+\[8,(100,100|300,3)\]\S* copy\(")
    computations = re.split(r"\n(?=\S)", hlo)
    copies = [c.split("\n", 1)[0][:60] for c in computations if big.search(c)]
    assert all(c.startswith("ENTRY") for c in copies), copies
    # The pattern does match the copies XLA makes outside the loop.
    assert any(big.search(c) for c in computations if c.startswith("ENTRY"))
