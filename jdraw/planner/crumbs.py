"""Crumbs: strokes of a pixel or two that a plan should not lift the pen for.

The local model now and then leaves a pixel or two at a junction or a sharp corner
and comes back for it later: a pen lift of its own for a dot of ink no person would
lift for. The join stage's last step (:func:`jdraw.planner.splits.edit_plan`) and the
tiler's stitcher (:mod:`jdraw.tiling.stitch`) draw such a crumb as part of the stroke
it touches (:func:`absorb_crumbs`), a stroke that adds no more than a crumb's pixels
first cut down to them (:func:`trim_to_new_ink`, which the stitcher also uses to trim
a tile's fragments and drop those that add nothing).
"""

from __future__ import annotations

import numpy as np

from jdraw.planner.ranker import reverse

CRUMB = 5  # pixels: a stroke this short that touches another is drawn as part of it


def absorb_crumbs(strokes, crumb: int = CRUMB) -> list:
    """Strokes with each crumb drawn as part of a stroke it touches.

    A crumb is a stroke of at most ``crumb`` pixels, most often a pixel or two
    the local model left at a junction and came back for: a pen lift of its
    own for a dot of ink no person would lift for. When one of its ends
    touches (8-neighbour) another stroke, it is drawn there: on from that
    stroke's end if it touches an end, else as a detour out along it and back
    from the point it touches. No pixel is added or lost. Crumbs that touch
    nothing (a dot) stay strokes of their own. A stroke that inks at most
    ``crumb`` pixels no other stroke inks is cut down to them first
    (:func:`trim_to_new_ink`).
    """
    from jdraw.planner.stroke_tokens import path_pixels

    S = trim_to_new_ink([np.asarray(s, np.float64).reshape(-1, 2) for s in strokes], crumb)
    # A path inks at least as many pixels as its box is long: only short ones are counted.
    size = [
        len(path_pixels(s)) if np.ptp(s, axis=0).max() < crumb else crumb + 1 + len(s) for s in S
    ]
    k = 0
    while k < len(S):
        if size[k] > crumb or len(S) < 2:
            k += 1
            continue
        c = S[k]
        host = None
        for j, p in enumerate(S):
            if j == k:
                continue
            for from_start in (True, False):
                d = np.abs(p - (c[0] if from_start else c[-1])).max(-1)
                i = int(d.argmin())
                if d[i] <= 1 and (host is None or size[j] > size[host[0]]):
                    host = (j, i, from_start)
        if host is None:
            k += 1
            continue
        j, i, from_start = host
        out = c if from_start else reverse(c)  # the crumb from the end touching the host
        p = S[j]
        if i == len(p) - 1:
            S[j] = np.concatenate([p, out])
        elif i == 0:
            S[j] = np.concatenate([reverse(out), p])
        else:
            back = reverse(out)
            S[j] = np.concatenate([p[: i + 1], out, back[1:], p[i:]])
        size[j] += size[k]
        del S[k], size[k]
        k = 0  # a host may now touch another crumb
    return S


def trim_to_new_ink(strokes, crumb: int = CRUMB, *, drop: bool = False, ends: bool = False) -> list:
    """Strokes with each one that adds at most ``crumb`` pixels cut down to those pixels.

    When the local model cuts a sharp corner by a pixel (an N's apex), the
    start model comes back for that pixel and the local model runs on from it
    along the line already drawn, up to its bound of moves that ink nothing
    new: a pen lift and a line drawn twice for a pixel or two. A tile's
    planner, retracing a stroke's end to reach a pixel or two beyond it, does
    the same. Such a stroke is replaced by the pixels only it inks, in the
    order it first reaches them, when they form one 8-connected run;
    :func:`absorb_crumbs` then draws them as part of the stroke they touch.
    Strokes adding least go first, and those they free are counted again.

    With ``ends``, a stroke whose new pixels are in several runs loses the
    pixels others ink from its two ends only, so it stays one path. A stroke
    that adds nothing is set to ``None`` with ``drop``, else left as it is
    (:func:`jdraw.planner.splits.drop_covered` drops it). Strokes cut down are
    ``int64`` pixel paths. No pixel is lost.
    """
    from jdraw.planner.stroke_tokens import path_pixels

    S = list(strokes)
    if len(S) < 2:
        return S
    pix = [path_pixels(s) for s in S]
    lo = np.min([p.min(0) for p in pix], axis=0)
    pix = [p - lo for p in pix]  # pixels as ids, on a canvas of any size
    width = int(max(p[:, 0].max() for p in pix)) + 2
    ids = [np.unique(p[:, 1] * width + p[:, 0]) for p in pix]
    every, count = np.unique(np.concatenate(ids), return_counts=True)
    at = [np.searchsorted(every, p[:, 1] * width + p[:, 0]) for p in pix]
    new = [int((count[np.unique(a)] == 1).sum()) for a in at]
    for k in sorted((k for k in range(len(S)) if new[k] <= crumb), key=new.__getitem__):
        mine = count[at[k]] == 1  # others may have been cut down since
        if not (mine.any() or drop):
            continue
        keep = np.zeros(len(mine), bool)
        if mine.any():
            _, first = np.unique(at[k][mine], return_index=True)
            keep[np.flatnonzero(mine)[np.sort(first)]] = True
            run = pix[k][keep]
            if len(run) > 1 and np.abs(np.diff(run, axis=0)).max() > 1:
                if not ends:
                    continue
                i0, i1 = np.flatnonzero(mine)[[0, -1]]
                keep[:] = False
                keep[i0 : i1 + 1] = True
        count[np.unique(at[k])] -= 1  # the stroke's old pixels ...
        count[np.unique(at[k][keep])] += 1  # ... less those it keeps
        S[k] = pix[k][keep] + lo if keep.any() else None
    return S
