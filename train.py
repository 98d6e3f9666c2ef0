"""Trains jdraw's local and global models.

  python train.py --config configs/paper.py --workdir runs/paper [--config.train.num_steps=100]

Running the same command again resumes from the workdir's latest checkpoint.
"""

from absl import app, flags, logging
from ml_collections import config_flags

from jdraw.train import loop as training

_CONFIG = config_flags.DEFINE_config_file(
    "config", "configs/paper.py", "Training config (configs/*.py)."
)
_WORKDIR = flags.DEFINE_string("workdir", None, "Where checkpoints, metrics and the bundle go.")


def main(argv):
    del argv
    logging.set_verbosity(logging.WARNING)  # Orbax logs every save at INFO
    cfg = _CONFIG.value
    workdir = _WORKDIR.value or f"runs/{cfg.get('name', 'run')}"
    if cfg.get("stage") == "ranker":
        from jdraw.train import ranker as ranker_train

        print(ranker_train.train(cfg, workdir))
        return
    if cfg.get("stage") == "reading":
        from jdraw.train import reading as reading_train

        print(reading_train.train(cfg, workdir))
        return
    if cfg.get("stage") == "splitter":
        from jdraw.train import splitter as splitter_train

        print(splitter_train.train(cfg, workdir))
        return
    result = training.train(cfg, workdir)
    print({k: v for k, v in result.items() if k != "val"})
    if "val" in result:
        print("validation:", result["val"])


if __name__ == "__main__":
    app.run(main)
