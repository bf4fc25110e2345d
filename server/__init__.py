"""The HTTP validation service: `urdflint serve`, or `urdflint.server.app:app` in any ASGI server.

See ``app.py`` for the endpoints, ``limits.py`` for the limits and their environment
variables, ``pool.py`` and ``worker.py`` for how lint jobs run, ``uploads.py`` for the
meshes zip. FastAPI and uvicorn are imported only here, never by the command line.
"""
