"""The bundled default planner (jdraw/checkpoints/default), all its stages in one config.

Command (every stage in order, each resumable; stages already done are skipped):
  python train.py --config configs/default.py --workdir runs/default
  python train.py --config configs/default.py:tiny --workdir /tmp/jdraw-default-tiny  # tests
  python train.py --config configs/default.py:mix --workdir runs/default_mix  # other scripts too

Writes runs/default/bundle, laid out as jdraw/checkpoints/default, which
``jdraw.plan(images, checkpoint="runs/default/bundle")`` loads. The stages
(``stage_order``), each in its own folder of the workdir:

1. ``local``: the local model (8/16/32-channel window encoder, 128-wide LSTM)
   trained from scratch on the paper's budget (3,600 steps, about 100,000
   strokes) of characters drawn five ways: jdraw's own lines (40%), OpenCV's
   1-pixel and anti-aliased lines and 3- and 5-pixel pens (15% each),
   canonicalised as ``jdraw.plan`` canonicalises its input. Adam 1e-3 with a
   cosine decay to 1e-4. Its start model does not train (weight 0).
2. ``start``: the whole-canvas start model, a U-Net at half resolution (16, 32,
   64 channels), trained beside the local model of stage 1, which does not move:
   1,500 steps of 32 stroke starts.
3. ``splitter``: the tracer (stage 2's bundle) plans 9,000 training characters
   drawn the same five ways, 1,500 Latin letters and 2,000 cursive fragments
   (jdraw.data.mix); two small MLPs, each corner and end pair also given the
   drawing's context and the pixels around it, learn where a drawn stroke should
   be cut and which stroke ends are one stroke, also ends up to 16 px apart
   linked through the ink, and in joined-up writing up to 40 moves back over a
   stroke's own line, where strokes are first cut at T's so that a branch can be
   drawn on the way (jdraw.train.splitter, jdraw.planner.splits). Three fitted
   with seeds 0, 1 and 2, bundled as one (``members``).
4. ``ranker``: the tracer plans 600 more characters (and 2,500 give KanjiVG's
   own strokes), 2,000 Latin letters, 400 cursive fragments and 1,000 printed
   words of Latin letters (jdraw.data.mix); the ranker (128 wide, each pair and
   stroke also given the drawing's context; cursive 15% and Latin letters 10%
   of every batch's heading examples) learns the writers' order and direction
   of its strokes (jdraw.train.ranker, jdraw.planner.ranker). Three rankers are
   fitted on the same examples, seeds 0, 1 and 2, and bundled as one that
   scores their mean (``members``; jdraw.planner.ranker.ensemble). Made alone by
   the ``ranker_only`` variant, with stages 1 and 2 as bundled.

A string ``"stage:NAME"`` in a stage's config is ``WORKDIR/NAME/bundle``.
These are the configs the bundled default was trained with, flattened (stages
1 and 2 were configs/lean.py and lean_start.py; stages 3 and 4 were made on
2026-12-05 with stages 1 and 2 as bundled, copied in as ``retrace`` says, by
``python train.py --config configs/default.py --workdir runs/default16``; the
bundle's json files keep the configs, and tests/test_pipeline.py compares them
with these; stage 4 was made again on 2026-12-06, three rankers as one, by the
``ranker_only`` variant, and stage 3 on 2026-12-07 by the ``joined_t_cuts`` and
``joined_t_cuts_patches`` variants, whose docstrings have the commands).
Result (docs/scripts.md, results/beyond_default_core.json: this bundle with the planner as
it is since joined-up writing is drawn at the size it was learned at, 2026-12-07;
results/beyond_default_trim.json and beyond_default_tcut.json before it).

Wall time on the 2-core CPU: about 58 min, the sum of the stages' recorded
times (training loops 2,105 s and 298 s; the bundle's json files), the splitter's
tracing (about 12 min, two processes sharing its chunks, and 29 s for its three fits)
and the ranker's (4 min 4 s of tracing and 49 s for its three fits),
not one fresh run of this command; loading,
compiling and validation add a few minutes. The tiny variant: 2 min 20 s and
2 min 39 s in two runs on the CPU shared with other jobs; its bundle plans, badly.
Result: README.md ("Beyond the paper") and docs/results.md.
"""

import pathlib

import ml_collections

STYLES = dict(clean=0.4, cv2=0.15, aa=0.15, px3=0.15, px5=0.15)  # drawing mix (jdraw.data.variants)


def local() -> ml_collections.ConfigDict:
    c = ml_collections.ConfigDict()
    c.name = "default/local"
    c.seed = 0
    c.model = ml_collections.ConfigDict(
        dict(
            hidden=128,
            core="lstm",
            extraction="late",
            kind="two_scale",
            global_net="unet",
            start_widths=(8, 16, 32, 64),  # untrained here; stage "start" replaces it
            start_full_res_convs=0,
            blocks=((8, 8), (8, 16), (16, 16), (16, 32)),
        )
    )
    c.data = ml_collections.ConfigDict(dict(augment=1.0, styles=dict(STYLES)))
    c.train = ml_collections.ConfigDict(
        dict(
            learning_rate=1e-3,
            final_lr_fraction=0.1,
            windows=512,  # encoder windows (local steps) per batch
            strokes=64,  # stroke slots per batch (LSTM rows)
            max_len=96,  # local steps per stroke
            strokes_per_char=4,
            train_local=True,
            global_batch=1,
            global_per_char=1,
            global_weight=0.0,
            init_from="",
            num_steps=3600,
            log_every=20,
            checkpoint_every=100,
        )
    )
    c.eval = ml_collections.ConfigDict(dict(every=500, val_chars=48))
    c.planner = ml_collections.ConfigDict(dict(join=True))
    return c


def start() -> ml_collections.ConfigDict:
    c = local()
    c.name = "default/start"
    c.model.start_widths = (16, 32, 64)
    c.model.start_half_res = True
    c.train.update(
        dict(
            init_from="stage:local",
            train_local=False,
            global_batch=32,
            global_per_char=4,
            global_weight=1.0,
            num_steps=1500,
        )
    )
    return c


def splitter() -> ml_collections.ConfigDict:
    """The bundled splitter stage (2026-12-07): ``joined_t_cuts_patches`` of
    :func:`splitter_12_05`. In drawings that ``plan_image`` plans as joined-up writing,
    ends up to 40 moves apart back over a stroke's own line are joined, strokes are
    first cut where another's end meets their line, and the nets also see the pixels
    around each corner and pair; three seeds as one."""
    c = splitter_12_05()
    c.patches = True  # the nets also see the ink and strokes around each corner and pair
    c.retrace = 40  # moves back over a stroke's own line an end pair may be linked
    c.retrace_where = "joined"  # ... learned in joined-up writing only,
    c.bundle_retrace = 0  # ... asked by plan_image there, never by jdraw.plan
    c.join_shares = dict(latin=0.1)  # of every batch's end pairs
    c.t_cuts = True  # a T's branch may be drawn on the way (jdraw.planner.corners.t_cuts)
    c.members = 3  # fitted with seeds 0, 1, 2 and bundled as one
    return c


def splitter_12_05() -> ml_collections.ConfigDict:
    """The splitter stage bundled from 2026-12-05 to 2026-12-07, on which every
    variant below but ``tiny`` and ``ranker_only`` builds."""
    c = ml_collections.ConfigDict()
    c.name = "default/splitter"
    c.stage = "splitter"
    c.seed = 0
    c.tracer = "stage:start"
    c.out = "stage:splitter"
    c.chars = 9000
    c.chunk = 100
    c.augment = 1.0
    c.styles = dict(STYLES)
    c.extra = dict(latin=1500, cursive=2000)  # jdraw.data.mix: school letters, cursive
    c.patches = False  # the nets see each corner's and join's geometry only
    c.context = True  # ... and the drawing's context (jdraw.planner.stroke_tokens.context)
    c.reach = 16  # pixels: ends linked through the ink (back over a drawn line, as cursive is)
    # No ``retrace`` key: ends further than ``reach`` are not linked (own_retrace sets it;
    # the bundled splitter was trained before the key existed, and absent reads as 0).
    c.hidden = 64
    c.steps = 3000
    c.batch = 512
    c.learning_rate = 3e-3
    return c


def ranker() -> ml_collections.ConfigDict:
    c = ml_collections.ConfigDict()
    c.name = "default/ranker"
    c.stage = "ranker"
    c.seed = 0
    c.tracer = "stage:start"
    c.out = "stage:ranker"
    c.chars = 600
    c.demo_chars = 2500
    # jdraw.data.mix: school letters, cursive, and printed words of school letters
    c.extra = dict(latin=2000, cursive=400, latin_words=1000)
    c.heading_shares = dict(cursive=0.15, latin=0.1)  # of every batch's heading examples
    c.chunk = 100
    c.augment = 1.0
    c.styles = dict(STYLES)
    c.hidden = 128
    c.context = True  # every pair and stroke also sees the drawing's context
    c.members = 3  # fitted with seeds 0, 1, 2 and bundled as one: their mean scores
    c.steps = 4000
    c.batch = 512
    c.learning_rate = 3e-3
    return c


def ranker_only() -> ml_collections.ConfigDict:
    """The ranker stage alone, traced by the bundled default's own models.

      python train.py --config configs/default.py:ranker_only --workdir runs/default_ranker
      cp runs/default_ranker/out/ranker.npz runs/default_ranker/out/ranker.json \\
          jdraw/checkpoints/default/

    made the bundled default's ranker (the tracer plans with ``order="model"`` and
    no splitter, so only its local and start models, stage 2's, are used).
    """
    c = ranker()
    c.tracer = str(
        pathlib.Path(__file__).resolve().parents[1] / "jdraw" / "checkpoints" / "default"
    )
    c.out = "runs/default_ranker/out"
    return c


def splitter_before(s: ml_collections.ConfigDict, extra=None) -> ml_collections.ConfigDict:
    """The splitter stage as it was before 2026-12-04 (no context, ``extra`` sets only,
    reach 8), with which the variants below were measured."""
    s.context = False
    s.reach = 8
    if extra:
        s.extra = dict(extra)
    else:
        del s["extra"]
    return s


def ranker_before(r: ml_collections.ConfigDict, extra=None) -> ml_collections.ConfigDict:
    """The ranker stage as it was before 2026-12-04 (64 wide, no context, ``extra`` sets
    only), with which the variants below were measured."""
    r.update(hidden=64, context=False)
    del r["heading_shares"]
    del r["members"]
    if extra:
        r.extra = dict(extra)
    else:
        del r["extra"]
    return r


def tiny(c: ml_collections.ConfigDict) -> ml_collections.ConfigDict:
    """Every stage on a budget of seconds: the pipeline's test, not a usable planner."""
    for name in ("local", "start"):
        s = c.stages[name]
        s.model.update(hidden=16, blocks=((4, 4), (4, 8), (8, 8), (8, 8)))
        s.train.update(windows=32, strokes=4, num_steps=4, log_every=2, checkpoint_every=2)
        s.eval.update(every=0, val_chars=0)
    c.stages.local.model.start_widths = (4, 8)
    c.stages.start.model.start_widths = (4, 8)
    c.stages.start.train.update(global_batch=2, global_per_char=2)
    for name in ("splitter", "ranker"):
        c.stages[name].update(chars=4, chunk=4, steps=20, batch=32)
        if "extra" in c.stages[name]:
            c.stages[name].extra = {k: 4 for k in c.stages[name].extra}
    c.stages.ranker.demo_chars = 4
    return c


def mix(c: ml_collections.ConfigDict) -> ml_collections.ConfigDict:
    """Splitter and ranker also trained on Latin letters and cursive words (docs/scripts.md).

    Not the bundled default: with the default's local and start models, its
    splitter traces all 9,000 KanjiVG characters plus ``extra`` other scripts
    (jdraw.data.mix) and its ranker orders the strokes that splitter leaves
    (runs/mix9k, 21 min of tracing). Latin dev glyphs: stroke accuracy 0.879
    -> 0.912, order over all pairs 0.881 -> 0.869, direction 0.821 -> 0.940;
    KanjiVG's test split: order over all pairs 0.9582 -> 0.9538, stroke
    accuracy 0.9870 -> 0.9865 (results/beyond_mix9k.json).
    """
    c.name = "default_mix"
    splitter_before(c.stages.splitter, dict(latin=1500, cursive=2000))
    ranker_before(c.stages.ranker, dict(latin=400, cursive=400))
    c.stages.ranker.tracer_split = "stage:splitter"
    return c


def scripts(c: ml_collections.ConfigDict) -> ml_collections.ConfigDict:
    """Every stage trained on the mix of scripts, the local model on scribbles too.

    The local model draws 40% of its characters from other sets
    (``data.extra``, jdraw.data.mix): cursive fragments 20%, scribbles
    (jdraw.data.scribbles: loops, cusps, crossings, retraces) 12%, Latin
    letters 8%; the start model the same without scribbles, whose starts mean
    nothing. The splitter traces all 9,000 KanjiVG characters plus 1,500 Latin
    and 2,000 cursive, the ranker 600 + 2,500 KanjiVG plus 400 of each, traced
    with that splitter. Not the bundled default: KanjiVG falls (test split,
    stroke accuracy 0.9870 -> 0.9818, order over all pairs 0.9582 -> 0.9508),
    for Latin stroke accuracy 0.879 -> 0.922 and cursive words 3.39 -> 2.92
    drawn strokes per written one. About 70 min on the 2-core CPU (local
    model 42 min, start model 8 min, splitter 18 min, ranker 2 min; runs/scripts).
    Results: docs/scripts.md.
    """
    c.name = "default_scripts"
    c.stages.local.data.extra = dict(cursive=0.2, scribble=0.12, latin=0.08)
    c.stages.start.data.extra = dict(cursive=0.2, latin=0.1)
    splitter_before(c.stages.splitter, dict(latin=1500, cursive=2000))
    ranker_before(c.stages.ranker, dict(latin=400, cursive=400))
    c.stages.ranker.tracer_split = "stage:splitter"
    return c


def tune(c: ml_collections.ConfigDict) -> ml_collections.ConfigDict:
    """The bundled default's local model trained on from where it is, on a mix of scripts.

    The local stage starts from ``jdraw/checkpoints/default`` (every array,
    its start model too, which this stage leaves as it is: its loss weighs
    nothing and it has no batch statistics) and trains 1,200 more steps at 0.3
    of the default's learning rate with 45% of its characters from other
    sets: cursive fragments 25%, scribbles 15%, Latin letters 5%. The splitter
    and ranker are traced with it, on KanjiVG alone as the default's are.
    Not the default: the local stage took 36 min on the 2-core CPU (runs/tune);
    with the default's splitter and ranker, 40 cursive val words go from 3.39 to
    3.29 drawn strokes per written one, and KanjiVG's test split falls (stroke
    accuracy 0.9870 -> 0.9830, order over all pairs 0.9582 -> 0.9546).
    Results: docs/scripts.md.
    """
    c.name = "default_tune"
    c.stage_order = ("local", "splitter", "ranker")
    loc = c.stages.local
    loc.model.update(start_widths=(16, 32, 64), start_half_res=True)  # the default's start net
    loc.data.extra = dict(cursive=0.25, scribble=0.15, latin=0.05)
    default = str(pathlib.Path(__file__).resolve().parents[1] / "jdraw" / "checkpoints" / "default")
    loc.train.update(init_from=default, learning_rate=3e-4, num_steps=1200)
    c.stages.splitter.tracer = "stage:local"
    c.stages.ranker.tracer = "stage:local"
    splitter_before(c.stages.splitter)
    ranker_before(c.stages.ranker)
    del c.stages["start"]
    return c


def tune_start(c: ml_collections.ConfigDict) -> ml_collections.ConfigDict:
    """``tune``, and then its start model trained on the same way, before the splitter.

    The start stage begins from the ``tune`` local stage's bundle (its start
    model is the default's) and trains 800 steps at 3e-4 with cursive fragments
    25% and Latin letters 10% of its characters; the local model does not move.
    Run in the ``tune`` workdir, it reuses that run's local stage. Not the
    default: 64 cursive val fragments on jdraw's lines go from 1.80 to 1.57
    traced strokes per written one, but 20 cursive val words through
    ``plan_image`` from 2.85 to 3.00. Results: docs/scripts.md.
    """
    c = tune(c)
    c.name = "default_tune_start"
    c.stage_order = ("local", "start", "splitter", "ranker")
    st = start()
    st.data.extra = dict(cursive=0.25, latin=0.1)
    st.train.update(learning_rate=3e-4, num_steps=800)
    c.stages.start = st
    c.stages.splitter.tracer = "stage:start"
    c.stages.ranker.tracer = "stage:start"
    return c


def retrace(c: ml_collections.ConfigDict) -> ml_collections.ConfigDict:
    """The default's tracer and ranker, with a splitter that may join ends 32 px apart.

    A cursive writer goes back over the line (an n's first stem, an a's oval:
    jdraw.data.cursive); the tracer lifts at the dead end instead and starts
    again where the line turned back, up to some 30 px away along the ink. The
    default's joiner links ends at most 8 moves apart through the ink
    (``reach``); this one may link them 32 moves apart, back over the drawn line,
    and learns when from KanjiVG's 9,000 characters plus 1,500 Latin and 2,000
    cursive ones (as ``mix``). The local and start stages are the default's,
    copied in before the run:

      mkdir -p runs/retrace/local runs/retrace/start
      cp -r jdraw/checkpoints/default runs/retrace/local/bundle
      cp -r jdraw/checkpoints/default runs/retrace/start/bundle
      python train.py --config configs/default.py:retrace --workdir runs/retrace

    The ranker stage is the default's config as it was before 2026-12-04
    (``ranker_before``), so it traces and fits that ranker again. Not the
    default: with that ranker, 40 cursive val words go from 3.39 to 2.50 drawn
    strokes per written one, but KanjiVG's order
    over all pairs falls from 0.9582 to 0.9521 and Latin letters lose order and
    direction. Results: docs/scripts.md.
    """
    c.name = "default_retrace"
    ranker_before(c.stages.ranker)
    splitter_before(c.stages.splitter, dict(latin=1500, cursive=2000))
    c.stages.splitter.reach = 32
    return c


def context(c: ml_collections.ConfigDict) -> ml_collections.ConfigDict:
    """``retrace``'s splitter reading the drawing's context, the ranker traced with it.

    Every corner, end pair and stroke pair the splitter and ranker score also
    carries a dozen numbers about the whole drawing (how many strokes, how long,
    how much they turn, how many close on themselves, how often they cross:
    jdraw.planner.stroke_tokens.context), so one net may learn that a corner in
    a drawing of few curved strokes is not cut as a kanji's is. The ranker is
    the default's config (it reads the context too) but orders the strokes this
    splitter leaves. The local and start stages are the default's, copied in as
    ``retrace`` says.
    """
    c = retrace(c)
    c.name = "default_context"
    c.stages.splitter.context = True
    c.stages.ranker = ranker()  # the default's ranker config of 2026-12-04:
    c.stages.ranker.extra = dict(latin=2000, cursive=400)  # no printed words,
    del c.stages.ranker["heading_shares"]  # headings drawn as the sets come
    del c.stages.ranker["members"]  # one ranker, as measured
    c.stages.ranker.tracer_split = "stage:splitter"
    return c


def own_retrace(c: ml_collections.ConfigDict) -> ml_collections.ConfigDict:
    """The default with a joiner that may go back 40 moves over a stroke's own line.

    Ends up to ``reach`` (16) moves apart through the ink are candidates as in the
    default; ends further apart, up to ``retrace`` (40) moves, only where that path
    goes back over one of the two strokes' own line (``jdraw.planner.ink_paths.own_line``),
    as a cursive writer runs back down the stem just drawn up. Latin letters give
    under 1% of the end pairs, so they are 10% of every batch's (``join_shares``).
    The local and start stages are the default's, copied in before the run:

      mkdir -p runs/own_retrace/local runs/own_retrace/start
      cp -r jdraw/checkpoints/default runs/own_retrace/local/bundle
      cp -r jdraw/checkpoints/default runs/own_retrace/start/bundle
      python train.py --config configs/default.py:own_retrace --workdir runs/own_retrace

    Not the default: 40 cursive val words go from 1.94 to 1.51 drawn strokes per
    written one, but the Latin dev glyphs' order over all pairs falls from 0.905 to
    0.774 (a Y or p drawn as one stroke, back over its stem) and KanjiVG val's from
    0.9608 to 0.9584. Results: docs/scripts.md.
    """
    c.name = "default_own_retrace"
    c.stages.splitter.retrace = 40
    c.stages.splitter.join_shares = dict(latin=0.1)
    return c


def joined_retrace(c: ml_collections.ConfigDict) -> ml_collections.ConfigDict:
    """``own_retrace``'s splitter, its long joins learned where ``plan_image`` asks for them.

    End pairs up to 40 moves apart back over a stroke's own line are examples only in
    drawings that ``plan_image`` plans as joined-up writing
    (``jdraw.tiling.layout.mostly_joined``; cursive fragments, few kanji), and the
    bundle keeps ``retrace`` 0, so ``jdraw.plan`` joins as the default does and
    ``plan_image`` asks for 40 in joined-up writing. The local and start stages are the
    default's, copied in as ``own_retrace`` says:

      mkdir -p runs/joined_retrace/local runs/joined_retrace/start
      cp -r jdraw/checkpoints/default runs/joined_retrace/local/bundle
      cp -r jdraw/checkpoints/default runs/joined_retrace/start/bundle
      python train.py --config configs/default.py:joined_retrace --workdir runs/joined_retrace

    Not the default: over three seeds (20 min of tracing in two processes, then 5 s a
    fit) cursive val words gain 0.02 of stroke accuracy (1.641 -> 1.605-1.650 drawn per
    written stroke) and lose 0.02 of direction, and Arabic words with the hint start in
    their rightmost letter in 0.87-0.91 of them (0.91), about what a second seed moves
    them. Results: docs/scripts.md.
    """
    c = own_retrace(c)
    c.name = "default_joined_retrace"
    c.stages.splitter.retrace_where = "joined"
    c.stages.splitter.bundle_retrace = 0
    return c


def joined_t_cuts(c: ml_collections.ConfigDict) -> ml_collections.ConfigDict:
    """``joined_retrace``'s splitter, its join net also taught to draw a T's branch on the way.

    In drawings that count as joined-up writing, strokes are cut where another
    stroke's end meets their line (``jdraw.planner.corners.t_cuts``) before the end
    pairs are labelled; the two parts of a cut are one line only where a reference
    stroke runs straight from one into the other (``jdraw.train.splitter.through``).
    The bundle's splitter cuts so where ``plan_image`` asks for joins back over the
    line. Three seeds as one (``members``). The local and start stages are the
    default's, copied in as ``own_retrace`` says:

      mkdir -p runs/tcut2/local runs/tcut2/start
      cp -r jdraw/checkpoints/default runs/tcut2/local/bundle
      cp -r jdraw/checkpoints/default runs/tcut2/start/bundle
      python train.py --config configs/default.py:joined_t_cuts --workdir runs/tcut2

    Not the default as it is (2026-12-07): fewer strokes on cursive words, but Arabic
    words start in their rightmost letter less often; with ``patches`` it is
    (``joined_t_cuts_patches``). Results: docs/scripts.md ("A T's branch drawn on the way").
    """
    c = joined_retrace(c)
    c.name = "default_joined_t_cuts"
    c.stages.splitter.t_cuts = True
    c.stages.splitter.members = 3
    return c


def joined_t_cuts_patches(c: ml_collections.ConfigDict) -> ml_collections.ConfigDict:
    """``joined_t_cuts`` with nets that also see the ink and the strokes around each
    corner and pair (``patches``): fitted on the same examples (runs/tcut2's, seconds).

    The bundled default's splitter stage since 2026-12-07 (:func:`splitter`): its
    splitter.npz and splitter.json were made by the python command in docs/scripts.md
    ("A T's branch drawn on the way") with this variant, on ``joined_t_cuts``'s traced
    examples. Results: docs/scripts.md ("The T-cut splitter that sees the patches").
    """
    c = joined_t_cuts(c)
    c.name = "default_joined_t_cuts_patches"
    c.stages.splitter.patches = True
    return c


def scribble_splitter(c: ml_collections.ConfigDict) -> ml_collections.ConfigDict:
    """The default with its splitter also traced on 3,000 scribbles (jdraw.data.scribbles).

    A scribble is one to three random pen-down curves with loops, cusps, crossings and
    turns back over the line: every cusp and loop inside one curve is a place not to
    cut, and every crossing of two curves one to join straight through. The local and
    start stages are the default's, copied in as ``own_retrace`` says:

      mkdir -p runs/scribble_splitter/local runs/scribble_splitter/start
      cp -r jdraw/checkpoints/default runs/scribble_splitter/local/bundle
      cp -r jdraw/checkpoints/default runs/scribble_splitter/start/bundle
      python train.py --config configs/default.py:scribble_splitter --workdir runs/scribble_splitter

    Not the default: it moved no dev figure by more than a word or two (40 cursive val
    words 1.94 -> 1.92 drawn strokes per written one; Latin dev order 0.917 -> 0.899
    with a 1-px tolerance; KanjiVG val order 0.9638 -> 0.9617). Results: docs/scripts.md.
    """
    c.name = "default_scribble_splitter"
    c.stages.splitter.extra = dict(latin=1500, cursive=2000, scribble=3000)
    return c


def splitter_members(c: ml_collections.ConfigDict) -> ml_collections.ConfigDict:
    """The default with five splitters as one (seeds 0 to 4 on the same traced examples).

    ``members``: jdraw.train.splitter.train fits that many and writes their mean
    (jdraw.planner.splits.ensemble), as the ranker stage does. The local and start
    stages are the default's, copied in as ``own_retrace`` says; the splitter's
    examples are the default's, so ``train.py`` retraces them (or reuses a workdir's).

    Not the default: KanjiVG val 0.9864 / 0.9638 -> 0.9876 / 0.9658 (stroke accuracy,
    order over all pairs), but the Latin dev glyphs' direction 0.899 -> 0.893 and
    strokes per true stroke 1.039 -> 1.071, within what one seed's splitter swings by
    (docs/scripts.md, 2026-12-06, evening).
    """
    c.name = "default_splitter_members"
    c.stages.splitter.members = 5
    return c


def cross_weight(c: ml_collections.ConfigDict) -> ml_collections.ConfigDict:
    """The default with its join net taught that a cursive "do not join" weighs 4 joins.

    In the cursive fragments nearly every end pair is "join"; the few that are not are
    mostly a t's or an x's cross and the line it crosses, which the default's join net
    scores near 0 (bench/cross_pairs.py) and the planner then joins. Here those pairs
    weigh 4 in the join loss (``join_negatives``; jdraw.train.splitter.negative_weights),
    on the default splitter's own examples. The local and start stages are the
    default's, copied in before the run:

      mkdir -p runs/cross_weight/local runs/cross_weight/start
      cp -r jdraw/checkpoints/default runs/cross_weight/local/bundle
      cp -r jdraw/checkpoints/default runs/cross_weight/start/bundle
      python train.py --config configs/default.py:cross_weight --workdir runs/cross_weight

    (its ranker stage then fits a ranker as the default's was made; what was measured
    is the bundled default with this stage's splitter.npz and splitter.json in place).

    Not the default: over two sets of three seeds, cursive words are drawn in the
    writer's order far more often (order over all pairs, 64 val words 0.55 -> 0.67) at
    the same stroke accuracy, but with more pen lifts (1.09 drawn per written stroke,
    1.67 per piece, against the bar's 1.5); KanjiVG val and the Latin dev glyphs move
    no more than a second set of seeds moves them. Results: docs/scripts.md ("Crosses
    weighed more in the join loss").
    """
    c.name = "default_cross_weight"
    c.stages.splitter.join_negatives = dict(cursive=4.0)
    return c


def get_config(variant: str | None = None) -> ml_collections.ConfigDict:
    c = ml_collections.ConfigDict()
    c.name = "default"
    c.stage_order = ("local", "start", "splitter", "ranker")
    c.stages = ml_collections.ConfigDict(
        dict(local=local(), start=start(), splitter=splitter(), ranker=ranker())
    )
    if variant == "tiny":
        c.name = "default_tiny"
        return tiny(c)
    if variant == "cross_weight":  # measured against the bundled splitter
        return cross_weight(c)
    if variant and variant != "ranker_only":  # measured against the splitter of 2026-12-05
        c.stages.splitter = splitter_12_05()
    if variant == "mix":
        return mix(c)
    if variant == "mix_tiny":
        return tiny(mix(c))
    if variant == "scripts":
        return scripts(c)
    if variant == "scripts_tiny":
        return tiny(scripts(c))
    if variant == "tune":
        return tune(c)
    if variant == "tune_start":
        return tune_start(c)
    if variant == "retrace":
        return retrace(c)
    if variant == "ranker_only":
        return ranker_only()
    if variant == "context":
        return context(c)
    if variant == "context_tiny":
        return tiny(context(c))
    if variant == "own_retrace":
        return own_retrace(c)
    if variant == "joined_retrace":
        return joined_retrace(c)
    if variant == "joined_t_cuts":
        return joined_t_cuts(c)
    if variant == "joined_t_cuts_patches":
        return joined_t_cuts_patches(c)
    if variant == "scribble_splitter":
        return scribble_splitter(c)
    if variant == "splitter_members":
        return splitter_members(c)
    if variant:
        raise ValueError(
            "configs/default.py: unknown variant "
            f"{variant!r} (tiny, mix, mix_tiny, scripts, scripts_tiny, tune, tune_start, "
            "retrace, context, context_tiny, own_retrace, joined_retrace, joined_t_cuts, "
            "joined_t_cuts_patches, scribble_splitter, splitter_members, cross_weight, ranker_only "
            "or none)"
        )
    return c
