"""The paper's two-scale model in Flax NNX (§III, Fig. 2).

A residual encoder (a first 3x3 conv to 16 channels, then four pre-activation
blocks BN -> ReLU -> Conv3x3, twice, with channels (16, 16), (16, 16),
(16, 32), (32, 64)) whose convolutions are shared by the two models; each model
has its own first layer and its own batch-norm layers (the local model sees
windows around the pen, the global model whole canvases: their activation
statistics differ, so sharing running averages would be wrong for both).

* Local model: encoder -> 5x5x64 at the pen -> LSTM -> touch (sigmoid) and a
  25-way move.
* Global model: encoder -> 1x1 conv -> 100x100 logits for the next start.

The local encoder runs in one of two exact ways:

* ``full``: encode the whole 100x100 local state with SAME convolutions, then
  cut the 5x5 patch at the pen with ``lax.dynamic_slice`` (zero outside).
* ``window``: the patch depends only on a ``(5 + 2r)``-square window of the
  input (``r`` = 9, the receptive radius), so encode that window alone with
  VALID convolutions, zeroing every convolution's input outside the canvas so
  borders match SAME padding. Same numbers in inference mode, ~20x cheaper.
"""

from __future__ import annotations

from collections.abc import Sequence

import jax
import jax.numpy as jnp
from flax import nnx

from jdraw.model.start_net import NOT_CANDIDATE, StartNet, start_candidates
from jdraw.state import GLOBAL_CHANNELS, LOCAL_CHANNELS

PATCH = 5
BLOCKS = ((16, 16), (16, 16), (16, 32), (32, 64))


def receptive_radius(blocks: Sequence[Sequence[int]] = BLOCKS) -> int:
    """Pixels each side that one output of the encoder sees (3x3 convs only)."""
    return 1 + 2 * len(blocks)


def window_size(blocks: Sequence[Sequence[int]] = BLOCKS) -> int:
    return PATCH + 2 * receptive_radius(blocks)


def _conv(x, w, b, padding):
    y = jax.lax.conv_general_dilated(
        x, w, (1, 1), padding, dimension_numbers=("NHWC", "HWIO", "NHWC")
    )
    return y + b


class ConvParams(nnx.Module):
    """A ``k x k`` convolution's kernel ``[k, k, cin, cout]`` and bias."""

    def __init__(self, cin: int, cout: int, k: int, rngs: nnx.Rngs):
        init = nnx.initializers.he_normal()
        self.w = nnx.Param(init(rngs.params(), (k, k, cin, cout)))
        self.b = nnx.Param(jnp.zeros((cout,)))


class Trunk(nnx.Module):
    """The residual blocks' convolutions, shared by both models."""

    def __init__(self, blocks: Sequence[Sequence[int]], rngs: nnx.Rngs):
        self.blocks = tuple((int(a), int(b)) for a, b in blocks)
        self.conv_a = nnx.List([ConvParams(ci, co, 3, rngs) for ci, co in self.blocks])
        self.conv_b = nnx.List([ConvParams(co, co, 3, rngs) for _, co in self.blocks])
        self.proj = nnx.List(
            [ConvParams(ci, co, 1, rngs) if ci != co else None for ci, co in self.blocks]
        )


class Norms(nnx.Module):
    """One model's batch norms: two per block and a final one."""

    def __init__(self, blocks: Sequence[Sequence[int]], rngs: nnx.Rngs):
        bn = lambda c: nnx.BatchNorm(c, momentum=0.99, rngs=rngs)
        self.a = nnx.List([bn(ci) for ci, _ in blocks])
        self.b = nnx.List([bn(co) for _, co in blocks])
        self.final = bn(blocks[-1][1])


def encode(x, first: ConvParams, trunk: Trunk, norms: Norms, inside=None):
    """The residual encoder.

    Args:
      x: ``[N, S, S, C]`` state images, zero outside the canvas.
      inside: ``None`` for SAME convolutions over the whole input, or
        ``bool [N, S, S]`` marking canvas pixels for the VALID window form;
        then the output is ``[N, S - 2r, S - 2r, 64]``, zero off the canvas.

    Returns:
      ``[N, S', S', 64]`` features.
    """
    valid = inside is not None
    pad = "VALID" if valid else "SAME"
    size = x.shape[1]

    def mask(o):  # canvas mask after ``o`` 3x3 convolutions, ``[N, s, s, 1]``
        if not valid:
            return None
        return inside[:, o : size - o, o : size - o, None]

    def conv(h, p, o):
        if valid:
            h = h * mask(o)
        return _conv(h, p.w[...], p.b[...], pad)

    def norm(bn, h, o):
        return jax.nn.relu(bn(h, mask=mask(o)))

    h = conv(x, first, 0)
    o = 1
    for i in range(len(trunk.blocks)):
        y = conv(norm(norms.a[i], h, o), trunk.conv_a[i], o)
        y = conv(norm(norms.b[i], y, o + 1), trunk.conv_b[i], o + 1)
        sc = h[:, 2:-2, 2:-2] if valid else h
        if trunk.proj[i] is not None:
            sc = _conv(sc, trunk.proj[i].w[...], trunk.proj[i].b[...], "VALID")
        h = sc + y
        o += 2
    h = norm(norms.final, h, o)
    return h * mask(o) if valid else h


def extract(features: jax.Array, pen: jax.Array) -> jax.Array:
    """The ``[5, 5, C]`` patch of ``features [H, W, C]`` centred at ``pen`` (x, y), zero-padded."""
    h = PATCH // 2
    padded = jnp.pad(features, ((h, h), (h, h), (0, 0)))
    return jax.lax.dynamic_slice(padded, (pen[1], pen[0], 0), (PATCH, PATCH, features.shape[-1]))


class LSTM(nnx.Module):
    """An LSTM cell split so the input projection can run on packed steps."""

    def __init__(self, din: int, hidden: int, rngs: nnx.Rngs):
        self.hidden = hidden
        self.wi = nnx.Linear(din, 4 * hidden, rngs=rngs)
        self.wh = nnx.Linear(hidden, 4 * hidden, use_bias=False, rngs=rngs)

    def project(self, v):
        """``[..., din] -> [..., 4H]``."""
        return self.wi(v)

    def init_carry(self, batch_shape=()):
        z = jnp.zeros((*batch_shape, self.hidden))
        return (z, z)

    def step(self, carry, xp):
        """One step from the projected input ``xp [..., 4H]``; returns ``(carry, h)``."""
        c, h = carry
        i, f, g, o = jnp.split(xp + self.wh(h), 4, axis=-1)
        c = jax.nn.sigmoid(f + 1.0) * c + jax.nn.sigmoid(i) * jnp.tanh(g)
        h = jax.nn.sigmoid(o) * jnp.tanh(c)
        return (c, h), h


class FeedForward(nnx.Module):
    """Ablation (a): the LSTM replaced by one fully connected layer."""

    def __init__(self, din: int, hidden: int, rngs: nnx.Rngs):
        self.hidden = hidden
        self.wi = nnx.Linear(din, hidden, rngs=rngs)

    def project(self, v):
        return self.wi(v)

    def init_carry(self, batch_shape=()):
        return (jnp.zeros((*batch_shape, 0)),)

    def step(self, carry, xp):
        return carry, jax.nn.relu(xp)


class DrawModel(nnx.Module):
    """Local and global models with a shared trunk.

    Args:
      hidden: LSTM width.
      core: ``"lstm"`` or ``"fc"`` (ablation a).
      extraction: ``"late"`` (the paper's model) or ``"initial"`` (ablation b:
        cut a 5x5 patch of the state first, then encode it).
      kind: ``"two_scale"`` (the paper's model) or ``"global_only"`` (ablation
        c: the global model looped on itself, with a touch head; see
        :mod:`jdraw.planner.global_only`).
    """

    def __init__(
        self,
        *,
        hidden: int = 256,
        blocks: Sequence[Sequence[int]] = BLOCKS,
        core: str = "lstm",
        extraction: str = "late",
        kind: str = "two_scale",
        global_net: str = "paper",
        start_widths: Sequence[int] = (8, 16, 32, 64),
        start_full_res_convs: int = 0,
        start_half_res: bool = False,
        rngs: nnx.Rngs,
    ):
        if core not in ("lstm", "fc"):
            raise ValueError(f"core must be 'lstm' or 'fc', got {core!r}")
        if extraction not in ("late", "initial"):
            raise ValueError(f"extraction must be 'late' or 'initial', got {extraction!r}")
        if kind not in ("two_scale", "global_only"):
            raise ValueError(f"kind must be 'two_scale' or 'global_only', got {kind!r}")
        if global_net not in ("paper", "unet") or (global_net == "unet" and kind != "two_scale"):
            raise ValueError(
                f"global_net must be 'paper', or 'unet' with kind 'two_scale', got {global_net!r}"
            )
        self.extraction = extraction
        self.kind = kind
        self.trunk = Trunk(blocks, rngs)
        width = self.trunk.blocks[-1][1]
        self.local_first = ConvParams(LOCAL_CHANNELS, self.trunk.blocks[0][0], 3, rngs)
        self.local_norms = Norms(self.trunk.blocks, rngs)
        cls = LSTM if core == "lstm" else FeedForward
        self.core = cls(PATCH * PATCH * width, hidden, rngs)
        self.touch_head = nnx.Linear(hidden, 1, rngs=rngs)
        self.move_head = nnx.Linear(hidden, 25, rngs=rngs)
        self.global_net = global_net
        if global_net == "unet":  # ours: whole-canvas view, ~1/8 of the cost
            self.start_net = StartNet(
                GLOBAL_CHANNELS,
                start_widths,
                full_res_convs=start_full_res_convs,
                half_res=start_half_res,
                rngs=rngs,
            )
        else:
            self.global_first = ConvParams(GLOBAL_CHANNELS, self.trunk.blocks[0][0], 3, rngs)
            self.global_norms = Norms(self.trunk.blocks, rngs)
            self.global_head = ConvParams(width, 1, 1, rngs)
        # Ablation (c) decides pen up/down from pooled global features.
        self.global_touch = nnx.Linear(2 * width, 1, rngs=rngs) if kind == "global_only" else None

    @property
    def window(self) -> int:
        """Side of the local input window the model needs."""
        return PATCH if self.extraction == "initial" else window_size(self.trunk.blocks)

    def local_features(self, windows, inside):
        """``[N, S, S, 3]`` windows (see :meth:`window`) -> ``[N, 5 * 5 * 64]``."""
        if self.extraction == "initial":
            f = encode(windows, self.local_first, self.trunk, self.local_norms)
        else:
            f = encode(windows, self.local_first, self.trunk, self.local_norms, inside=inside)
        return f.reshape(f.shape[0], -1)

    def local_features_full(self, states, pens):
        """Naive form: encode ``[N, 100, 100, 3]`` states whole, cut at ``pens [N, 2]``."""
        f = encode(states, self.local_first, self.trunk, self.local_norms)
        return jax.vmap(extract)(f, pens).reshape(states.shape[0], -1)

    def heads(self, h):
        """``h [..., H]`` -> ``(move logits [..., 25], touch logit [...])``."""
        return self.move_head(h), self.touch_head(h)[..., 0]

    def global_logits(self, states, restrict: bool = True):
        """``[N, 100, 100, 4]`` -> next-start logits ``[N, 100, 100]``.

        ``restrict``: for our start model, planning prefers the pixels where a
        stroke can begin (:func:`jdraw.model.start_net.start_candidates`); training
        scores the raw logits. The paper's model is never restricted.
        """
        if self.global_net == "unet":
            logits = self.start_net(states)
            if restrict:
                ok = start_candidates(states)
                logits = jnp.where(ok, logits, logits + NOT_CANDIDATE)
            return logits
        f = encode(states, self.global_first, self.trunk, self.global_norms)
        return _conv(f, self.global_head.w[...], self.global_head.b[...], "VALID")[..., 0]

    def position_and_touch(self, states):
        """Ablation (c): states ``[N, 100, 100, 4]`` -> (position ``[N, 100, 100]``, touch ``[N]``).

        The next pen position's logits and the pen-down logit, the latter from
        the canvas's pooled features.
        """
        f = encode(states, self.global_first, self.trunk, self.global_norms)
        pos = _conv(f, self.global_head.w[...], self.global_head.b[...], "VALID")[..., 0]
        pooled = jnp.concatenate([f.mean((1, 2)), f.max((1, 2))], -1)
        return pos, self.global_touch(pooled)[..., 0]


def build(cfg, seed: int = 0) -> DrawModel:
    """A model from a config's ``model`` section (hidden, core, extraction, kind, global_net)."""
    return DrawModel(
        hidden=int(cfg.hidden),
        blocks=tuple(tuple(b) for b in cfg.get("blocks", BLOCKS)),
        core=str(cfg.get("core", "lstm")),
        extraction=str(cfg.get("extraction", "late")),
        kind=str(cfg.get("kind", "two_scale")),
        global_net=str(cfg.get("global_net", "paper")),
        start_widths=tuple(cfg.get("start_widths", (8, 16, 32, 64))),
        start_full_res_convs=int(cfg.get("start_full_res_convs", 0)),
        start_half_res=bool(cfg.get("start_half_res", False)),
        rngs=nnx.Rngs(seed),
    )
