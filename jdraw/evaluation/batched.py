"""Planning many canvases in batches of one compiled size, for the evaluations."""

from __future__ import annotations

import numpy as np

from jdraw.planner import plan as api


def plan_batched(
    inputs: np.ndarray, checkpoint, batch: int = 32, progress: bool = True, desc="planning", **kw
):
    """Plans ``inputs`` ``bool [N, 100, 100]`` in batches of ``batch`` as traced.

    Every call has the compiled batch size (the last batch is padded); ``kw``
    goes to ``jdraw.plan``. Returns one :class:`jdraw.Plan` of all ``N``.
    """
    from jdraw.plans import Plan

    it = range(0, len(inputs), batch)
    if progress:
        from tqdm import tqdm

        it = tqdm(it, desc=desc, unit="batch")
    parts = []
    for s in it:
        chunk = inputs[s : s + batch]
        n = len(chunk)
        if n < batch:  # pad to the compiled batch size
            chunk = np.concatenate([chunk, np.zeros((batch - n, 100, 100), bool)])
        p = api.plan(chunk, checkpoint=checkpoint, order="model", **kw)
        parts.append(Plan(p.strokes[:n], p.actions[:n], p.lengths[:n], p.truncated[:n]))
    T = max(p.actions.shape[1] for p in parts)
    return Plan(
        strokes=[s for p in parts for s in p.strokes],
        actions=np.concatenate(
            [np.pad(p.actions, ((0, 0), (0, T - p.actions.shape[1]), (0, 0))) for p in parts]
        ),
        lengths=np.concatenate([p.lengths for p in parts]),
        truncated=np.concatenate([p.truncated for p in parts]),
    )
