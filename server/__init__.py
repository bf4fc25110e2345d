"""The HTTP validation service: `urdflint serve`, or `urdflint.server.app:app` in any ASGI server.

See ``app.py`` for the endpoints and how the app is assembled from ``routes_check.py``
(``POST /v1/check``), ``routes_meta.py`` (probes and rules) and ``page.py`` (the web
pages and security headers); ``limits.py`` for the limits and their environment variables;
``pool.py``, ``starting.py``, ``worker.py``, ``jobs.py`` and ``fence.py`` for how lint jobs
run; ``uploads.py`` for the meshes zip. FastAPI and uvicorn are imported only here, never by
the command line.
"""
