"""Large images: tiles, planning them, stitching the strokes."""
