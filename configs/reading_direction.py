"""The reading-direction detector (jdraw.images.reading): right-to-left script or not.

Command:
  python train.py --config configs/reading_direction.py --workdir runs/reading_direction
  python train.py --config configs/reading_direction.py:ensemble --workdir runs/rd_ens \
      --config.out=runs/rd_ens/out  # three detectors, seeds 0-2, read as one
  python train.py --config configs/reading_direction.py:elastic --workdir runs/rd_elastic \
      --config.out=runs/rd_elastic/out  # windows bent by a smooth random field
  python train.py --config configs/reading_direction.py:elastic_cjk --workdir runs/rd_ecjk \
      --config.out=runs/rd_ecjk/out  # the same, with more CJK faces to fit on

The ``ensemble`` variant (with hand-printed Latin, ``print_words``) fits one
detector per seed of ``members``, each in ``WORKDIR/seed<s>`` and resumable on
its own (one that has written its ``out`` is read back), then sets the threshold
of their mean logit on the validation fonts (jdraw.train.reading.combine). It was
measured and not bundled (docs/reading_direction.md, 2026-12-08). So was the
``elastic`` variant (``elastic = 2.0``: half of each batch's windows bent by
jdraw.train.reading_data.bend), alone and read as one with the bundled detector.
``elastic_cjk`` also fits on the CJK faces of jdraw.data.cjk_faces.DETECTOR_MORE_TRAIN
(``more_cjk``; apt-get install fonts-wqy-microhei fonts-cwtex-ming
fonts-arphic-bkai00mp fonts-takao-mincho fonts-vlgothic fonts-unfonts-extra).

Needs the fonts of jdraw.data.fonts.DETECTOR_TRAIN, DETECTOR_VAL and DETECTOR_EVAL:
  apt-get install culmus culmus-fancy fonts-kacst fonts-kacst-one fonts-arabeyes \
    fonts-farsiweb fonts-hosny-thabit fonts-sil-lateef fonts-sil-harmattan \
    fonts-ukij-uyghur fonts-sil-scheherazade fonts-dejavu-core fonts-liberation \
    fonts-kaushanscript fonts-urw-base35 fonts-sil-andika fonts-sil-charis \
    fonts-sil-gentium fonts-comfortaa fonts-noto-core fonts-noto-cjk \
    fonts-freefont-ttf fonts-sil-ezra fonts-hosny-amiri fonts-dancingscript \
    fonts-breip fonts-dkg-handwriting fonts-humor-sans fonts-comic-neue fonts-lobstertwo \
    fonts-arphic-ukai fonts-arphic-uming fonts-wqy-zenhei fonts-ipafont-gothic \
    fonts-ipafont-mincho fonts-unfonts-core fonts-nanum \
    fonts-ldco fonts-freefarsi fonts-lemonada fonts-sil-alkalami fonts-nafees fonts-paktype

Random letters of 15 scripts set in the training fonts (words_per_script
drawings per left-to-right script, rtl_words_per_script per right-to-left
one) and random sketches are cut into line windows, each line also stretched
along x (kept in the workdir, so a rerun fits at once); a small CNN is fitted
on them, each batch distorted (``augment``), with an Orbax checkpoint every 500
steps. Its pooling and threshold are set on drawings in the validation fonts
(at most max_false_rtl of left-to-right ones read right to left), and it is
written to ``out``, the package's
jdraw/assets/reading, with its provenance and its accuracy on drawings set
in the held-out fonts.

Wall time and result: see jdraw/assets/reading/direction.json ("seconds",
"held_out_accuracy") and docs/reading_direction.md.
"""

import ml_collections


def get_config(variant: str | None = None) -> ml_collections.ConfigDict:
    """The bundled detector's config; ``"ensemble"``: three fitted apart, read as one;
    ``"elastic"``: windows also bent as other fonts and hands bend letters;
    ``"elastic_cjk"``: the same, with more CJK faces to fit on."""
    c = ml_collections.ConfigDict()
    c.name = "reading_direction"
    c.stage = "reading"
    c.seed = 0
    c.out = "jdraw/assets/reading"
    c.words_per_script = 400  # drawings per left-to-right script
    c.rtl_words_per_script = 2500  # drawings per right-to-left script
    c.sketches = 600
    c.cursive_words = 600  # drawings of joined-up English (EMS Allure train words), left to right
    c.print_words = 0  # hand-printed Latin (print_sample); 600 not kept (docs/reading_direction.md)
    c.min_height = 30  # px, ink height of a drawing
    c.max_height = 160
    c.two_words = 0.3  # fraction of drawings with two words
    c.marker = 0.4  # fraction drawn with a thick outline (a marker)
    c.slant = 0.4  # fraction sheared like slanted handwriting
    c.stretch = 1.4  # lines also cut stretched along x by a factor in [1/stretch, stretch]
    c.width = 64  # px, window width (windows are reading.WINDOW = 32 px high)
    # A line image fits its letter bodies; "all" (marks too) measured worse
    # (docs/reading_direction.md, 2026-12-06).
    c.span = "tall"
    c.channels = (16, 32, 48, 64)
    c.steps = 6000
    c.batch = 256
    c.learning_rate = 3e-3
    c.augment = 1.0  # strength of jdraw.train.reading.augment's distortions (0: thickening only)
    c.elastic = 0.0  # px: half of the windows bent by a smooth random field (reading_data.bend)
    c.more_cjk = False  # also fit on jdraw.data.cjk_faces.DETECTOR_MORE_TRAIN's CJK faces
    c.pool = "choose"  # window pooling: "logit", "prob", or "choose" on the validation fonts
    c.val_words_per_font = 20  # drawings per validation font, for the threshold
    c.max_false_rtl = 0.0  # left-to-right validation drawings allowed to read rtl
    c.eval_words_per_font = 12
    c.members = ()  # seeds: one detector each, read as one (jdraw.train.reading.combine)
    if variant == "ensemble":
        c.print_words = 600
        c.members = (0, 1, 2)
    elif variant in ("elastic", "elastic_cjk"):
        c.elastic = 2.0
        c.more_cjk = variant == "elastic_cjk"
    elif variant is not None:
        raise ValueError(
            f"unknown variant {variant!r}; expected 'ensemble', 'elastic' or 'elastic_cjk'"
        )
    return c


def tiny() -> ml_collections.ConfigDict:
    """A few drawings and steps: what the tests run."""
    c = get_config()
    c.words_per_script = 2
    c.rtl_words_per_script = 2
    c.sketches = 2
    c.cursive_words = 2
    c.print_words = 2
    c.steps = 3
    c.batch = 16
    c.val_words_per_font = 1
    c.eval_words_per_font = 1
    return c
