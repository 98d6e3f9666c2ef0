"""Training as several processes, on one machine or many: ``jax.distributed``.

Every process runs the same ``train.py`` command; one of them (process 0, at
the coordinator's address) is the coordinator. Each builds the same global
batch (a pure function of the seed and step, :mod:`jdraw.train.feed`) and
places its devices' rows of it; the step is one jitted program over all
processes' devices, its gradient averaged across them, so every process holds
the same parameters. Orbax writes each checkpoint once; process 0 alone writes
the metrics, the bundle and validates.

On CPUs the processes exchange arrays through gloo
(``jax_cpu_collectives_implementation``).
"""

from __future__ import annotations

import os

import jax
import numpy as np

ENV = ("JAX_COORDINATOR_ADDRESS", "JAX_NUM_PROCESSES", "JAX_PROCESS_ID")


def settings(
    coordinator: str | None = None,
    num_processes: int | None = None,
    process_id: int | None = None,
    environ=None,
) -> tuple[str, int, int] | None:
    """``(coordinator, num_processes, process_id)`` from the flags, else the environment.

    Flags win over ``JAX_COORDINATOR_ADDRESS``, ``JAX_NUM_PROCESSES`` and
    ``JAX_PROCESS_ID``. ``None`` when neither names a coordinator (one process).

    Raises:
      ValueError: a coordinator without a process count and id, or an id out of range.
    """
    env = os.environ if environ is None else environ
    coordinator = coordinator or env.get(ENV[0]) or None
    if num_processes is None and env.get(ENV[1]):
        num_processes = int(env[ENV[1]])
    if process_id is None and env.get(ENV[2]):
        process_id = int(env[ENV[2]])
    if coordinator is None:
        if num_processes not in (None, 1):
            raise ValueError(f"{num_processes} processes need a coordinator address (host:port)")
        return None
    if num_processes is None or process_id is None:
        raise ValueError(
            f"coordinator {coordinator}: also give the process count and this process's id "
            f"(--num_processes, --process_id or {ENV[1]}, {ENV[2]})"
        )
    if not 0 <= process_id < num_processes:
        raise ValueError(f"process id {process_id} is not in [0, {num_processes})")
    return coordinator, int(num_processes), int(process_id)


def initialize(
    coordinator: str | None = None,
    num_processes: int | None = None,
    process_id: int | None = None,
) -> bool:
    """Joins the processes of a run (see :func:`settings`); ``False`` when there is one."""
    s = settings(coordinator, num_processes, process_id)
    if s is None:
        return False
    if jax.config.jax_platforms in (None, "", "cpu") or os.environ.get("JAX_PLATFORMS") == "cpu":
        jax.config.update("jax_cpu_collectives_implementation", "gloo")
    jax.distributed.initialize(s[0], num_processes=s[1], process_id=s[2])
    return True


def is_lead() -> bool:
    """Whether this process writes the run's files (process 0)."""
    return jax.process_index() == 0


BARRIER_TIMEOUT_S = 24 * 3600  # process 0 may trace a splitter's examples for many minutes


def barrier(name: str) -> None:
    """Waits until every process reaches here (no-op with one process); ``name`` is unique.

    A barrier of the coordination service, which waits up to ``BARRIER_TIMEOUT_S``:
    a collective (``multihost_utils.sync_global_devices``) gives up when gloo's
    context has waited 30 s for a process busy elsewhere.
    """
    if jax.process_count() > 1:
        import orbax.checkpoint as ocp

        every = set(range(jax.process_count()))  # named: the service's barrier, not gloo's
        ocp.multihost.sync_global_processes(name, timeout=BARRIER_TIMEOUT_S, processes=every)


def global_array(x: np.ndarray, sharding) -> jax.Array:
    """A global array from ``x``, the same whole array on every process; each places its part."""
    x = np.asarray(x)
    return jax.make_array_from_callback(x.shape, sharding, lambda idx: x[idx])


def local_copy(tree):
    """``tree``'s replicated arrays as numpy arrays of this process's copy."""
    return jax.tree.map(lambda a: np.asarray(a.addressable_data(0)), tree)
