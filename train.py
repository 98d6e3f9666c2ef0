"""Trains jdraw's models: one config, or every stage of a pipeline config.

  python train.py --config configs/default.py --workdir runs/default   # the default, all stages
  python train.py --config configs/paper.py --workdir runs/paper [--config.train.num_steps=100]

Running the same command again resumes: a pipeline skips the stages it has
done, and a model stage resumes from its workdir's latest Orbax checkpoint.

On several processes or hosts (jax.distributed), run the same command on each,
with the coordinator's host:port, the process count and this process's id
(flags, or JAX_COORDINATOR_ADDRESS, JAX_NUM_PROCESSES, JAX_PROCESS_ID):

  python train.py --config configs/default.py --workdir /shared/runs/default \
      --coordinator host0:1234 --num_processes 2 --process_id 0   # 1 on the other host
"""

import pathlib

from absl import app, flags, logging
from ml_collections import config_flags

_CONFIG = config_flags.DEFINE_config_file(
    "config", "configs/paper.py", "Training config (configs/*.py[:variant])."
)
_WORKDIR = flags.DEFINE_string("workdir", None, "Where checkpoints, metrics and the bundle go.")
_COORD = flags.DEFINE_string("coordinator", None, "host:port of process 0 (several processes).")
_NPROC = flags.DEFINE_integer("num_processes", None, "Processes in the run (several processes).")
_PID = flags.DEFINE_integer("process_id", None, "This process's id, 0 to num_processes - 1.")


def main(argv):
    del argv
    logging.set_verbosity(logging.WARNING)  # Orbax logs every save at INFO
    from jdraw.train import distributed

    distributed.initialize(_COORD.value, _NPROC.value, _PID.value)
    cfg = _CONFIG.value
    workdir = _WORKDIR.value or f"runs/{cfg.get('name', 'run')}"
    from jdraw.train import pipeline

    if pipeline.is_pipeline(cfg):
        result = pipeline.train(cfg, workdir)
        if distributed.is_lead():
            print(f"bundle: {result['bundle']}")
        return
    result = pipeline.run_stage(cfg, pathlib.Path(workdir))
    if not distributed.is_lead():
        return
    print({k: v for k, v in result.items() if k not in ("val", "logs")})
    if "val" in result:
        print("validation:", result["val"])


if __name__ == "__main__":
    app.run(main)
