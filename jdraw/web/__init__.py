"""``jdraw serve``: a page to draw or drop an image, watch its plan and download it.

:mod:`jdraw.web.app` is the Starlette app (the page and ``POST /api/plan``),
:mod:`jdraw.web.server` the command, :mod:`jdraw.web.planning` the one-worker
queue, :mod:`jdraw.web.upload` the header check and decoding of uploads,
:mod:`jdraw.web.options` the form fields, ``static/`` the page. Needs the
``[web]`` extra; importing this package alone imports none of it.
"""
