"""Plans out: SVG, G-code, JSON, pictures and the vpype plugin."""
