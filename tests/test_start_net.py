"""The whole-canvas start model sees far ink; the paper's does not."""

import jax.numpy as jnp
import numpy as np
from ml_collections import ConfigDict

from jdraw import model as M

FAR_EFFECT = 1e-6  # logit change that counts as "depends on"


def _logit_change(global_net):
    m = M.build(ConfigDict(dict(hidden=8, global_net=global_net)), seed=3)
    m.eval()
    x = np.zeros((1, 100, 100, 4), np.float32)
    x[0, 10, 10:30, 3] = 1  # unvisited ink near the probed pixel
    y = x.copy()
    y[0, 75, 75, 3] = 1  # one more ink pixel 65 px away (Chebyshev)
    a = m.global_logits(jnp.asarray(x))[0, 10, 12]
    b = m.global_logits(jnp.asarray(y))[0, 10, 12]
    return float(abs(a - b))


def test_start_net_logit_depends_on_ink_60_px_away():
    assert _logit_change("unet") > FAR_EFFECT


def test_paper_global_logit_does_not():
    assert _logit_change("paper") == 0.0
