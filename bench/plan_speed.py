"""Characters per second of ``jdraw.plan``: the old vmap loop against the slot loop.

  nice -n 10 python bench/plan_speed.py [--checkpoint DIR] [--chars 64] [--stream 512]
  nice -n 10 python bench/plan_speed.py --rss 1000   # peak memory, 1,000 images in one call

Same weights, same characters for every batch size (held-out KanjiVG test
split, no augmentation); batch ``b`` is ``jdraw.plan`` called on ``b`` images
at a time, as a user calls it (canonical form, planner and stroke ranker),
"stream" one call on all of ``--stream`` images. Checks that both loops give identical
actions. Prints the work per character (global-model starts and local-model
steps evaluated), the measured cost of one global sub-batch and one local
step, and the speed those costs allow. Takes about 10 minutes on a shared
2-core CPU.
"""

from __future__ import annotations

import argparse
import resource
import sys
import time

import jax
import jax.numpy as jnp
import numpy as np
from flax import nnx

import jdraw
from jdraw import state
from jdraw.data import demos as demo
from jdraw.data import kanji
from jdraw.planner import loop as planner
from jdraw.planner import plan as api
from jdraw.planner import slots


def chars(n: int) -> np.ndarray:
    ks = kanji.load(progress=False)
    idx = kanji.split_indices(ks, "test")
    idx = np.resize(idx, n)  # cycles past the 1,000 test characters
    return np.stack([demo.sample(ks, int(i)).target for i in idx])


_STREAMS = []  # the slot loop's work, recorded around api.stream_plan
_stream_plan = api.stream_plan


def _recorded(*args, **kw):
    out = _stream_plan(*args, **kw)
    _STREAMS.append(out)
    return out


api.stream_plan = _recorded


def run(targets, batch, loop, checkpoint, width, k):
    """Plans ``targets`` ``batch`` at a time; returns chars/s, actions and the work done.

    ``checkpoint`` is a folder or ``None`` (the bundled default), as a user
    names it, so the bundle's stroke ranker runs too.
    """
    kw = dict(checkpoint=checkpoint, loop=loop, batch_size=width, global_batch=k)
    jdraw.plan(targets[:batch], **kw)  # compile
    n = (len(targets) // batch) * batch
    _STREAMS.clear()
    t = time.perf_counter()
    plans = [jdraw.plan(targets[i : i + batch], **kw) for i in range(0, n, batch)]
    dt = time.perf_counter() - t
    actions = [a[:m] for p in plans for a, m in zip(p.actions, p.lengths)]
    w = min(width, api._bucket(batch))
    return n / dt, actions, work(actions, batch, loop, w, k)


def work(actions, batch, loop, width, k):
    """Per character: global starts evaluated, global-model calls, local steps
    evaluated, starts used and local steps used (that moved or lifted)."""
    n = len(actions)
    strokes = [_strokes(a) for a in actions]
    used = sum(len(x) for x in strokes) / n, sum(sum(x) + len(x) for x in strokes) / n
    if loop == "slots":
        sums = [sum(int(getattr(o, f).sum()) for o in _STREAMS) for f in slots.Stream._fields[3:]]
        starts, calls, steps, local_rows, _ = sums
        return (
            calls * min(k, width) / n,
            calls / n,
            local_rows / n,
            starts / n,
            steps / n,
        )
    # Under vmap every image runs each stroke's body and each local step of the
    # batch's longest (a stroke's local steps counted as its moves + 1 lift);
    # the global model runs once per stroke on the whole batch.
    g = loc = calls = 0
    for i in range(0, n, batch):
        per = [_strokes(a) for a in actions[i : i + batch]]
        s = max(len(x) for x in per)
        g, calls = g + len(per) * s, calls + s
        loc += len(per) * sum(max((x[j] + 1 if j < len(x) else 0) for x in per) for j in range(s))
    return g / n, calls / n, loc / n, *used


def _strokes(a):
    """Moves per stroke of one plan's actions ``[n, 3]``."""
    starts = np.flatnonzero(a[:, 2] == 0)
    ends = np.append(starts[1:], len(a))
    return [int((a[s + 1 : e, 2] == 1).sum()) for s, e in zip(starts, ends)]


def per_call_costs(model, targets, width, k, reps=16):
    """Seconds for one global sub-batch of ``k`` starts and one local step of ``width`` slots.

    Each is timed as ``reps`` calls in a ``lax.fori_loop`` inside one jitted
    call, as in the planner's loop (no per-call dispatch), the best of a few.
    """
    limits = planner.Limits()
    policy = planner.model_policy()
    graphdef, st = nnx.split(model)
    labels = np.stack([state.component_labels(t) for t in targets[:width]])

    def loaded(st, targets, labels):
        m = nnx.merge(graphdef, st)
        load = lambda t, lab: slots.load(policy, m, (), t, lab, 0, limits.max_steps)
        return jax.vmap(load)(targets, labels)

    def looped(f, n):
        def g(st, s):
            m = nnx.merge(graphdef, st)
            body = lambda i, s: jax.vmap(lambda s: f(policy, m, s, limits))(s)
            return jax.lax.fori_loop(0, n, body, s)

        return jax.jit(g)

    def timed(f, s, samples=5):
        one, many = looped(f, 1), looped(f, reps + 1)
        jax.block_until_ready((one(st, s), many(st, s)))
        best = np.inf
        for _ in range(samples):  # the best of a few: a busy spell only slows
            t = time.perf_counter()
            jax.block_until_ready(one(st, s))
            t1 = time.perf_counter()
            jax.block_until_ready(many(st, s))
            best = min(best, (time.perf_counter() - t1 - (t1 - t)) / reps)
        return best

    def local(policy, m, s, limits):  # one local step of one image, as the slot loop runs it
        obs = slots.observe(policy, m, s)
        return slots.move(s, policy.decide(m, s.pstate, s.lstate, obs), limits)

    fresh = jax.jit(loaded)(st, jnp.asarray(targets[:width]), jnp.asarray(labels))
    t_glob = timed(slots.start, jax.tree.map(lambda a: a[:k], fresh))
    started = looped(slots.start, 1)(st, fresh)
    t_loc = timed(local, started)
    return t_glob, t_loc


def rss(n, checkpoint):
    """Plans ``n`` images in one call in this process; prints peak RSS and compilations."""
    targets = chars(n)
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    t = time.perf_counter()
    p = jdraw.plan(targets, checkpoint=checkpoint)
    dt = time.perf_counter() - t
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    print(
        f"{n} images: {dt:.1f} s ({n / dt:.2f} chars/s, compile included), peak RSS "
        f"{peak / 1024:.0f} MiB (before planning {before / 1024:.0f} MiB), "
        f"compilations {api._TRACES['plan']}, truncated {int(p.truncated.sum())}"
    )


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--checkpoint", default=None, help="bundle folder (default: the bundled model)")
    ap.add_argument("--chars", type=int, default=64, help="characters for batches 1, 8 and 64")
    ap.add_argument("--stream", type=int, default=512, help="images in the streamed call")
    ap.add_argument("--width", type=int, default=64, help="slots (jdraw.plan batch_size)")
    ap.add_argument("--global-batch", type=int, default=4, help="global sub-batch K")
    ap.add_argument("--rss", type=int, default=0, help="only: peak RSS for this many images")
    ap.add_argument("--rounds", type=int, default=2, help="interleaved rounds; best counts")
    ap.add_argument("--skip-old-stream", action="store_true", help="old loop: skip the stream row")
    args = ap.parse_args()
    if args.rss:
        rss(args.rss, args.checkpoint)
        return
    model = api.load_model(args.checkpoint)
    targets = chars(max(args.chars, args.stream))
    configs = [
        (loop, label, batch, n)
        for loop in ("vmap", "slots")
        for label, batch, n in (
            ("1", 1, args.chars),
            ("8", 8, args.chars),
            ("64", 64, args.chars),
            (f"{args.stream} streamed", args.stream, args.stream),
        )
        if batch <= n and not (loop == "vmap" and batch == args.stream)
    ]
    if not args.skip_old_stream:  # the old loop cannot stream: calls of 64
        configs.insert(3, ("vmap", f"{args.stream} streamed", 64, args.stream))
    # Rounds interleave the configurations so that a busy spell on a shared
    # machine does not land on one of them; the best round counts.
    best = {}
    for r in range(args.rounds):
        for loop, label, batch, n in configs:
            if "streamed" in label and r < args.rounds - 1:
                continue
            cps, acts, w = run(
                targets[:n], batch, loop, args.checkpoint, args.width, args.global_batch
            )
            if cps > best.get((loop, label), (0,))[0]:
                best[loop, label] = (cps, acts, w)
            print(f"  round {r}: {loop:>5} batch {label}: {cps:.2f} chars/s", file=sys.stderr)
    same = all(
        all(np.array_equal(a, b) for a, b in zip(best["vmap", lab][1], best["slots", lab][1]))
        for lab in {lab for _, lab in best}
        if ("vmap", lab) in best and ("slots", lab) in best
    )
    head = (
        "| loop | batch | chars/s | global starts/char (evaluated / used) | global calls/char | "
        "local steps/char (evaluated / used) |"
    )
    print(head)
    print("|" + " --- |" * 6)
    for (loop, label), (cps, _, (g, calls, loc, g_used, l_used)) in best.items():
        print(
            f"| {loop} | {label} | {cps:.2f} | {g:.1f} / {g_used:.1f} | {calls:.2f} | "
            f"{loc:.1f} / {l_used:.1f} |"
        )
    print(f"identical actions, old loop vs slot loop: {same}")
    if ("slots", "64") not in best:
        return
    s1, s64 = best["slots", "1"][0], best["slots", "64"][0]
    print(f"slot loop, batch 64 vs batch 1: {s64 / s1:.2f}x per character")

    # The speed the per-call costs allow at this width.
    w, k = args.width, args.global_batch
    t_g, t_l = per_call_costs(model, targets, w, k)
    t_g1, t_l1 = per_call_costs(model, targets, 1, 1)
    g, loc = best["slots", "64"][2][3:]
    per_char = g * t_g / k + loc * t_l / w
    per_char1 = g * t_g1 + loc * t_l1
    print(
        f"per call: global sub-batch of {k} {t_g * 1e3:.1f} ms ({t_g / k * 1e3:.1f} ms/start), "
        f"of 1 {t_g1 * 1e3:.1f} ms; local step of {w} slots {t_l * 1e3:.1f} ms "
        f"({t_l / w * 1e3:.2f} ms/slot), of 1 {t_l1 * 1e3:.2f} ms"
    )
    print(
        f"limit at batch 64: {g:.2f} starts x {t_g / k * 1e3:.1f} ms + {loc:.1f} steps x "
        f"{t_l / w * 1e3:.2f} ms = {per_char * 1e3:.0f} ms/char -> {1 / per_char:.1f} chars/s; "
        f"measured {s64:.2f} ({s64 * per_char:.0%} of it)"
    )
    print(
        f"limit at batch 1: {per_char1 * 1e3:.0f} ms/char -> {1 / per_char1:.1f} chars/s; "
        f"measured {s1:.2f} ({s1 * per_char1:.0%} of it: the rest is each call's own work, "
        f"canonical form, ranker, Python); the two limits differ "
        f"{per_char1 / per_char:.2f}x per character"
    )


if __name__ == "__main__":
    main()
