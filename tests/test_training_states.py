"""Host-built training examples give the model the states the planner gives it.

The training batches (:mod:`jdraw.data.batches`) hold a stroke's pen
positions and the canvas before it; the losses build the model's inputs from
them (:mod:`jdraw.train.losses`). The planner builds them inside ``jit`` as it
draws (:mod:`jdraw.planner.loop`). Replaying a demonstration through the
jitted planner while recording what a policy is given must yield the same
images at the same pen positions, bit for bit.
"""

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from jdraw import state as S
from jdraw.data import batches, kanji
from jdraw.data import demos as D
from jdraw.model.network import window_size
from jdraw.planner import loop as planner
from jdraw.train import losses

W = window_size()  # the paper model's local window


def recording_replay(record: dict) -> planner.Policy:
    """The replay policy, recording the model inputs the planner hands a policy.

    The images are built from the policy's arguments as
    :func:`jdraw.planner.loop.model_policy` builds them, and sent to the host
    keyed ``("global", stroke)`` or ``("local", stroke, step)``.
    """
    base = planner.replay_policy()

    def put(key):
        def f(*arrays):
            record[tuple(int(k) for k in key(arrays))] = [np.asarray(a) for a in arrays[1:]]

        return f

    def start(ctx, pst, target, visited, last, pen, has_pen, allowed):
        stroke = pst[3]
        x = S.global_state(target, visited, last, pen, has_pen)
        jax.debug.callback(put(lambda a: (0, a[0])), stroke, x)
        return base.start(ctx, pst, target, visited, last, pen, has_pen, allowed)

    def observe(ctx, pst, target, labels, visited, pen):
        win, inside = S.local_window(target, labels, visited, pen, W)
        jax.debug.callback(put(lambda a: (1, a[0][0], a[0][1])), jnp.stack(pst[3:]), win, inside)
        return base.observe(ctx, pst, target, labels, visited, pen)

    return planner.Policy(start, base.begin, observe, base.decide)


def planner_states(d: D.Demo) -> dict:
    """Replays ``d`` through the jitted planner; the recorded model inputs."""
    record = {}
    starts, moves, n_moves = D.replay_arrays([d], len(d.strokes), max(len(s) for s in d.strokes))
    limits = planner.Limits(max_steps=2048, max_stroke_steps=512, max_idle_steps=512)
    policy = recording_replay(record)

    @jax.jit
    def run(starts, moves, n_moves, target, labels):
        pst = (starts, moves, n_moves, jnp.int32(0), jnp.int32(0))
        return planner.run(policy, None, pst, target, labels, limits)

    out = run(starts[0], moves[0], n_moves[0], d.target, S.component_labels(d.target))
    jax.block_until_ready(out)
    jax.effects_barrier()
    assert not bool(out.truncated)
    return record


@pytest.fixture(scope="module")
def chars(kanji_set):
    """Three training characters, unaugmented, with the planner's recorded inputs."""
    idx = [int(i) for i in kanji.split_indices(kanji_set, "train")[:3]]
    return {i: (D.sample(kanji_set, i), planner_states(D.sample(kanji_set, i))) for i in idx}


def _which(chars, target):
    (i,) = [i for i, (d, _) in chars.items() if np.array_equal(d.target, target)]
    return chars[i]


def test_local_windows_equal_the_planners(kanji_set, chars):
    rng = np.random.default_rng(0)
    b = batches.local_batch(
        kanji_set,
        np.asarray(list(chars)),
        rng,
        windows=512,
        strokes=24,
        max_len=96,
        per_char=4,
        strength=0.0,
    )
    windows = jax.jit(
        jax.vmap(losses.stroke_windows, in_axes=(0, 0, 0, 0, 0, None)), static_argnums=5
    )
    wins, inside = windows(b["target"], b["labels"], b["visited"], b["pts"], b["n_moves"], W)
    checked = 0
    for k in range(b["n_strokes"]):
        d, rec = _which(chars, b["target"][k])
        n = int(b["n_moves"][k])
        (s,) = [
            s
            for s, st in enumerate(d.strokes)
            if len(st) == n + 1 and np.array_equal(st, b["pts"][k, : n + 1])
        ]
        steps = int(b["valid"][k].sum())
        assert steps == n + 1  # every move, then the step that says "lift"
        for t in range(steps):
            want_win, want_inside = rec[(1, s, t)]
            np.testing.assert_array_equal(np.asarray(wins[k, t]), want_win, err_msg=f"{s} {t}")
            np.testing.assert_array_equal(np.asarray(inside[k, t]), want_inside)
            checked += 1
    assert b["n_strokes"] >= 6 and checked > 100


def test_global_states_equal_the_planners(kanji_set, chars):
    rng = np.random.default_rng(1)
    g = batches.global_batch(kanji_set, np.asarray(list(chars)), rng, size=16, strength=0.0)
    x, allowed = jax.jit(jax.vmap(losses.global_inputs))(
        g["target"], g["visited"], g["last"], g["pen"], g["has_pen"], g["start"]
    )
    firsts = 0
    for k in range(16):
        d, rec = _which(chars, g["target"][k])
        start = divmod(int(g["start"][k]), 100)[::-1]
        cands = [s for s, st in enumerate(d.strokes) if tuple(st[0]) == start]
        assert any(np.array_equal(np.asarray(x[k]), rec[(0, s)][0]) for s in cands), k
        assert bool(allowed[k, g["start"][k]])
        firsts += not g["has_pen"][k]
    assert 0 < firsts < 16  # both the first stroke (no pen yet) and later ones
