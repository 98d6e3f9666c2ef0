"""The whole-canvas start model sees far ink; the paper's does not."""

import jax.numpy as jnp
import numpy as np
from ml_collections import ConfigDict

from jdraw.model import network as M

FAR_EFFECT = 1e-6  # logit change that counts as "depends on"


def _logit_change(global_net):
    m = M.build(ConfigDict(dict(hidden=8, global_net=global_net)), seed=3)
    m.eval()
    x = np.zeros((1, 100, 100, 4), np.float32)
    x[0, 10, 10:30, 3] = 1  # unvisited ink near the probed pixel
    y = x.copy()
    y[0, 75, 75, 3] = 1  # one more ink pixel 65 px away (Chebyshev)
    a = m.global_logits(jnp.asarray(x), restrict=False)[0, 10, 12]
    b = m.global_logits(jnp.asarray(y), restrict=False)[0, 10, 12]
    return float(abs(a - b))


def test_start_net_logit_depends_on_ink_60_px_away():
    assert _logit_change("unet") > FAR_EFFECT


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
