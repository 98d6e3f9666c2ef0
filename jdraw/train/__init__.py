"""Training: losses, the step, the loop, the stroke ranker."""
