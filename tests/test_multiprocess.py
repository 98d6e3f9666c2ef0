"""train's loop as 2 local CPU processes (jax.distributed, gloo) equals 1 process.

Each process builds the same global batch and places its device's half; the
step averages the gradient across both. After a few steps both processes hold
the same parameters, and those of one process with two devices (the same
global batches, split the same way) up to TOL. (Against one process on one
device, the gradient's sum is associated differently, and Adam's first steps,
about lr * sign(gradient), turn a difference in the last bit of a near-zero
gradient into one of up to 2 lr: 3e-5 was seen on 2 of 102,400 weights.)
"""

import os
import pathlib
import socket
import subprocess
import sys

import numpy as np

ROOT = pathlib.Path(__file__).parent.parent
TOL = 1e-6  # absolute, on parameters of order 0.1 after 3 Adam steps of 3e-3
STEPS = 3

WORKER = """
import sys
import numpy as np
from flax import traverse_util
from jdraw.train import distributed, loop
from configs import tiny

n, pid, port, steps = (int(a) for a in sys.argv[1:5])
workdir, out = sys.argv[5:7]
if n > 1:
    assert distributed.initialize(f"127.0.0.1:{port}", n, pid)
cfg = tiny.get_config()
cfg.train.update(num_steps=steps, checkpoint_every=2)
cfg.eval.val_chars = 0
r = loop.train(cfg, workdir, progress=False, return_params=True)
flat = traverse_util.flatten_dict(r["params"])
np.savez(out, **{"/".join(map(str, k)): v for k, v in flat.items()})
"""


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _launch(n: int, pid: int, port: int, workdir, out, devices: int = 1) -> subprocess.Popen:
    env = {**os.environ, "JAX_PLATFORMS": "cpu", "PYTHONPATH": str(ROOT)}
    env["XLA_FLAGS"] = f"--xla_force_host_platform_device_count={devices}"
    args = [sys.executable, "-c", WORKER, *map(str, (n, pid, port, STEPS, workdir, out))]
    return subprocess.Popen(
        args, cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True
    )


def _load(path) -> dict:
    with np.load(path) as z:
        return {k: z[k] for k in z.files}


def test_two_processes_train_as_one(tmp_path):
    port = _free_port()
    procs = [_launch(2, i, port, tmp_path / "two", tmp_path / f"p{i}.npz") for i in range(2)]
    procs.append(_launch(1, 0, 0, tmp_path / "one", tmp_path / "one.npz", devices=2))
    for p in procs:
        out, _ = p.communicate(timeout=600)
        assert p.returncode == 0, out[-3000:]
    p0, p1, one = (_load(tmp_path / f) for f in ("p0.npz", "p1.npz", "one.npz"))
    assert p0.keys() == p1.keys() == one.keys() and len(p0) > 10
    from configs import tiny
    from jdraw.model import bundle
    from jdraw.model import network as M

    init = bundle.state_arrays(M.build(tiny.get_config().model, seed=0))
    saved = _load(tmp_path / "two" / "bundle" / "params.npz")  # process 0 wrote it
    moved = 0.0
    for k in p0:
        np.testing.assert_array_equal(p0[k], p1[k], err_msg=k)  # the same program, same data
        np.testing.assert_allclose(p0[k], one[k], atol=TOL, rtol=0, err_msg=k)
        np.testing.assert_array_equal(saved[k], p0[k], err_msg=k)
        moved = max(moved, float(np.abs(p0[k] - init[k]).max()))
    assert moved > 100 * TOL  # it trained: the agreement above is not of untouched parameters
    # Orbax saved each checkpoint once, for both processes: steps 2 and 3.
    steps = sorted(int(p.name) for p in (tmp_path / "two" / "checkpoints").iterdir())
    assert steps == [2, STEPS]
    assert not (tmp_path / "two" / "bundle.tmp").exists()
