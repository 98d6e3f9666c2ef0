"""The whole-canvas start model sees far ink; the paper's does not."""

import jax.numpy as jnp
import numpy as np
import pytest
from ml_collections import ConfigDict

from jdraw.model import network as M
from jdraw.model import start_net

FAR_EFFECT = 1e-6  # logit change that counts as "depends on"


def _logit_change(global_net, **model):
    m = M.build(ConfigDict(dict(hidden=8, global_net=global_net, **model)), seed=3)
    m.eval()
    x = np.zeros((1, 100, 100, 4), np.float32)
    x[0, 10, 10:30, 3] = 1  # unvisited ink near the probed pixel
    y = x.copy()
    y[0, 75, 75, 3] = 1  # one more ink pixel 65 px away (Chebyshev)
    a = m.global_logits(jnp.asarray(x), restrict=False)[0, 10, 12]
    b = m.global_logits(jnp.asarray(y), restrict=False)[0, 10, 12]
    return float(abs(a - b))


@pytest.mark.parametrize("half_res", [False, True])
def test_start_net_logit_depends_on_ink_60_px_away(half_res):
    model = dict(start_widths=(16, 32, 64), start_half_res=True) if half_res else {}
    assert _logit_change("unet", **model) > FAR_EFFECT


def test_space_to_depth_round_trip_keeps_each_pixel():
    x = jnp.arange(2 * 6 * 4 * 3, dtype=jnp.float32).reshape(2, 6, 4, 3)
    d = start_net.space_to_depth(x)
    assert d.shape == (2, 3, 2, 12)
    np.testing.assert_array_equal(d[0, 1, 1, :3], x[0, 2, 2])  # a block's top-left pixel
    np.testing.assert_array_equal(d[0, 1, 1, 9:], x[0, 3, 3])  # and its bottom-right
    np.testing.assert_array_equal(start_net.depth_to_space(d), x)


def test_half_res_start_net_gives_each_pixel_its_own_logit():
    m = M.build(
        ConfigDict(
            dict(hidden=8, global_net="unet", start_widths=(16, 32, 64), start_half_res=True)
        ),
        seed=1,
    )
    m.eval()
    x = np.zeros((1, 100, 100, 4), np.float32)
    x[0, 20:60, 40, 3] = 1
    logits = np.asarray(m.global_logits(jnp.asarray(x), restrict=False))[0]
    assert logits.shape == (100, 100)
    block = logits[20:22, 40:42]  # one 2x2 block: four different logits
    assert len(np.unique(block)) == 4
    with pytest.raises(ValueError, match="even"):
        m.start_net(jnp.zeros((1, 99, 99, 4)))


def test_paper_global_logit_does_not():
    assert _logit_change("paper") == 0.0


def test_start_candidates_are_ends_junctions_and_drawn_ink():
    from jdraw import state
    from jdraw.model.start_net import start_candidates

    t = np.zeros((20, 20), bool)
    t[10, 2:18] = True  # a horizontal line
    t[3:10, 9] = True  # a vertical one meeting it from above (a T)
    visited = np.zeros_like(t)
    visited[10, 2:5] = True  # its first pixels already drawn
    x = state.global_state(
        jnp.asarray(t), jnp.asarray(visited), jnp.zeros_like(t), jnp.zeros(2, jnp.int32), False
    )
    c = np.asarray(start_candidates(x[None]))[0]
    assert c[10, 17] and c[3, 9]  # free ends
    assert c[10, 9]  # the junction
    assert c[10, 5]  # beside drawn ink
    assert not c[10, 13] and not c[6, 9]  # inside a line
    assert not (c & ~t).any()
