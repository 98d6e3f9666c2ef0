"""As many of the accepted joins as can be made: one join given up for two.

:func:`jdraw.planner.joins.join_pairs` takes the end pairs the join net
accepts best first, and skips one that would reuse an end or close a ring.
In joined-up writing a greedy take can block two joins with one: the
connector of a word accepted into the loop of an e takes the end that the
loop's own return needed, and that return's other end is left free. This
gives up such a join for two accepted ones wherever the two ends it freed
each find a free partner (an augmenting path of three pairs, as in a
matching), and no ring of strokes is closed. Each swap makes one more join,
so it stops after at most as many swaps as there are strokes.
"""

from __future__ import annotations

End = tuple[int, bool]  # (stroke, at its end rather than its start)
Pair = tuple[int, bool, int, bool]


def _ends(p: Pair) -> tuple[End, End]:
    return (p[0], p[1]), (p[2], p[3])


def greedy(pairs, n: int) -> list[Pair]:
    """The pairs :func:`jdraw.planner.joins.join_pairs` would join, in order:
    each end once, no ring among the ``n`` strokes."""
    parent = list(range(n))

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    used, out = set(), []
    for p in pairs:
        a, b = _ends(p)
        if a in used or b in used or find(a[0]) == find(b[0]):
            continue
        parent[find(a[0])] = find(b[0])
        used |= {a, b}
        out.append(tuple(p))
    return out


def most_joins(pairs, n: int) -> list[Pair]:
    """The pairs to join among ``pairs`` (best first) for ``n`` strokes: the greedy
    take (:func:`greedy`), then while some taken pair can be given up for two of
    ``pairs`` that use its two ends and two free ones without a ring, that swap
    (the first taken pair, then the best pairs, that allow one)."""
    pairs = [tuple(p) for p in pairs]
    at: dict[End, list[Pair]] = {}
    for p in pairs:
        for e in _ends(p):
            at.setdefault(e, []).append(p)
    taken = greedy(pairs, n)
    while True:
        swap = _swap(taken, at, n)
        if swap is None:
            return taken
        taken = swap


def _swap(taken: list[Pair], at: dict, n: int) -> list[Pair] | None:
    used = {e for p in taken for e in _ends(p)}
    for t, old in enumerate(taken):
        x, y = _ends(old)
        rest = taken[:t] + taken[t + 1 :]
        chain = _chains(rest, n)
        for q1 in at.get(x, ()):
            u = _other(q1, x)
            if q1 == old or u in used or chain[x[0]] == chain[u[0]]:
                continue
            for q2 in at.get(y, ()):
                v = _other(q2, y)
                if q2 in (q1, old) or v in used or v == u:
                    continue
                # a ring unless q2 links two chains that stay apart once q1 is made
                a, b = (chain[e[0]] for e in (y, v))
                if a != b and {a, b} != {chain[x[0]], chain[u[0]]}:
                    return rest + [q1, q2]
    return None


def _chains(pairs, n: int) -> list[int]:
    """Each of the ``n`` strokes' chain (a label) once ``pairs`` are joined."""
    parent = list(range(n))

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for p in pairs:
        parent[find(p[0])] = find(p[2])
    return [find(k) for k in range(n)]


def _other(p: Pair, e: End) -> End:
    a, b = _ends(p)
    return b if a == e else a
