"""The networks, their bundles and training checkpoints."""
