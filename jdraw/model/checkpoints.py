"""Training workdirs: where their Orbax checkpoints live, reading them, exporting bundles.

A workdir holds ``config.json`` (the run's config) and ``checkpoints/``, an
Orbax ``CheckpointManager`` whose steps hold the items ``model`` (the NNX
state as a pure dict), ``optimizer``, ``step`` (progress counters) and
``config``. Reading a workdir needs only the model item; this module imports
nothing from training or planning, so inference reads a workdir in memory.
"""

from __future__ import annotations

import json
import pathlib
from typing import TYPE_CHECKING, NamedTuple

import jax
from flax import nnx
from ml_collections import ConfigDict

from jdraw.model import bundle
from jdraw.model import network as M

if TYPE_CHECKING:
    import orbax.checkpoint as ocp

ITEMS = ("model", "optimizer", "step", "config")


class Restored(NamedTuple):
    model: M.DrawModel  # in eval mode
    config: ConfigDict  # the run's whole config
    step: int
    progress: dict  # the ``step`` item: strokes_seen, global_seen, wall_time_s


def manager(workdir, *, read_only: bool = False) -> ocp.CheckpointManager:
    """The workdir's checkpoint manager; ``read_only`` writes and deletes nothing."""
    import orbax.checkpoint as ocp  # here: importing jdraw to plan from a bundle needs no Orbax

    opts = ocp.CheckpointManagerOptions(
        max_to_keep=None if read_only else 2,  # reading keeps every step there is
        save_interval_steps=1,
        read_only=read_only,
        create=not read_only,
    )
    return ocp.CheckpointManager(
        pathlib.Path(workdir).resolve() / "checkpoints", options=opts, item_names=ITEMS
    )


def abstract(tree):
    """Shapes and dtypes of ``tree``'s arrays, what Orbax restores into."""
    import orbax.checkpoint as ocp

    return jax.tree.map(ocp.utils.to_shape_dtype_struct, tree)


def read_config(workdir) -> ConfigDict:
    path = pathlib.Path(workdir) / "config.json"
    if not path.exists():
        raise bundle.BundleError(f"{path}: missing; {workdir} is not a jdraw training workdir")
    return ConfigDict(json.loads(path.read_text()))


def latest_step(workdir) -> int | None:
    """The workdir's latest saved step, or ``None``."""
    if not (pathlib.Path(workdir) / "checkpoints").exists():
        return None
    mgr = manager(workdir, read_only=True)
    try:
        return mgr.latest_step()
    finally:
        mgr.close()


def restore(workdir) -> Restored:
    """Builds the workdir's model from its config and fills in its latest parameters.

    Raises:
      jdraw.model.bundle.BundleError: no ``config.json`` or no checkpoint yet.
    """
    import orbax.checkpoint as ocp

    workdir = pathlib.Path(workdir)
    cfg = read_config(workdir)
    mgr = manager(workdir, read_only=True)
    try:
        step = mgr.latest_step() if (workdir / "checkpoints").exists() else None
        if step is None:
            raise bundle.BundleError(f"{workdir / 'checkpoints'}: no checkpoint saved yet")
        model = M.build(cfg.model, seed=int(cfg.seed))
        state = nnx.state(model)
        r = mgr.restore(
            step,
            args=ocp.args.Composite(
                model=ocp.args.StandardRestore(abstract(nnx.to_pure_dict(state))),
                step=ocp.args.JsonRestore(),
            ),
        )
    finally:
        mgr.close()
    nnx.replace_by_pure_dict(state, r["model"])
    nnx.update(model, state)
    model.eval()
    return Restored(model, cfg, int(step), dict(r["step"]))


def provenance(workdir, cfg: ConfigDict, progress: dict) -> dict:
    """A bundle's provenance: the workdir, the config's name and the progress counters.

    A run that started from another bundle (``cfg.train.init_from``) records
    that bundle's provenance under ``init_from``, so a bundle made in stages
    says what each stage trained.
    """
    prov = {"workdir": str(workdir), "config": cfg.get("name", ""), **progress}
    src = cfg.train.get("init_from") if "train" in cfg else None
    if src and (pathlib.Path(src) / "bundle.json").exists():
        prov["init_from"] = {"bundle": str(src), **bundle.read_meta(src).get("provenance", {})}
    return prov


def write_bundle(model, cfg: ConfigDict, out_dir, prov: dict) -> pathlib.Path:
    """Writes a run's bundle: ``model``, its config section and the whole config beside it."""
    tc = json.loads(cfg.to_json_best_effort())
    planner = cfg.get("planner")
    planner = planner.to_dict() if planner is not None else None
    return bundle.write(model, cfg.model.to_dict(), out_dir, prov, tc, planner)


def export(checkpoint_or_workdir, out_dir) -> pathlib.Path:
    """Writes the inference bundle of a training workdir's latest checkpoint.

    ``jdraw.plan(images, checkpoint=out_dir)`` then loads it.

    Args:
      checkpoint_or_workdir: a training workdir (with ``config.json`` and
        ``checkpoints/``) or an existing bundle (copied).
      out_dir: where to write ``bundle.json`` and ``params.npz``.
    """
    src = pathlib.Path(checkpoint_or_workdir)
    if (src / "bundle.json").exists():
        mdl, model_cfg = bundle.load(src)
        meta = bundle.read_meta(src)
        tc = src / bundle.TRAINING_CONFIG
        tc = json.loads(tc.read_text()) if tc.exists() else None
        return bundle.write(
            mdl, model_cfg, out_dir, meta.get("provenance"), tc, meta.get("planner")
        )
    r = restore(src)
    prov = provenance(src, r.config, {"step": r.step, **r.progress})
    return write_bundle(r.model, r.config, out_dir, prov)
