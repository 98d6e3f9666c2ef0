"""``jdraw.model.checkpoints``: a training checkpoint to an inference bundle."""

from __future__ import annotations

import json
import pathlib

from flax import nnx
from ml_collections import ConfigDict

from jdraw.model import bundle


def _latest(workdir: pathlib.Path):
    from jdraw.train import loop as training

    cfg_path = workdir / "config.json"
    if not cfg_path.exists():
        raise bundle.BundleError(f"{cfg_path}: missing; {workdir} is not a jdraw training workdir")
    cfg = ConfigDict(json.loads(cfg_path.read_text()))
    mgr = training.checkpoint_manager(workdir, cfg)
    step = mgr.latest_step()
    if step is None:
        raise bundle.BundleError(f"{workdir / 'checkpoints'}: no checkpoint saved yet")
    from jdraw.model import network as M

    mdl = M.build(cfg.model, seed=int(cfg.seed))
    graphdef, st = nnx.split(mdl)
    import optax

    params = nnx.state(mdl, nnx.Param)
    opt_state = optax.adam(cfg.train.learning_rate).init(params)
    st, _, progress = training.restore(mgr, step, st, opt_state)
    mgr.close()
    mdl = nnx.merge(graphdef, st)
    return mdl, cfg, step, progress


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
        return bundle.write(mdl, model_cfg, out_dir, meta.get("provenance"), tc)
    mdl, cfg, step, progress = _latest(src)
    prov = {"workdir": str(src), "step": int(step), "config": cfg.get("name", ""), **progress}
    tc = json.loads((src / "config.json").read_text())
    return bundle.write(mdl, cfg.model.to_dict(), out_dir, prov, tc)


def bundle_for_workdir(workdir) -> pathlib.Path:
    """The bundle of a workdir: ``workdir/bundle``, exported if older than the checkpoint."""
    workdir = pathlib.Path(workdir)
    out = workdir / "bundle"
    ck = workdir / "checkpoints"
    if not (out / "bundle.json").exists() or (
        ck.exists() and ck.stat().st_mtime > (out / "bundle.json").stat().st_mtime
    ):
        export(workdir, out)
    return out
