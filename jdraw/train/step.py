"""The training state and the jitted step.

The functional loop of the Flax NNX performance guide: ``nnx.split`` once into
the graph, the parameters and the rest (batch-norm statistics); a plain
``jax.jit`` step that merges them, takes the gradient with
``nnx.value_and_grad`` and returns the new state, its buffers donated.
"""

from __future__ import annotations

import pathlib
from typing import NamedTuple

import jax
import numpy as np
import optax
from flax import nnx

from jdraw.model import bundle
from jdraw.model import network as M
from jdraw.train import losses


class TrainState(NamedTuple):
    """What a step carries from one step to the next (a pytree)."""

    params: nnx.State  # the model's nnx.Param arrays
    rest: nnx.State  # its other state: batch-norm statistics
    opt_state: optax.OptState


class Setup(NamedTuple):
    graphdef: nnx.GraphDef
    tx: optax.GradientTransformation
    state: TrainState


def init_from_bundle(model: M.DrawModel, bundle_dir) -> int:
    """Copies every array of a bundle that ``model`` has (same path and shape).

    Used to train a new global model beside a trained local model
    (the start stage of ``configs/default.py``). Returns the number of arrays copied.
    """
    with np.load(pathlib.Path(bundle_dir) / "params.npz") as z:
        arrays = {k: z[k] for k in z.files}
    return bundle.fill(model, arrays, partial=True)


def create_state(cfg, *, tx: optax.GradientTransformation | None = None) -> Setup:
    """The model of ``cfg.model`` (seed ``cfg.seed``, in train mode) and its optimizer.

    ``cfg.train.init_from`` (optional) names a bundle whose matching arrays
    are copied in; ``tx`` defaults to Adam with ``cfg.train.learning_rate``,
    decayed along a cosine to ``cfg.train.final_lr_fraction`` of it over
    ``num_steps`` when that is set (the step count lives in the optimizer's
    state, so a resumed run continues the schedule).
    """
    model = M.build(cfg.model, seed=int(cfg.seed))
    if cfg.train.get("init_from"):
        init_from_bundle(model, cfg.train.init_from)
    model.train()
    graphdef, params, rest = nnx.split(model, nnx.Param, ...)
    lr = float(cfg.train.learning_rate)
    if cfg.train.get("final_lr_fraction") is not None:
        lr = optax.cosine_decay_schedule(
            lr, int(cfg.train.num_steps), alpha=float(cfg.train.final_lr_fraction)
        )
    tx = tx or optax.adam(lr)
    return Setup(graphdef, tx, TrainState(params, rest, tx.init(params)))


def model_of(graphdef: nnx.GraphDef, state: TrainState) -> M.DrawModel:
    """The model a training state holds (a new module; training mode as saved)."""
    return nnx.merge(graphdef, state.params, state.rest)


def make_step(graphdef: nnx.GraphDef, tx: optax.GradientTransformation, global_weight: float):
    """``step(state, batch) -> (state, logs)``, jitted, ``state`` donated.

    ``batch`` is :func:`jdraw.train.feed.make_batch`'s dict (see
    :func:`jdraw.train.losses.total_loss`).
    """

    def loss_fn(model, batch):
        return losses.total_loss(model, batch, global_weight)

    def step(state: TrainState, batch: dict):
        model = nnx.merge(graphdef, state.params, state.rest)
        (_, logs), grads = nnx.value_and_grad(loss_fn, has_aux=True)(model, batch)
        updates, opt_state = tx.update(grads, state.opt_state, state.params)
        params = optax.apply_updates(state.params, updates)
        rest = nnx.state(model, nnx.Not(nnx.Param))  # batch norm's updated statistics
        return TrainState(params, rest, opt_state), logs

    return jax.jit(step, donate_argnums=0)
