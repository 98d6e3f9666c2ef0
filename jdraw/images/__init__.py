"""Images in: loading, binarising, skeletons, canonical lines, fitting to the canvas."""
