"""Training the stroke ranker (:mod:`jdraw.planner.ranker`) on the tracer's own strokes.

The tracer (a planner bundle) plans augmented training characters; each drawn
stroke is labelled with the KanjiVG stroke it matches, and the ranker learns
KanjiVG's order and direction from those noisy strokes. The labelled examples
are saved in the workdir as they are made, so an interrupted run resumes
where it stopped; the ranker itself trains in seconds.
"""

from __future__ import annotations

import json
import pathlib
import time

import jax
import jax.numpy as jnp
import numpy as np
import optax
from flax import nnx

from jdraw.data import demos as demo
from jdraw.data import variants
from jdraw.planner import ranker


def examples(drawn_strokes, ref_images, ref_points, iou: float = 0.5):
    """Labels the tracer's strokes of one character with the reference's order.

    Each drawn stroke takes the index of the reference stroke it overlaps
    most (IoU at least ``iou``; others are left out). Pairs of strokes that
    match different reference strokes become order examples; each matched
    stroke becomes a heading example (its start nearer the reference start).

    Returns:
      ``(pairs [P, PAIR_FEATURES] a-before-b inputs, their swapped inputs,
      heading feats [H, F], reversed feats [H, F], heading labels [H],
      the drawing's context for each pair [P, C] and each heading [H, C])``
      (:func:`jdraw.planner.stroke_tokens.context`; a ranker without context
      leaves the last two out).
    """
    if not drawn_strokes:
        return None
    tk = ranker.tokens(drawn_strokes)
    imgs = np.zeros((len(tk.paths), *ref_images.shape[1:]), bool)
    for k, p in enumerate(tk.paths):
        imgs[k, p[:, 1], p[:, 0]] = True
    d = imgs.reshape(len(imgs), -1).astype(np.float64)
    t = ref_images.reshape(len(ref_images), -1).astype(np.float64)
    inter = d @ t.T
    union = d.sum(1)[:, None] + t.sum(1)[None] - inter
    m = np.where(union > 0, inter / np.maximum(union, 1), 0.0)
    best, ok = m.argmax(1), m.max(1) >= iou
    idx = np.flatnonzero(ok)
    first, second = [], []
    for a in idx:
        for b in idx:
            if best[a] < best[b]:
                first.append(a)
                second.append(b)
    first, second = np.asarray(first, int), np.asarray(second, int)
    x_ab = ranker.pair_inputs(tk.feats, tk.rel, first, second)
    x_ba = ranker.pair_inputs(tk.feats, tk.rel, second, first)
    lab = []
    for a in idx:
        rp = np.asarray(ref_points[best[a]], float)
        s = tk.paths[a][0]
        lab.append(np.linalg.norm(s - rp[0]) <= np.linalg.norm(s - rp[-1]))
    ctx = ranker.drawing_context(tk)
    tile = lambda k: np.repeat(ctx[None], k, 0)
    return (
        x_ab,
        x_ba,
        tk.feats[idx],
        tk.rfeats[idx],
        np.asarray(lab, np.float32),
        tile(len(x_ab)),
        tile(len(idx)),
    )


def train_ranker(
    data,
    *,
    steps: int = 3000,
    batch: int = 512,
    lr: float = 3e-3,
    seed: int = 0,
    context: bool = False,
    hidden: int = 64,
    heading_draw=None,
):
    """Fits a :class:`Ranker` on stacked :func:`examples` (numpy arrays); returns it and logs.

    ``context``: the ranker also sees each drawing's context (``data``'s last two arrays).
    ``heading_draw``: ``(groups [H] int, p [G] float)``, each heading's set and
    each set's share of a batch's headings (:func:`heading_shares`); ``None``:
    headings drawn uniformly, as pairs always are.
    """
    x_ab, x_ba, f, rf, lab = data[:5]
    if context:
        if len(data) < 7:
            raise ValueError(
                "a ranker with context needs examples made with their context: "
                "these predate it; remove the workdir's examples/ to make them again"
            )
        cp, ch = data[5], data[6]
        x_ab, x_ba = np.concatenate([x_ab, cp], -1), np.concatenate([x_ba, cp], -1)
        f, rf = np.concatenate([f, ch], -1), np.concatenate([rf, ch], -1)
    model = ranker.Ranker(hidden, context=context, rngs=nnx.Rngs(seed))
    tx = optax.adam(lr)
    graphdef, params = nnx.split(model, nnx.Param)
    opt = tx.init(params)

    def loss_fn(params, xa, xb, hf, hr, hl):
        m = nnx.merge(graphdef, params)
        po = m.pair(xa, xb)  # label: a before b, always 1 here (pairs come ordered)
        lo = jnp.mean(optax.sigmoid_binary_cross_entropy(po, jnp.ones_like(po)))
        ho = m.heading(hf, hr)
        lh = jnp.mean(optax.sigmoid_binary_cross_entropy(ho, hl))
        return lo + lh, (jnp.mean(po > 0), jnp.mean((ho > 0) == (hl > 0.5)))

    @jax.jit
    def step(params, opt, xa, xb, hf, hr, hl):
        (loss, accs), g = jax.value_and_grad(loss_fn, has_aux=True)(params, xa, xb, hf, hr, hl)
        upd, opt = tx.update(g, opt, params)
        return optax.apply_updates(params, upd), opt, loss, accs

    rng = np.random.default_rng(seed)
    if heading_draw is not None:
        groups, share = heading_draw
        members = [np.flatnonzero(groups == g) for g in range(len(share))]
    logs = []
    for s in range(steps):
        pi = rng.integers(len(x_ab), size=batch)
        if heading_draw is None:
            hi = rng.integers(len(f), size=batch)
        else:
            counts = rng.multinomial(batch, share)
            hi = np.concatenate([m[rng.integers(len(m), size=c)] for m, c in zip(members, counts)])
        # Show each pair in both orders: the net learns an antisymmetric score.
        params, opt, loss, accs = step(params, opt, x_ab[pi], x_ba[pi], f[hi], rf[hi], lab[hi])
        if s % 500 == 0 or s == steps - 1:
            logs.append(
                {
                    "step": s,
                    "loss": float(loss),
                    "pair_acc": float(accs[0]),
                    "heading_acc": float(accs[1]),
                }
            )
    nnx.update(model, params)
    return model, logs


def traced_chunk(cfg, ks, pool, kind: str, k: int, salt: int = 0):
    """Chunk ``k`` of ``cfg.chunk`` augmented training characters and their strokes.

    ``kind="traced"``: drawn as ``cfg.get("styles")`` says (:func:`jdraw.data.variants.sample`)
    and planned by ``cfg.tracer`` (its own noisy strokes); ``"demo"``: KanjiVG's
    strokes as they are. ``salt`` (:func:`jdraw.data.mix.salt`) keeps another
    set's draws apart from KanjiVG's, which stay as they were; ``cfg.tracer_split``
    (``jdraw.plan``'s ``split=``: a bool, or a folder holding a splitter) cuts and
    joins the tracer's strokes first. Returns the
    demonstrations and each one's strokes.
    """
    from jdraw.planner import plan as api

    seed = [int(cfg.seed), k, int(kind == "demo")] + ([salt] if salt else [])
    rng = np.random.default_rng(seed)
    styles = variants.weights(cfg.get("styles", None) if kind == "traced" else None)
    demos = [
        demo.sample(ks, int(rng.choice(pool)), rng, float(cfg.augment))
        if styles is None
        else variants.sample(ks, int(rng.choice(pool)), rng, float(cfg.augment), styles)
        for _ in range(cfg.chunk)
    ]
    if kind == "traced":
        targets = np.stack([d.target for d in demos])
        drawn = api.plan(
            targets,
            checkpoint=cfg.tracer,
            order="model",
            split=cfg.get("tracer_split", False),
        ).strokes
    else:
        drawn = [d.strokes for d in demos]
    return demos, drawn


def chunk_jobs(cfg) -> list[tuple[str, str, int]]:
    """``(set, kind, k)`` of every chunk: KanjiVG's, then ``cfg.extra``'s (``{name: chars}``)."""
    jobs = [("kanji", "demo", k) for k in range(int(np.ceil(cfg.get("demo_chars", 0) / cfg.chunk)))]
    jobs += [("kanji", "traced", k) for k in range(int(np.ceil(cfg.chars / cfg.chunk)))]
    for name, chars in dict(cfg.get("extra", None) or {}).items():
        jobs += [(name, "traced", k) for k in range(int(np.ceil(chars / cfg.chunk)))]
    return jobs


def chunk_path(workdir: pathlib.Path, name: str, kind: str, k: int) -> pathlib.Path:
    """Where chunk ``k`` goes; KanjiVG's keep the names they had before other sets."""
    tag = kind if name == "kanji" else f"{kind}_{name}"
    return workdir / "examples" / f"{tag}_{k:04d}.npz"


def made_chunks(cfg, workdir, label, progress: bool = True) -> list[pathlib.Path]:
    """Traces every chunk of :func:`chunk_jobs` not yet saved; ``label(demos, drawn)`` -> parts.

    One npz per chunk, written whole or not at all, so an interrupted run resumes.
    """
    from jdraw.data import mix

    workdir = pathlib.Path(workdir)
    (workdir / "examples").mkdir(parents=True, exist_ok=True)
    jobs = chunk_jobs(cfg)
    sets: dict = {}
    it = jobs
    if progress:
        from tqdm import tqdm

        it = tqdm(jobs, desc="examples", unit="chunk")
    paths = []
    for name, kind, k in it:
        path = chunk_path(workdir, name, kind, k)
        paths.append(path)
        if path.exists():
            continue
        if name not in sets:
            sets[name] = mix.load(name, progress=progress)
        ks, pool = sets[name]
        demos, drawn = traced_chunk(cfg, ks, pool, kind, k, salt=mix.salt(name))
        parts = [p for p in label(demos, drawn) if p is not None]
        write_chunk(path, parts)
    return paths


def make_examples(cfg, workdir, progress: bool = True) -> list[pathlib.Path]:
    """Labelled examples in chunks of ``cfg.chunk`` augmented training characters.

    ``cfg.chars`` KanjiVG characters are planned by the tracer (its own noisy
    strokes), drawn as ``cfg.get("styles")`` says if given
    (:func:`jdraw.data.variants.sample`); ``cfg.get("demo_chars", 0)`` more
    contribute KanjiVG's strokes as they are; ``cfg.get("extra")`` adds other
    sets (:mod:`jdraw.data.mix`).
    """

    def label(demos, drawn):
        return [
            examples(s, ranker.stroke_masks(d.strokes), d.strokes) for d, s in zip(demos, drawn)
        ]

    return made_chunks(cfg, workdir, label, progress=progress)


def write_chunk(path: pathlib.Path, parts) -> None:
    """Saves per-character tuples of arrays, stacked, as one npz: there whole or not at all."""
    arrays = [np.concatenate([p[i] for p in parts]) for i in range(len(parts[0]))]
    tmp = path.with_suffix(".tmp.npz")
    np.savez(tmp, *arrays)
    tmp.rename(path)


def read_chunks(paths, n: int) -> tuple[np.ndarray, ...]:
    """The ``n`` arrays of every chunk :func:`write_chunk` saved, stacked."""
    parts = []
    for p in paths:
        with np.load(p) as z:
            parts.append([z[f"arr_{i}"] for i in range(n)])
    return tuple(np.concatenate([p[i] for p in parts]) for i in range(n))


def set_groups(paths, names) -> tuple[np.ndarray, np.ndarray]:
    """Each pair's and heading's set name (``names[i]`` for chunk ``paths[i]``), in
    :func:`load_examples`' order."""
    pg, hg = [], []
    for p, name in zip(paths, names):
        with np.load(p) as z:
            pg += [name] * len(z["arr_0"])
            hg += [name] * len(z["arr_2"])
    return np.asarray(pg), np.asarray(hg)


def shares_of(groups: np.ndarray, shares, known=None) -> tuple[np.ndarray, np.ndarray]:
    """``(index [N] int, p [G] float)``: each example's set (``groups [N]``, names) as
    an index into the sorted names of the sets present, and each set's share of a batch.

    ``shares`` maps a set's name to its share; the sets it leaves out share the
    rest by their number of examples. A set it names must be one of ``known``
    (the config's sets; default: those present); one that is known but gave no
    examples (a tracer too poor to match any stroke) is left out and the
    shares of the rest scaled up.
    """
    sets = sorted(set(groups.tolist()))
    known = set(sets) if known is None else set(known)
    unknown = set(shares) - known
    if unknown:
        raise ValueError(f"shares name sets that are not trained on: {sorted(unknown)}")
    fixed = {k: float(v) for k, v in dict(shares).items()}
    if sum(fixed.values()) > 1 or any(v < 0 for v in fixed.values()):
        raise ValueError(f"shares {fixed}: each >= 0, summing to <= 1")
    rest = 1.0 - sum(fixed.values())
    free = [k for k in sets if k not in fixed]
    n_free = sum(int((groups == k).sum()) for k in free)
    p = np.asarray(
        [fixed[k] if k in fixed else rest * (groups == k).sum() / max(n_free, 1) for k in sets]
    )
    return np.searchsorted(np.asarray(sets), groups), p / p.sum()


def heading_shares(paths, names, shares) -> tuple[np.ndarray, np.ndarray]:
    """``(groups [H], p [G])`` for :func:`train_ranker`'s ``heading_draw``: each heading's
    set (``names[i]`` for chunk ``paths[i]``) and each set's share (:func:`shares_of`)."""
    return shares_of(set_groups(paths, names)[1], shares, known=names)


def load_examples(paths, context: bool = False) -> tuple[np.ndarray, ...]:
    """Stacked :func:`examples` of every chunk; the context arrays too if ``context``."""
    try:
        return read_chunks(paths, 7 if context else 5)
    except KeyError as e:  # a chunk made before examples carried their context
        raise ValueError(
            f"{pathlib.Path(paths[0]).parent}: examples made before they carried their "
            "drawing's context; delete them to remake them"
        ) from e


def seed_members(cfg, fit_one, combine):
    """``(net, logs)``: ``fit_one(seed)`` for seeds ``cfg.seed`` to ``cfg.seed + cfg.members - 1``.

    One member is returned as fitted; more as ``combine(nets)`` (their mean, an
    ensemble), with one list of logs per member. The ranker's and the splitter's
    stages both fit their members this way.
    """
    members = int(cfg.get("members", 1))
    if members < 1:
        raise ValueError(f"members must be 1 or more, got {members}")
    fitted = [fit_one(int(cfg.seed) + k) for k in range(members)]
    if members == 1:
        return fitted[0]
    return combine([m for m, _ in fitted]), [lg for _, lg in fitted]


def fit_members(data, cfg, heading_draw=None):
    """``(ranker, logs)``: :func:`train_ranker` with ``cfg``'s settings, ``cfg.members`` times.

    Member ``k`` is fitted with seed ``cfg.seed + k``; more than one are returned as
    their :func:`jdraw.planner.ranker.ensemble`, with one list of logs per member.
    """

    def fit_one(seed):
        return train_ranker(
            data,
            steps=int(cfg.steps),
            batch=int(cfg.batch),
            lr=float(cfg.learning_rate),
            seed=seed,
            context=bool(cfg.get("context", False)),
            hidden=int(cfg.get("hidden", 64)),
            heading_draw=heading_draw,
        )

    return seed_members(cfg, fit_one, ranker.ensemble)


def train(cfg, workdir, progress: bool = True) -> dict:
    """Makes (or reuses) the examples, fits the ranker, writes it into ``cfg.out``.

    With ``cfg.members`` = k > 1, k rankers are fitted on the same examples
    (:func:`fit_members`) and written as one, their mean.
    """
    workdir = pathlib.Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    (workdir / "config.json").write_text(cfg.to_json_best_effort(indent=2) + "\n")
    t0 = time.time()
    paths = make_examples(cfg, workdir, progress=progress)
    t1 = time.time()
    context = bool(cfg.get("context", False))
    data = load_examples(paths, context)
    draw = None
    if cfg.get("heading_shares", None):
        names = [name for name, _, _ in chunk_jobs(cfg)]
        draw = heading_shares(paths, names, dict(cfg.heading_shares))
    model, logs = fit_members(data, cfg, draw)
    t2 = time.time()
    result = {
        "pairs": int(len(data[0])),
        "headings": int(len(data[2])),
        "trace_s_this_call": t1 - t0,
        "fit_s": t2 - t1,
        "logs": logs,
    }
    out = ranker.save(model, cfg.out, provenance={"config": json.loads(cfg.to_json()), **result})
    ranker.save(model, workdir / "ranker")
    (workdir / "result.json").write_text(json.dumps(result, indent=2) + "\n")
    result["out"] = str(out)
    return result
