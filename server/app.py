"""The urdflint HTTP validation service (FastAPI): ``urdflint serve`` or any ASGI server.

    uvicorn urdflint.server.app:app --host 0.0.0.0 --port 8000
    urdflint serve --host 0.0.0.0 --port 8000 --workers 1

Endpoints (OpenAPI at ``/openapi.json``, shown by ``/docs``, which works offline):

``POST /v1/check``      lint one URDF or xacro file: a raw ``application/xml``/``text/xml``
                        body, or ``multipart/form-data`` with ``urdf`` (a .urdf/.xacro file,
                        or the XML as a text field) and an optional ``meshes`` zip. Options
                        as query parameters or form fields (``options.py``). 200 with the
                        CLI's ``--format json`` document plus ``passed``, whenever linting
                        ran, even on a broken model
``POST /v1/fix``        the same request plus ``unsafe_fixes``: the automatic fixes applied
                        to the uploaded file in rounds, as ``urdflint fix`` (``fixing.py``);
                        200 with the check's document for the fixed file plus ``fixed``
                        (its text), ``diff`` (unified) and ``applied`` (how many)
``GET /v1/capabilities`` targets, formats, whether ``confirm`` is allowed and which
                        engines are installed, the limits (touches no worker)
``GET /v1/rules``       the rule catalogue (as ``urdflint rules --format json``)
``GET /v1/rules/{code}`` one rule, with its full page as Markdown (``markdown``, as
                        ``urdflint explain --long``) and its short page
                        (``short_markdown``, as ``urdflint explain``)
``GET /healthz``        liveness: 200 while the process serves requests, touching nothing
                        else (not even the workers: a restart would not fix a busy server)
``GET /readyz``         readiness: a worker builds a tiny model with Pinocchio and loads a
                        tiny mesh; reports the optional capabilities, ``confirm`` and the
                        limits. 503
                        with ``{"ready": false, "reason": ...}`` while the workers start,
                        when every one is busy, or when they cannot start (the reason
                        names the cause, e.g. the worker's import error)
``GET /version``        versions of urdflint and the libraries it uses
``GET /``, ``/rules``, ``/rules/{code}``, ``/docs``, ``/static``
                        the web pages (``page.py``, ``server/static``), when present

Status codes: 200 linting ran; 404 unknown rule; 413 body or upload over its limit; 415
not XML, multipart, or a .urdf/.xacro file; 422 malformed request, option or archive,
with the reason in ``detail``; 503 every worker and queue place taken, the server is
starting (``Retry-After``), or no lint worker can start (see ``/readyz``); 504 the job
overran ``URDFLINT_TIMEOUT`` (its worker is killed and replaced). Never 500 for bad input.

Start-up: the app answers at once and starts the lint workers in the background, retrying
a few times (``pool.Pool.keep_starting``). When no worker can ever start (a broken install,
say), the server logs why and exits with :data:`EXIT_NO_WORKERS` after a graceful
shutdown, so an orchestrator restarts it or shows the failure (``create_app`` with
``exit_on_failure=False``, as in-process tests use it, only reports it on ``/readyz``).

Limits come from the environment (see ``limits.py``: ``URDFLINT_MAX_URDF_BYTES``,
``URDFLINT_MAX_ZIP_BYTES``, ``URDFLINT_TIMEOUT``, ``URDFLINT_JOBS``, ``URDFLINT_QUEUE``
and more). Each lint job runs in a worker process (``pool.py``, ``worker.py``) inside a
per-request temporary folder that is removed afterwards; nothing outside that folder is
read and no network connection is opened. The service keeps no state between requests:
scale it by running more containers behind any load balancer.

The ``confirm`` option (load the model in MuJoCo, PyBullet, Drake, Pinocchio) is off by
default: the engines are heavy native code loading untrusted input. ``urdflint serve
--allow-confirm`` (``URDFLINT_ALLOW_CONFIRM=1``) turns it on; each engine then runs in its
own process with a memory limit and a timeout, within the job's time limit, on a copy of
the model that only references the upload's files (``confirming.py``).

:func:`create_app` assembles the app: the routes of ``routes_meta.py`` (probes, rules),
``routes_check.py`` (the check), ``routes_fix.py`` (the fix) and ``page.py`` (the web page,
security headers), the limits middleware (``limits.Guard``) and one worker pool, kept in
``app.state``.
"""

from __future__ import annotations

import asyncio
import logging
import os
import signal
import sys
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager, suppress

from fastapi import FastAPI

from urdflint import __version__
from urdflint.engine import registry

from . import options as opts
from . import page, routes_check, routes_fix, routes_meta
from .limits import Guard, Limits, Load
from .page import SecurityHeaders
from .pool import Pool
from .routing import option_error

log = logging.getLogger("urdflint.server")
EXIT_NO_WORKERS = 3  # the exit code when no lint worker can start (as uvicorn's start-up failure)
DESCRIPTION = """Lint robot descriptions (URDF and xacro) with every urdflint rule.

`POST /v1/check` returns exactly the JSON document `urdflint check --format json` prints,
plus `passed`. Send the URDF as the raw body (`Content-Type: application/xml`) or as the
`urdf` part of a multipart form, with an optional `meshes` zip whose top-level folders
(and `package.xml` files) are the ROS packages `package://` URIs resolve against.

`POST /v1/fix` takes the same request (plus `unsafe_fixes`) and applies the automatic fixes
to the uploaded file, as `urdflint fix`: it returns the fixed file as `fixed`, a unified
`diff`, the number of fixes `applied`, and the check's document for the fixed file.
"""


def create_app(limits: Limits | None = None, *, exit_on_failure: bool = False) -> FastAPI:
    """A new app with its own worker pool (started with the app's lifespan, or lazily).

    With ``exit_on_failure``, the process stops (exit code :data:`EXIT_NO_WORKERS`) when no
    lint worker can start; the module's ``app``, which servers run, is made so.
    """
    limits = limits or Limits.from_env()
    pool = Pool(
        size=limits.jobs,
        timeout=limits.timeout,
        memory=limits.worker_memory,
        max_tasks=limits.max_tasks,
    )
    if exit_on_failure:
        pool.on_failed = _stop_server

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        registry.load_rules()
        starting = asyncio.create_task(pool.keep_starting())
        starting.add_done_callback(_report_start)
        try:
            yield
        finally:
            starting.cancel()
            await pool.close()
            if exit_on_failure and pool.failed is not None:
                _exit(pool.failed)

    app = FastAPI(
        title="urdflint",
        summary="A linter for robot descriptions (URDF and xacro), as a service",
        description=DESCRIPTION,
        version=__version__,
        lifespan=lifespan,
        docs_url=None,  # page.py serves /docs from the copy of Swagger UI in static/
        redoc_url=None,  # ReDoc would come from a CDN: not offline, so not served
    )
    app.state.limits = limits
    app.state.pool = pool
    app.state.readiness = {}  # the last successful /readyz answer and when (routes_meta)
    app.state.load = Load()  # lint requests in flight: /readyz says when no place is left
    app.add_middleware(Guard, limits=limits, load=app.state.load)
    app.add_middleware(SecurityHeaders)
    app.exception_handler(opts.OptionError)(option_error)
    # routes in this order: the OpenAPI document lists them so
    app.include_router(routes_meta.router)
    app.include_router(routes_check.router)
    app.include_router(routes_fix.router)
    app.include_router(page.router)
    page.mount_static(app)  # after the middleware above: its own runs outermost
    return app


def _report_start(task: asyncio.Task[bool]) -> None:
    """Retrieve a failed start's exception, so asyncio does not log it a second time."""
    with suppress(asyncio.CancelledError):
        task.exception()  # retrieved (the pool logged it)


def _stop_server(reason: str) -> None:
    """No lint worker can start: shut the server down gracefully (SIGTERM to itself)."""
    log.critical("stopping the server: %s", reason)
    os.kill(os.getpid(), signal.SIGTERM)


def _exit(reason: str) -> None:
    """End the process with :data:`EXIT_NO_WORKERS`, once the server has shut down.

    ``os._exit``: uvicorn would end with 0 after a SIGTERM, which an orchestrator takes
    for a clean stop; the shutdown (connections, the pool) is already done here.
    """
    log.critical("exiting with code %d: %s", EXIT_NO_WORKERS, reason)
    logging.shutdown()
    for stream in (sys.stdout, sys.stderr):
        with suppress(Exception):
            stream.flush()
    os._exit(EXIT_NO_WORKERS)


app = create_app(exit_on_failure=True)
