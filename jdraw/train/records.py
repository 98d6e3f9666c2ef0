"""What a run leaves in its workdir: Orbax checkpoints and ``metrics.jsonl``.

The checkpoint layout (items ``model``, ``optimizer``, ``step``, ``config``)
is :mod:`jdraw.model.checkpoints`'s, which reads it for inference; training
also saves and restores the optimizer, to resume.
"""

from __future__ import annotations

import json
import pathlib

import orbax.checkpoint as ocp
from flax import nnx

from jdraw.model import checkpoints
from jdraw.train.step import TrainState

manager = checkpoints.manager


def save(mgr: ocp.CheckpointManager, step: int, state: TrainState, progress: dict, cfg) -> None:
    """Saves ``state`` as checkpoint ``step`` (asynchronously: Orbax writes in the background)."""
    model_state = nnx.merge_state(state.params, state.rest)
    mgr.save(
        step,
        args=ocp.args.Composite(
            model=ocp.args.StandardSave(nnx.to_pure_dict(model_state)),
            optimizer=ocp.args.StandardSave(state.opt_state),
            step=ocp.args.JsonSave({"step": int(step), **progress}),
            config=ocp.args.JsonSave(json.loads(cfg.to_json())),
        ),
    )


def restore(mgr: ocp.CheckpointManager, step: int, state: TrainState) -> tuple[TrainState, dict]:
    """Checkpoint ``step`` in the shapes of ``state``; returns it and the progress counters."""
    model_state = nnx.merge_state(state.params, state.rest)
    r = mgr.restore(
        step,
        args=ocp.args.Composite(
            model=ocp.args.StandardRestore(checkpoints.abstract(nnx.to_pure_dict(model_state))),
            optimizer=ocp.args.StandardRestore(checkpoints.abstract(state.opt_state)),
            step=ocp.args.JsonRestore(),
        ),
    )
    nnx.replace_by_pure_dict(model_state, r["model"])
    params, rest = nnx.split_state(model_state, nnx.Param, ...)
    return TrainState(params, rest, r["optimizer"]), dict(r["step"])


def append(log_path: pathlib.Path, record: dict) -> None:
    """Appends one JSON line to ``metrics.jsonl``."""
    with open(log_path, "a") as f:
        f.write(json.dumps(record) + "\n")


def drop_records_after(log_path: pathlib.Path, step: int) -> None:
    """Rewrites ``metrics.jsonl`` without records past ``step`` (the restored one).

    A run killed after its last checkpoint logged steps it redoes on resume;
    without this they would appear twice. A half-written last line goes too.
    """
    if not log_path.exists():
        return
    kept = []
    for line in log_path.read_text().splitlines():
        try:
            rec = json.loads(line)
        except json.JSONDecodeError:
            continue
        # The final validation is logged again whenever a finished run is rerun.
        if isinstance(rec, dict) and int(rec.get("step", 0)) <= step and "final_val" not in rec:
            kept.append(line)
    tmp = log_path.with_suffix(".jsonl.tmp")
    tmp.write_text("".join(x + "\n" for x in kept))
    tmp.replace(log_path)
