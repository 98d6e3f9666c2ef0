"""A cheap global model that sees the whole canvas: a small U-Net for the next start.

The paper's global model (3x3 convolutions, 64 channels at full resolution, a
1x1 head) gives each pixel's "start here" logit a 19x19 view, so it can learn
little beyond "start near the pen". This network goes down to a 13x13 grid and
back up with skips, adds coordinate channels and a pooled summary of the whole
canvas at the coarsest level, so every logit depends on every pixel of the
state, while the logits stay per pixel (starts stay exact).

Channels are few at full resolution, which is where the cost is: about 1/8 of
the paper's global encoder in multiply-adds (``bench/global_cost.py``).

On a CPU the full-resolution layers cost most of the time even when they are
a small part of the multiply-adds (a few channels over 10,000 pixels), so
``half_res=True`` starts at 50x50: 2x2 blocks of pixels become the channels
of one (space to depth), the network runs at 50, 25 and 13, and its last
layer gives four logits per block, one per pixel (depth to space), plus a
linear term of the pixel's own state channels. Logits stay per pixel.
"""

from __future__ import annotations

from collections.abc import Sequence

import jax
import jax.numpy as jnp
from flax import nnx

WIDTHS = (8, 16, 32, 64)  # channels at 100, 50, 25 and 13 pixels


def _conv(x, p, stride: int = 1):
    y = jax.lax.conv_general_dilated(
        x, p.w[...], (stride, stride), "SAME", dimension_numbers=("NHWC", "HWIO", "NHWC")
    )
    return y + p.b[...]


class _Conv(nnx.Module):
    def __init__(self, cin: int, cout: int, k: int, rngs: nnx.Rngs):
        self.w = nnx.Param(nnx.initializers.he_normal()(rngs.params(), (k, k, cin, cout)))
        self.b = nnx.Param(jnp.zeros((cout,)))


def coordinates(h: int, w: int) -> jax.Array:
    """``float32 [h, w, 2]``: x and y in [-1, 1]."""
    ys, xs = jnp.meshgrid(jnp.linspace(-1, 1, h), jnp.linspace(-1, 1, w), indexing="ij")
    return jnp.stack([xs, ys], -1)


def space_to_depth(x: jax.Array) -> jax.Array:
    """``[N, 2h, 2w, C] -> [N, h, w, 4C]``: each 2x2 block of pixels becomes one."""
    n, h, w, c = x.shape
    x = x.reshape(n, h // 2, 2, w // 2, 2, c).transpose(0, 1, 3, 2, 4, 5)
    return x.reshape(n, h // 2, w // 2, 4 * c)


def depth_to_space(x: jax.Array) -> jax.Array:
    """``[N, h, w, 4C] -> [N, 2h, 2w, C]``, the inverse of :func:`space_to_depth`."""
    n, h, w, c = x.shape
    x = x.reshape(n, h, w, 2, 2, c // 4).transpose(0, 1, 3, 2, 4, 5)
    return x.reshape(n, 2 * h, 2 * w, c // 4)


def _up(x, shape):
    """Doubles ``[N, h, w, C]`` by repeating pixels, cropped to ``shape`` (h', w')."""
    x = jnp.repeat(jnp.repeat(x, 2, axis=1), 2, axis=2)
    return x[:, : shape[0], : shape[1]]


class StartNet(nnx.Module):
    """``[N, 100, 100, C]`` global state -> ``[N, 100, 100]`` start logits.

    Args:
      in_channels: state channels (4 for :func:`jdraw.state.global_state`).
      widths: channels at each level; each level halves the side (100, 50, 25, 13;
        from 50 with ``half_res``).
      full_res_convs: extra 3x3 layers after the stem (at the first level).
      half_res: start at half the side (see the module's docstring).
    """

    def __init__(
        self,
        in_channels: int,
        widths: Sequence[int] = WIDTHS,
        *,
        full_res_convs: int = 0,
        half_res: bool = False,
        rngs: nnx.Rngs,
    ):
        widths = tuple(int(c) for c in widths)
        self.widths = widths
        self.half_res = bool(half_res)
        c0 = widths[0]
        cin = in_channels + 2  # and x, y
        self.stem = _Conv(4 * cin if half_res else cin, c0, 3, rngs)
        # More 3x3 layers at full resolution: sharper ends of strokes (exact starts).
        self.fine = nnx.List([_Conv(c0, c0, 3, rngs) for _ in range(full_res_convs)])
        self.down = nnx.List(
            [_Conv(a, b, 3, rngs) for a, b in zip(widths[:-1], widths[1:])]
        )  # stride 2
        self.mid = nnx.List([_Conv(c, c, 3, rngs) for c in widths[1:]])
        top = widths[-1]
        self.context = _Conv(2 * top, top, 1, rngs)  # pooled summary mixed back in
        # After concatenating the skip; 1x1 at full resolution, where pixels are many.
        self.up = nnx.List(
            [
                _Conv(b + a, a, 1 if i == 0 else 3, rngs)
                for i, (a, b) in enumerate(zip(widths[:-1], widths[1:]))
            ]
        )
        # With half_res: four logits per 2x2 block, and the pixel's own channels.
        self.head = _Conv(c0, 4 if half_res else 1, 1, rngs)
        self.pixel = _Conv(cin, 1, 1, rngs) if half_res else None

    def __call__(self, x: jax.Array) -> jax.Array:
        n, h, w, _ = x.shape
        if self.half_res and (h % 2 or w % 2):
            raise ValueError(f"half_res needs an even canvas side, got {h}x{w}")
        xy = jnp.broadcast_to(coordinates(h, w), (n, h, w, 2))
        x = jnp.concatenate([x, xy], -1)
        f = jax.nn.relu(_conv(space_to_depth(x) if self.half_res else x, self.stem))
        for fine in self.fine:
            f = jax.nn.relu(_conv(f, fine))
        skips = []
        for down, mid in zip(self.down, self.mid):
            skips.append(f)
            f = jax.nn.relu(_conv(f, down, stride=2))
            f = jax.nn.relu(_conv(f, mid))
        pooled = jnp.concatenate([f.mean((1, 2)), f.max((1, 2))], -1)[:, None, None]
        f = f + jax.nn.relu(
            _conv(jnp.broadcast_to(pooled, (*f.shape[:3], pooled.shape[-1])), self.context)
        )
        for i in reversed(range(len(self.up))):
            s = skips[i]
            f = jax.nn.relu(_conv(jnp.concatenate([_up(f, s.shape[1:3]), s], -1), self.up[i]))
        if self.half_res:
            return depth_to_space(_conv(f, self.head))[..., 0] + _conv(x, self.pixel)[..., 0]
        return _conv(f, self.head)[..., 0]


def start_candidates(states: jax.Array) -> jax.Array:
    """``bool [N, H, W]``: pixels where a stroke can begin, from global states.

    A stroke begins at a free end of the unwritten ink (at most one unwritten
    neighbour), on or beside ink already written (it continues from an
    earlier stroke), or at a junction of the drawing. On KanjiVG these hold
    99% of the true starts in a tenth of the pixels a start may take; the
    rest are inside a line, where an imprecise start leaves a fragment.

    Args:
      states: ``[N, H, W, 4]`` (loc, env, last, dif) as
        :func:`jdraw.state.global_state`.
    """
    visited = states[..., 1] > 0
    dif = states[..., 3] > 0
    target = visited | dif

    def around(m):  # 3x3 sums, centre excluded
        s = jax.lax.reduce_window(m.astype(jnp.int32), 0, jax.lax.add, (1, 3, 3), (1, 1, 1), "SAME")
        return s - m.astype(jnp.int32)

    near_visited = around(visited) + visited.astype(jnp.int32) > 0
    return (dif & (around(dif) <= 1)) | (target & near_visited) | (target & (around(target) >= 3))


# Added to the logits of pixels that are not candidates when planning: a start
# goes to a candidate whenever one is allowed, and the order among the others
# is kept for the rare drawing with none.
NOT_CANDIDATE = -1e4
