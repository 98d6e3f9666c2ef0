"""Evaluates a checkpoint on KanjiVG as the paper's §IV-A.

  python eval.py --name beyond_lean_reach --n 1   # the bundled default
  python eval.py --checkpoint jdraw/checkpoints/paper --name beyond_paper \
      --ranker jdraw/checkpoints/default
  python eval.py --checkpoint jdraw/checkpoints/paper --name paper --nocanonicalise \
      --variants=   # Table I, row 1, as measured

Writes results/NAME.json (pixel/stroke accuracy, stroke order over matched
and over all pairs, exact order, direction, drawn/true strokes, on 100 random
train and test characters, the whole test split, and the test split drawn by
OpenCV 1, 3 and 5 pixels wide; each as traced, x + y sorted and, where the
checkpoint has a ranker, ranked) and results/NAME_fig3.png. With --words=N (default
40, 0 skips) it also plans N cursive words of --words_split with jdraw.plan_image and
puts their scores under "cursive_words" (jdraw.evaluation.words).
"""

from absl import app, flags, logging

from jdraw.evaluation import evaluate, words

_CKPT = flags.DEFINE_string(
    "checkpoint", None, "Bundle folder or training workdir (default: bundled)."
)
_NAME = flags.DEFINE_string("name", "eval", "Result file stem under --out.")
_OUT = flags.DEFINE_string("out", "results", "Output folder.")
_N = flags.DEFINE_integer("n", 100, "Random characters from each of train and test.")
_FULL = flags.DEFINE_bool("full_test", True, "Also score the whole test split (1,000 characters).")
_BATCH = flags.DEFINE_integer("batch", 32, "Planning batch size.")
_SEED = flags.DEFINE_integer("seed", 0, "Which random characters.")
_VARIANTS = flags.DEFINE_list(
    "variants",
    ["cv2", "px3", "thick3"],
    "Other drawings of the test split (cv2, px3, px5, thick3 = px5, aa).",
)
_VCHARS = flags.DEFINE_integer("variant_chars", None, "Test characters for the variants (all).")
_CANON = flags.DEFINE_bool(
    "canonicalise", True, "Canonicalise inputs first (jdraw.plan's default)."
)
_JOIN = flags.DEFINE_enum(
    "join",
    "auto",
    ["auto", "yes", "no"],
    "Join strokes that go on through a junction (jdraw.planner.joins); auto: as the "
    "checkpoint says.",
)
_SPLIT = flags.DEFINE_string(
    "split",
    "auto",
    "Cut strokes at corners and join ends with the learned splitter (jdraw.planner.splits): "
    "auto (if the checkpoint has one), yes, no, or a folder holding another splitter.",
)
_LATIN = flags.DEFINE_integer(
    "latin", 4, "Drawings of each Latin dev glyph per style (jdraw.evaluation.latin); 0 skips."
)
_RANKER = flags.DEFINE_string(
    "ranker", None, "Folder with a stroke ranker to use instead of the checkpoint's own."
)
_WORDS = flags.DEFINE_integer(
    "words", 40, "Cursive words planned with jdraw.plan_image and scored; 0 skips."
)
_WORDS_SPLIT = flags.DEFINE_enum(
    "words_split", "val", ["train", "val", "test"], "Split of the cursive words."
)


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
        variants=tuple(_VARIANTS.value),
        variant_chars=_VCHARS.value,
        ranker_from=_RANKER.value,
        canonicalise=_CANON.value,
        join={"auto": None, "yes": True, "no": False}[_JOIN.value],
        split={"auto": None, "yes": True, "no": False}.get(_SPLIT.value, _SPLIT.value),
        latin_copies=_LATIN.value,
    )
    for style, m in res.get("latin_dev", {}).items():
        if isinstance(m, dict):
            print(
                f"latin_dev {style:5s} stroke {m['stroke_acc']:.4f}  order, all pairs "
                f"{m['order_all_pairs']:.4f}  direction {m['direction_agreement']:.4f}  "
                f"strokes/true {m['stroke_ratio']:.3f}  (n={m['n']})"
            )
    for k, r in res.items():
        if not isinstance(r, dict) or "by_order" not in r:
            continue
        for o, m in r["by_order"].items():
            print(
                f"{k:13s} {o:6s} pixel {m['pixel_acc']:.4f}  stroke {m['stroke_acc']:.4f}  "
                f"order {m['order_agreement']:.4f} (all pairs {m['order_all_pairs']:.4f}, "
                f"exact {m['exact_order']:.3f})  direction {m['direction_agreement']:.4f}  "
                f"strokes/true {m['stroke_ratio']:.3f}  (n={m['n']})"
            )
    if _WORDS.value:
        w = words.evaluate_words(
            _WORDS_SPLIT.value,
            _WORDS.value,
            checkpoint=_CKPT.value,
            split_strokes={"yes": True, "no": False}.get(_SPLIT.value),
        )
        words.add_to_results(f"{_OUT.value}/{_NAME.value}.json", w)
        print(words.summary(w))


if __name__ == "__main__":
    app.run(main)
