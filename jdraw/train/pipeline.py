"""A planner trained in stages, one command: models, then splitter and ranker, then one bundle.

A pipeline config (``configs/default.py``) holds ``stage_order`` and one config
per stage under ``stages``. Each stage runs in ``WORKDIR/NAME``: a model
stage (a config with ``model``) trains there with :func:`jdraw.train.loop.train`
and writes ``WORKDIR/NAME/bundle``; a ``splitter`` or ``ranker`` stage traces
with a planner bundle and fits its nets (:mod:`jdraw.train.splitter`,
:mod:`jdraw.train.ranker`). Every stage resumes where it stopped, and one that
is done is skipped. Strings ``"stage:NAME"`` in a stage's config stand for
``WORKDIR/NAME/bundle``. Last, ``WORKDIR/bundle`` is assembled as
``jdraw/checkpoints/default`` is laid out: the last model stage's bundle with
the splitter's and ranker's nets beside it.
"""

from __future__ import annotations

import json
import pathlib
import shutil

import jax
from ml_collections import ConfigDict

from jdraw.train import distributed

PREFIX = "stage:"
NETS = {"splitter": "splitter", "ranker": "ranker"}  # stage kind -> file stem in the bundle


def is_pipeline(cfg: ConfigDict) -> bool:
    return "stage_order" in cfg


def kind(stage_cfg: ConfigDict) -> str:
    """``"model"``, ``"splitter"``, ``"ranker"`` or ``"reading"``."""
    return stage_cfg.get("stage", "model") if "model" not in stage_cfg else "model"


def resolve(stage_cfg: ConfigDict, workdir: pathlib.Path) -> ConfigDict:
    """A copy of ``stage_cfg`` with every ``"stage:NAME"`` string made ``workdir/NAME/bundle``."""

    def fix(x):
        if isinstance(x, dict):
            return {k: fix(v) for k, v in x.items()}
        if isinstance(x, str) and x.startswith(PREFIX):
            return str(workdir / x[len(PREFIX) :] / "bundle")
        return x

    return ConfigDict(fix(stage_cfg.to_dict()))


def done(stage_cfg: ConfigDict, stage_dir: pathlib.Path) -> bool:
    """Whether a stage finished: a model stage wrote its bundle, a net stage its result."""
    if kind(stage_cfg) == "model":
        return (stage_dir / "bundle" / "bundle.json").exists()
    return (stage_dir / "result.json").exists()


def run_stage(stage_cfg: ConfigDict, stage_dir: pathlib.Path, progress: bool = True) -> dict:
    k = kind(stage_cfg)
    if k == "model":
        from jdraw.train import loop

        return loop.train(stage_cfg, stage_dir, progress=progress)
    if k == "splitter":
        from jdraw.train import splitter

        return splitter.train(stage_cfg, stage_dir, progress=progress)
    if k == "ranker":
        from jdraw.train import ranker

        return ranker.train(stage_cfg, stage_dir, progress=progress)
    if k == "reading":
        from jdraw.train import reading

        return reading.train(stage_cfg, stage_dir)
    raise ValueError(f"{stage_dir}: stage kind {k!r} is none of model, splitter, ranker, reading")


def assemble(cfg: ConfigDict, workdir: pathlib.Path) -> pathlib.Path:
    """Writes ``workdir/bundle``: the last model stage's bundle and the nets beside it."""
    out = workdir / "bundle"
    tmp = workdir / "bundle.tmp"
    shutil.rmtree(tmp, ignore_errors=True)
    models = [n for n in cfg.stage_order if kind(cfg.stages[n]) == "model"]
    if not models:
        raise ValueError(f"{cfg.get('name')}: a pipeline needs a model stage")
    shutil.copytree(workdir / models[-1] / "bundle", tmp)
    for name in cfg.stage_order:
        k = kind(cfg.stages[name])
        if k in NETS:
            src = pathlib.Path(resolve(cfg.stages[name], workdir).out)
            for ext in ("npz", "json"):
                shutil.copy2(src / f"{NETS[k]}.{ext}", tmp / f"{NETS[k]}.{ext}")
    shutil.rmtree(out, ignore_errors=True)
    tmp.rename(out)
    return out


def train(cfg: ConfigDict, workdir, progress: bool = True) -> dict:
    """Runs every stage of ``cfg`` not yet done, in order; returns each stage's result.

    Several processes (:mod:`jdraw.train.distributed`) share the model stages;
    the splitter and ranker stages (tracing on the host) and the bundle are
    process 0's alone.
    """
    workdir = pathlib.Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    unknown = [n for n in cfg.stage_order if n not in cfg.stages]
    if unknown:
        raise ValueError(f"{cfg.get('name')}: stage_order names stages not in stages: {unknown}")
    lead = jax.process_index() == 0
    if lead:
        (workdir / "config.json").write_text(cfg.to_json_best_effort(indent=2) + "\n")
    results = {}
    for name in cfg.stage_order:
        stage_cfg = resolve(cfg.stages[name], workdir)
        stage_dir = workdir / name
        if done(stage_cfg, stage_dir):
            results[name] = "done before"
            if progress and lead:
                print(f"stage {name}: done before ({stage_dir})")
            continue
        if kind(stage_cfg) != "model" and not lead:
            continue
        if progress and lead:
            print(f"stage {name} ({kind(stage_cfg)}) in {stage_dir}")
        r = run_stage(stage_cfg, stage_dir, progress=progress and lead)
        results[name] = {k: v for k, v in r.items() if k not in ("logs", "val")}
    if lead:
        results["bundle"] = str(assemble(cfg, workdir))
        (workdir / "result.json").write_text(json.dumps(results, indent=2, default=str) + "\n")
    distributed.barrier(f"jdraw.train.pipeline {workdir}")  # others wait for process 0's stages
    return results
