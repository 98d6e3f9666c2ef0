import json

import numpy as np
import pytest
from flax import nnx

import jdraw
from jdraw.model import bundle
from jdraw.model import network as M


@pytest.fixture
def small_bundle(tmp_path):
    cfg = {"hidden": 8, "core": "lstm", "extraction": "late"}
    m = M.DrawModel(hidden=8, rngs=nnx.Rngs(3))
    return bundle.write(m, cfg, tmp_path / "b"), m


def test_roundtrip(small_bundle):
    path, m = small_bundle
    m2, cfg = bundle.load(path)
    a, b = bundle.state_arrays(m), bundle.state_arrays(m2)
    assert cfg["hidden"] == 8 and a.keys() == b.keys()
    assert all(np.array_equal(a[k], b[k]) for k in a)


def test_missing_bundle_names_the_file(tmp_path):
    with pytest.raises(bundle.BundleError, match="bundle.json"):
        bundle.load(tmp_path)


def test_corrupt_json(small_bundle):
    path, _ = small_bundle
    (path / "bundle.json").write_text("{not json")
    with pytest.raises(bundle.BundleError, match=r"bundle\.json.*not valid JSON"):
        bundle.load(path)


def test_wrong_version(small_bundle):
    path, _ = small_bundle
    meta = json.loads((path / "bundle.json").read_text())
    meta["format_version"] = 99
    (path / "bundle.json").write_text(json.dumps(meta))
    with pytest.raises(bundle.BundleError, match="format_version 99"):
        bundle.load(path)


def test_corrupt_params(small_bundle):
    path, _ = small_bundle
    (path / "params.npz").write_bytes(b"garbage")
    with pytest.raises(bundle.BundleError, match=r"params\.npz.*corrupt"):
        jdraw.plan(np.zeros((100, 100)), checkpoint=path)


def test_mismatched_model(small_bundle):
    path, _ = small_bundle
    meta = json.loads((path / "bundle.json").read_text())
    meta["model"]["hidden"] = 16
    (path / "bundle.json").write_text(json.dumps(meta))
    with pytest.raises(bundle.BundleError, match=r"params\.npz.*shape"):
        bundle.load(path)


def test_provenance_records_the_bundle_a_run_started_from(tmp_path):
    from ml_collections import ConfigDict

    from jdraw.model import checkpoints

    mdl, cfg = bundle.load(bundle.PAPER_BUNDLE)
    bundle.write(mdl, cfg, tmp_path / "a", provenance={"config": "a", "strokes_seen": 5})
    run = ConfigDict(dict(name="b", train=dict(init_from=str(tmp_path / "a"))))
    prov = checkpoints.provenance("runs/b", run, {"step": 3})
    assert prov["config"] == "b" and prov["step"] == 3
    assert prov["init_from"]["config"] == "a" and prov["init_from"]["strokes_seen"] == 5
    plain = ConfigDict(dict(name="c", train=dict(init_from="")))
    assert "init_from" not in checkpoints.provenance("runs/c", plain, {})
