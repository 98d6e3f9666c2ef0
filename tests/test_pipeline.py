"""One command trains the default: configs/default.py's stages, resumable, into one bundle."""

import json
import pathlib

import numpy as np
import pytest

import jdraw
from configs import default
from jdraw.model import bundle
from jdraw.train import distributed, pipeline

# Paths the stages pass each other (now "stage:NAME") and names differ from the
# retired configs the default was trained with; every other value must match.
PATHS = ("name", "init_from", "tracer", "out")


def _values(cfg: dict) -> dict:
    out = {k: _values(v) if isinstance(v, dict) else v for k, v in cfg.items() if k not in PATHS}
    return json.loads(json.dumps(out))  # tuples -> lists, as the bundle's json holds them


def test_default_config_is_what_the_bundled_default_was_trained_with():
    c = json.loads(default.get_config().to_json_best_effort())
    here = bundle.DEFAULT_BUNDLE
    start = json.loads((here / bundle.TRAINING_CONFIG).read_text())
    assert _values(c["stages"]["start"]) == _values(start)
    for net in ("splitter", "ranker"):
        made = json.loads((here / f"{net}.json").read_text())["provenance"]["config"]
        assert _values(c["stages"][net]) == _values(made), net
    # The local stage's own config is not in the bundle; its model and budget are.
    local, prov = c["stages"]["local"], bundle.read_meta(here)["provenance"]["init_from"]
    assert local["train"]["num_steps"] == prov["step"] == 3600
    assert _values(local["data"]) == _values(start["data"])
    keep = {k: v for k, v in start["model"].items() if not k.startswith("start_")}
    assert _values({k: v for k, v in local["model"].items() if not k.startswith("start_")}) == (
        _values(keep)
    )
    assert c["stage_order"] == ["local", "start", "splitter", "ranker"]
    assert c["stages"]["start"]["train"]["init_from"] == "stage:local"
    assert c["stages"]["splitter"]["tracer"] == c["stages"]["ranker"]["tracer"] == "stage:start"


def test_tiny_default_runs_every_stage_into_a_bundle_that_plans(tmp_path, kanji_set):
    from jdraw.data import demos as demo
    from jdraw.data import kanji
    from jdraw.planner import plan as api

    cfg = default.get_config("tiny")
    result = pipeline.train(cfg, tmp_path, progress=False)
    out = tmp_path / "bundle"
    assert result["bundle"] == str(out)
    assert sorted(p.name for p in out.iterdir()) == sorted(
        p.name for p in bundle.DEFAULT_BUNDLE.iterdir()
    )
    meta = bundle.read_meta(out)
    assert meta["provenance"]["init_from"]["bundle"] == str(tmp_path / "local" / "bundle")
    assert api.load_ranker(out) is not None and api.load_splitter(out) is not None
    idx = kanji.split_indices(kanji_set, "test")[:2]
    targets = np.stack([demo.sample(kanji_set, int(i)).target for i in idx])
    plan = jdraw.plan(targets, checkpoint=out)
    assert len(plan.strokes) == 2 and all(len(s) > 0 for s in plan.strokes)
    # Run again: every stage is done and skipped, the bundle written again the same.
    before = (out / "params.npz").read_bytes()
    again = pipeline.train(cfg, tmp_path, progress=False)
    assert all(again[n] == "done before" for n in cfg.stage_order)
    assert (out / "params.npz").read_bytes() == before


def test_stage_paths_and_kinds():
    c = default.get_config()
    s = pipeline.resolve(c.stages.start, pathlib.Path("/w"))
    assert s.train.init_from == "/w/local/bundle" and s.train.learning_rate == 1e-3
    assert [pipeline.kind(c.stages[n]) for n in c.stage_order] == [
        "model",
        "model",
        "splitter",
        "ranker",
    ]
    with pytest.raises(ValueError, match="unknown variant"):
        default.get_config("huge")


def test_process_settings_from_flags_or_environment():
    env = {"JAX_COORDINATOR_ADDRESS": "h:1", "JAX_NUM_PROCESSES": "4", "JAX_PROCESS_ID": "3"}
    assert distributed.settings(environ=env) == ("h:1", 4, 3)
    assert distributed.settings("g:2", 2, 0, environ=env) == ("g:2", 2, 0)  # flags win
    assert distributed.settings(environ={}) is None  # one process
    with pytest.raises(ValueError, match="process count"):
        distributed.settings("h:1", environ={})
    with pytest.raises(ValueError, match="not in"):
        distributed.settings("h:1", 2, 2, environ={})
    with pytest.raises(ValueError, match="coordinator"):
        distributed.settings(None, 2, 0, environ={})


def test_mix_variant_adds_other_scripts_to_the_nets_only():
    base, mix = default.get_config().to_dict(), default.get_config("mix").to_dict()
    for name in ("local", "start"):
        assert mix["stages"][name] == base["stages"][name]
    assert mix["stages"]["splitter"]["extra"] == {"latin": 1500, "cursive": 2000}
    assert mix["stages"]["ranker"]["tracer_split"] == "stage:splitter"
    tiny = default.get_config("mix_tiny")
    assert all(v == 4 for n in ("splitter", "ranker") for v in tiny.stages[n].extra.values())
    # Every extra set named there is one jdraw.data.mix can load.
    from jdraw.data import mix as sets

    for name in mix["stages"]["splitter"]["extra"]:
        ks, pool = sets.load(name, progress=False)
        assert len(pool) > 0
