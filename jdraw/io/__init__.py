"""Plans out: SVG, G-code, JSON, pictures, plot statistics and the vpype plugin.

:func:`jdraw.io.outputs.write_outputs` writes any of them for a plan in one call.
"""
