"""The persistent XLA compilation cache: compile the planner once per machine.

Nearly all of a first ``jdraw draw`` is XLA compiling the planner's programs.
JAX can keep compiled programs on disk; :func:`enable` switches that on, in

* ``$JDRAW_CACHE_DIR`` when set (``off``, ``0``, ``none`` or ``false``: no cache),
* else ``$XDG_CACHE_HOME/jdraw``, else ``~/.cache/jdraw``,

inside a sub-folder named for the jax and jaxlib versions, so a cache written
by another version is never read (JAX's own keys include the versions too).
A folder that cannot be written does not stop planning: one warning, then
planning goes on without the cache. If the user has set JAX's own
``JAX_COMPILATION_CACHE_DIR`` (or ``jax_compilation_cache_dir``), that wins.
"""

from __future__ import annotations

import contextlib
import os
import pathlib
import tempfile
import warnings

ENV = "JDRAW_CACHE_DIR"
OFF = ("off", "0", "none", "false", "no")
_STATE: dict = {"done": False, "dir": None}


def cache_root() -> pathlib.Path | None:
    """The folder jdraw's caches live in, from the environment; ``None``: turned off."""
    env = os.environ.get(ENV)
    if env is not None:
        if env.strip().lower() in OFF or not env.strip():
            return None
        return pathlib.Path(env).expanduser()
    xdg = os.environ.get("XDG_CACHE_HOME")
    base = pathlib.Path(xdg).expanduser() if xdg else pathlib.Path.home() / ".cache"
    return base / "jdraw"


def versioned_dir(root: pathlib.Path) -> pathlib.Path:
    """``root/xla-jax<version>-jaxlib<version>``: one folder per jax/jaxlib pair."""
    import jax
    import jaxlib

    return root / f"xla-jax{jax.__version__}-jaxlib{jaxlib.__version__}"


def _writable(folder: pathlib.Path) -> str | None:
    """``None`` if ``folder`` can be created and written, else why not."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=folder, prefix=".probe-"):
            pass
    except OSError as e:
        return f"{type(e).__name__}: {e}"
    return None


def enable() -> pathlib.Path | None:
    """Switches JAX's persistent compilation cache on (once per process); returns its folder.

    Call before the first compilation (:func:`jdraw.plan` and
    :func:`jdraw.plan_image` call it). Returns ``None`` when the cache is
    turned off or cannot be written (then warns once), or JAX's own folder
    when the user set one.
    """
    if _STATE["done"]:
        return _STATE["dir"]
    _STATE["done"] = True
    import jax
    from jax.experimental.compilation_cache import compilation_cache as cc

    own = jax.config.jax_compilation_cache_dir
    if own:
        _STATE["dir"] = pathlib.Path(own)
        return _STATE["dir"]
    root = cache_root()
    if root is None:
        return None
    folder = versioned_dir(root)
    why = _writable(folder)
    if why is not None:
        warnings.warn(
            f"jdraw: compilation cache {str(folder)!r} cannot be written ({why}); planning "
            f"without it (set {ENV} to another folder, or {ENV}=off)",
            RuntimeWarning,
            stacklevel=2,
        )
        return None
    # Every program, however small: reading one back is cheaper than tracing it again.
    jax.config.update("jax_persistent_cache_min_compile_time_secs", 0.0)
    cc.set_cache_dir(str(folder))
    cc.reset_cache()  # a compilation before this one must not pin "no cache" for the process
    _STATE["dir"] = folder
    return folder


@contextlib.contextmanager
def bypassed():
    """Compilations inside neither read nor write JAX's cache: fresh executables.

    An executable JAX read back from its cache cannot be serialized again
    whole (on the CPU its functions are missing when the copy runs), so
    :mod:`jdraw.planner.executables` compiles the programs it stores in here.
    """
    import jax
    from jax.experimental.compilation_cache import compilation_cache as cc

    was = jax.config.jax_enable_compilation_cache
    jax.config.update("jax_enable_compilation_cache", False)
    cc.reset_cache()  # JAX decides once per process whether to use the cache; ask again
    try:
        yield
    finally:
        jax.config.update("jax_enable_compilation_cache", was)
        cc.reset_cache()
