"""The bundled checkpoint loads, plans held-out characters well, and draws the README example."""

import json
import pathlib

import numpy as np
import pytest

import jdraw
from jdraw.data import demos as demo
from jdraw.data import kanji
from jdraw.evaluation import metrics
from jdraw.model import bundle

EXAMPLE = pathlib.Path(__file__).parent.parent / "examples" / "images" / "kanji.png"
STROKE_ACC_FLOOR = 0.90  # on 16 test characters; eval.py measures the full figure
PIXEL_ACC_FLOOR = 0.999  # canonical inputs may drop a stray staircase pixel


def test_bundled_checkpoints_are_present_and_trained():
    """The package ships the paper's model and the default, nothing else."""
    here = bundle.DEFAULT_BUNDLE.parent
    assert sorted(p.name for p in here.iterdir() if p.is_dir()) == ["default", "paper"]
    paper = bundle.read_meta(bundle.PAPER_BUNDLE)
    assert paper["provenance"].get("strokes_seen", 0) >= 90_000
    # Each bundle's provenance counts its own stage, and the stage it started from
    # under "init_from". The default (configs/default.py): a lean local model trained
    # on the paper's budget, then a half-resolution start model beside it.
    default = bundle.read_meta(bundle.DEFAULT_BUNDLE)
    assert default["model"]["start_half_res"] is True
    assert default["provenance"]["config"] == "lean_start"
    assert default["provenance"].get("global_seen", 0) >= 45_000
    assert default["provenance"]["init_from"]["config"] == "lean"
    assert default["provenance"]["init_from"].get("strokes_seen", 0) >= 90_000
    assert default["planner"] == {"join": True}
    from jdraw.planner import plan as api

    assert api.load_ranker(None) is not None  # the default orders with its ranker
    sp = api.load_splitter(None)  # and cuts and joins strokes with its splitter
    assert sp is not None
    meta = json.loads((bundle.DEFAULT_BUNDLE / "splitter.json").read_text())["provenance"]
    assert meta["config"]["name"] == "default/splitter" and meta["corners"] >= 10_000
    assert sp.reach == meta["config"]["reach"] > 0  # it joins ends through the ink
    assert sp.context and set(meta["config"]["extra"]) == {"latin", "cursive"}  # other scripts
    rk = json.loads((bundle.DEFAULT_BUNDLE / "ranker.json").read_text())["provenance"]
    members = rk["config"]["members"]  # seeds fitted and bundled as one (their mean)
    assert members == 3 and len(rk["logs"]) == members
    assert api.load_ranker(None).context
    assert api.load_ranker(None).hidden == members * rk["config"]["hidden"] == 384


def test_a_first_format_splitter_still_loads(tmp_path):
    """The first splitters' json had no "reach" (they joined near ends only): reach 0."""
    from flax import nnx

    from jdraw.planner import splits

    splits.save(splits.Splitter(hidden=8, patches=False, reach=0, rngs=nnx.Rngs(0)), tmp_path)
    meta = json.loads((tmp_path / "splitter.json").read_text())
    del meta["reach"]
    (tmp_path / "splitter.json").write_text(json.dumps(meta))
    back = splits.load(tmp_path)
    assert back.reach == 0 and back.join_net.l1.kernel.shape[0] == splits.NEAR_GEOMETRY


@pytest.mark.parametrize("seed", [0])
def test_bundled_checkpoint_draws_held_out_characters(kanji_set, seed):
    rng = np.random.default_rng(seed)
    idx = rng.choice(kanji.split_indices(kanji_set, "test"), 16, replace=False)
    demos = [demo.sample(kanji_set, int(i)) for i in idx]
    plan = jdraw.plan(np.stack([d.target for d in demos]))
    s = metrics.score(demos, plan)
    assert s["pixel_acc"] >= PIXEL_ACC_FLOOR and s["truncated"] == 0.0
    assert s["stroke_acc"] >= STROKE_ACC_FLOOR, s


def test_readme_example_plans(tmp_path):
    from jdraw import cli

    png, svg = tmp_path / "s.png", tmp_path / "s.svg"
    assert (
        cli.main(
            [
                "draw",
                str(EXAMPLE),
                "--png",
                str(png),
                "--svg",
                str(svg),
                "--no-progress",
            ]
        )
        == 0
    )
    assert png.stat().st_size > 0 and "<polyline" in svg.read_text()


def test_eval_writes_results_and_figure(tmp_path):
    from jdraw.evaluation import evaluate

    res = evaluate.evaluate(
        None,
        out_dir=tmp_path,
        name="t",
        n_random=3,
        full_test=False,
        batch=4,
        progress=False,
        figure_chars=2,
        variants=("cv2",),
        variant_chars=2,
    )
    saved = json.loads((tmp_path / "t.json").read_text())
    assert saved["test_random"]["n"] == 3 and res["train_random"]["pixel_acc"] >= PIXEL_ACC_FLOOR
    assert set(saved["test_cv2"]["by_order"]) == {"model", "xy", "ranker"}
    assert saved["test_cv2"]["n"] == 2
    assert (tmp_path / "t_fig3.png").stat().st_size > 0
