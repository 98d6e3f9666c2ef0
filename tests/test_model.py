"""The exact window encoder against full-image encoding + extraction."""

import jax
import jax.numpy as jnp
import numpy as np
import pytest
from flax import nnx

from jdraw import state as S
from jdraw.model import network as M

TOL = 1e-5  # max abs difference, float32


@pytest.fixture(scope="module")
def trained_like_model():
    """Random weights with non-trivial batch-norm statistics (eval mode)."""
    m = M.DrawModel(hidden=32, rngs=nnx.Rngs(0))
    rng = np.random.default_rng(0)
    for bn in [*m.local_norms.a, *m.local_norms.b, m.local_norms.final]:
        c = bn.mean.shape[0]
        bn.mean.set_value(jnp.asarray(rng.normal(0, 0.5, c), jnp.float32))
        bn.var.set_value(jnp.asarray(rng.uniform(0.5, 2.0, c), jnp.float32))
        bn.bias.set_value(jnp.asarray(rng.normal(0, 0.3, c), jnp.float32))
    m.eval()
    return m


def _random_state(rng):
    target = rng.random((100, 100)) < 0.15
    visited = target & (rng.random((100, 100)) < 0.5)
    return target, S.component_labels(target), visited


def test_receptive_radius():
    assert M.receptive_radius() == 9 and M.window_size() == 23


def test_window_equals_full_encoding(trained_like_model):
    m = trained_like_model
    rng = np.random.default_rng(1)
    target, labels, visited = _random_state(rng)
    pens = [
        (0, 0),
        (99, 0),
        (0, 99),
        (99, 99),
        (50, 0),
        (0, 50),
        (99, 50),
        (50, 99),
        (1, 98),
        (8, 91),
    ]
    pens += [tuple(p) for p in rng.integers(0, 100, (10, 2))]
    pens = jnp.asarray(pens, jnp.int32)
    t, lab, v = jnp.asarray(target), jnp.asarray(labels), jnp.asarray(visited)

    @jax.jit
    def both(pens):
        wins, inside = jax.vmap(lambda p: S.local_window(t, lab, v, p, m.window))(pens)
        fw = m.local_features(wins, inside)
        states = jax.vmap(lambda p: S.local_state(t, lab, v, p))(pens)
        ff = m.local_features_full(states, pens)
        return fw, ff

    fw, ff = both(pens)
    assert fw.shape == (len(pens), 1600)
    err = float(jnp.max(jnp.abs(fw - ff)))
    assert err <= TOL, err
    assert float(jnp.max(jnp.abs(ff))) > 0.1  # not trivially zero


def test_window_crop_equals_full_state_crop():
    rng = np.random.default_rng(2)
    target, labels, visited = _random_state(rng)
    for pen in [(0, 0), (99, 99), (3, 60), (50, 50)]:
        p = jnp.asarray(pen, jnp.int32)
        win, inside = S.local_window(target, labels, visited, p, 23)
        full = np.pad(
            np.asarray(S.local_state(target, labels, visited, p)), ((11, 11), (11, 11), (0, 0))
        )
        np.testing.assert_array_equal(
            np.asarray(win), full[pen[1] : pen[1] + 23, pen[0] : pen[0] + 23]
        )
        assert int(inside.sum()) == (min(pen[0] + 11, 99) - max(pen[0] - 11, 0) + 1) * (
            min(pen[1] + 11, 99) - max(pen[1] - 11, 0) + 1
        )


def test_global_logits_shape_and_variants():
    for core, extraction in [("lstm", "late"), ("fc", "initial")]:
        m = M.DrawModel(hidden=16, core=core, extraction=extraction, rngs=nnx.Rngs(0))
        m.eval()
        assert m.global_logits(jnp.zeros((2, 100, 100, 4))).shape == (2, 100, 100)
        x = jnp.zeros((3, m.window, m.window, 3))
        assert m.local_features(x, jnp.ones(x.shape[:3], bool)).shape == (3, 1600)
    with pytest.raises(ValueError, match="core"):
        M.DrawModel(core="gru", rngs=nnx.Rngs(0))
