"""Validation during training: plan held-out characters and score them."""

from __future__ import annotations

import numpy as np

from jdraw.data import demos as demo
from jdraw.evaluation import metrics
from jdraw.model import network as M
from jdraw.planner import plan as api


def validate(model: M.DrawModel, ks, idx, max_steps: int = 1024) -> dict:
    """Pixel and stroke accuracy of planning the characters ``idx`` (no augmentation).

    ``model`` is planned with in eval mode (it is switched).
    """
    model.eval()
    demos = [demo.sample(ks, int(i)) for i in idx]
    plan = api.plan(np.stack([d.target for d in demos]), checkpoint=model, max_steps=max_steps)
    return metrics.score(demos, plan)
