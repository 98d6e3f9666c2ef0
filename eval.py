"""Evaluates a checkpoint on KanjiVG as the paper's §IV-A.

  python eval.py --checkpoint jdraw/checkpoints/default --name paper

Writes results/NAME.json (pixel/stroke accuracy, stroke order and direction
agreement on 100 random train and test characters and on the whole test
split) and results/NAME_fig3.png (target | trace | strokes by order).
"""

from absl import app, flags, logging

from jdraw import evaluate

_CKPT = flags.DEFINE_string(
    "checkpoint", None, "Bundle folder or training workdir (default: bundled)."
)
_NAME = flags.DEFINE_string("name", "eval", "Result file stem under --out.")
_OUT = flags.DEFINE_string("out", "results", "Output folder.")
_N = flags.DEFINE_integer("n", 100, "Random characters from each of train and test.")
_FULL = flags.DEFINE_bool("full_test", True, "Also score the whole test split (1,000 characters).")
_BATCH = flags.DEFINE_integer("batch", 32, "Planning batch size.")
_SEED = flags.DEFINE_integer("seed", 0, "Which random characters.")


def main(argv):
    del argv
    logging.set_verbosity(logging.WARNING)
    res = evaluate.evaluate(
        _CKPT.value,
        out_dir=_OUT.value,
        name=_NAME.value,
        n_random=_N.value,
        seed=_SEED.value,
        full_test=_FULL.value,
        batch=_BATCH.value,
    )
    for k in ("train_random", "test_random", "test_full"):
        if k in res:
            r = res[k]
            print(
                f"{k:13s} pixel {r['pixel_acc']:.4f}  stroke {r['stroke_acc']:.4f}  "
                f"order {r['order_agreement']:.4f}  "
                f"direction {r['direction_agreement']:.4f}  (n={r['n']})"
            )


if __name__ == "__main__":
    app.run(main)
