"""The urdflint HTTP validation service (FastAPI): ``urdflint serve`` or any ASGI server.

    uvicorn urdflint.server.app:app --host 0.0.0.0 --port 8000
    urdflint serve --host 0.0.0.0 --port 8000 --workers 1

Endpoints (OpenAPI at ``/docs`` and ``/openapi.json``):

``POST /v1/check``      lint one URDF or xacro file: a raw ``application/xml``/``text/xml``
                        body, or ``multipart/form-data`` with ``urdf`` (a .urdf/.xacro file,
                        or the XML as a text field) and an optional ``meshes`` zip. Options
                        as query parameters or form fields (``options.py``). 200 with the
                        CLI's ``--format json`` document plus ``passed``, whenever linting
                        ran, even on a broken model
``GET /v1/rules``       the rule catalogue (as ``urdflint rules --format json``)
``GET /v1/rules/{code}`` one rule, with its page as Markdown (as ``urdflint explain``)
``GET /healthz``        liveness: answers without touching anything else
``GET /readyz``         readiness: a worker builds a tiny model with Pinocchio and loads a
                        tiny mesh; reports the optional capabilities and the limits
``GET /version``        versions of urdflint and the libraries it uses
``GET /``, ``/static``  the web page (``server/static``), when present

Status codes: 200 linting ran; 404 unknown rule; 413 body or upload over its limit; 415
not XML, multipart, or a .urdf/.xacro file; 422 malformed request, option or archive,
with the reason in ``detail``; 503 every worker and queue place taken, or the server is
starting (``Retry-After``); 504 the job overran ``URDFLINT_TIMEOUT`` (its worker is
killed and replaced). Never 500 for bad input.

Limits come from the environment (see ``limits.py``: ``URDFLINT_MAX_URDF_BYTES``,
``URDFLINT_MAX_ZIP_BYTES``, ``URDFLINT_TIMEOUT``, ``URDFLINT_JOBS``, ``URDFLINT_QUEUE``
and more). Each lint job runs in a worker process (``pool.py``, ``worker.py``) inside a
per-request temporary folder that is removed afterwards; nothing outside that folder is
read and no network connection is opened. The service keeps no state between requests:
scale it by running more containers behind any load balancer.
"""

from __future__ import annotations

import asyncio
import logging
import platform
import shutil
import tempfile
import time
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager, suppress
from importlib import metadata
from pathlib import Path
from typing import Annotated, Any

from fastapi import FastAPI, Query, Request
from fastapi.responses import FileResponse, JSONResponse, PlainTextResponse, Response
from starlette.concurrency import run_in_threadpool
from starlette.datastructures import UploadFile
from starlette.exceptions import HTTPException

from urdflint import __version__
from urdflint.engine import docs, registry

from . import options as opts
from .limits import Guard, Limits
from .pool import Busy, JobTimeout, Pool, WorkerDied
from .uploads import ZipLimits, urdf_name
from .worker import CheckJob, ReadyJob

log = logging.getLogger("urdflint.server")

STATIC = Path(__file__).resolve().parent / "static"
XML_TYPES = ("application/xml", "text/xml")
READY_TTL = 30.0  # seconds a successful readiness check is reused
FORM_FIELD_BYTES = 128 * 1024
SECURITY_HEADERS = (
    (b"x-content-type-options", b"nosniff"),
    (b"referrer-policy", b"no-referrer"),
    (b"x-frame-options", b"DENY"),
)

DESCRIPTION = """Lint robot descriptions (URDF and xacro) with every urdflint rule.

`POST /v1/check` returns exactly the JSON document `urdflint check --format json` prints,
plus `passed`. Send the URDF as the raw body (`Content-Type: application/xml`) or as the
`urdf` part of a multipart form, with an optional `meshes` zip whose top-level folders
(and `package.xml` files) are the ROS packages `package://` URIs resolve against.
"""

CHECK_BODY = {
    "required": True,
    "content": {
        "application/xml": {"schema": {"type": "string", "description": "the URDF itself"}},
        "multipart/form-data": {
            "schema": {
                "type": "object",
                "required": ["urdf"],
                "properties": {
                    "urdf": {
                        "type": "string",
                        "format": "binary",
                        "description": "a .urdf or .xacro file (or the XML as text)",
                    },
                    "meshes": {
                        "type": "string",
                        "format": "binary",
                        "description": "optional zip: its folders are the ROS packages",
                    },
                    "select": {"type": "string"},
                    "ignore": {"type": "string"},
                    "fail_on": {"type": "string"},
                    "target": {"type": "string"},
                    "expect_mass": {"type": "string"},
                    "expect_com": {"type": "string"},
                    "xacro_args": {"type": "string"},
                    "config": {"type": "string", "description": "JSON, [tool.urdflint] keys"},
                    "svg": {"type": "boolean"},
                },
            }
        },
    },
}


def _error(status: int, detail: str, headers: dict[str, str] | None = None) -> JSONResponse:
    return JSONResponse({"detail": detail}, status_code=status, headers=headers)


class SecurityHeaders:
    """A few response headers every answer carries (pure ASGI, cheap)."""

    def __init__(self, app: Any) -> None:
        self.app = app

    async def __call__(self, scope: Any, receive: Any, send: Any) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return

        async def sending(message: Any) -> None:
            if message["type"] == "http.response.start":
                message["headers"] = [*message.get("headers", ()), *SECURITY_HEADERS]
            await send(message)

        await self.app(scope, receive, sending)


def _versions() -> dict[str, str | None]:
    found: dict[str, str | None] = {"urdflint": __version__, "python": platform.python_version()}
    for dist in ("lxml", "xacro", "trimesh", "yourdfpy", "pycollada", "pin", "fastapi", "uvicorn"):
        try:
            found[dist] = metadata.version(dist)
        except metadata.PackageNotFoundError:
            found[dist] = None
    return found


def _rule_dict(rule: registry.Rule) -> dict[str, Any]:
    return {
        "code": rule.code,
        "name": rule.name,
        "severity": str(rule.severity),
        "family": registry.FAMILIES[rule.family],
        "summary": rule.summary,
        "needs": list(rule.needs),
        "options": dict(rule.options),
    }


def create_app(limits: Limits | None = None) -> FastAPI:
    """A new app with its own worker pool (started with the app's lifespan, or lazily)."""
    limits = limits or Limits.from_env()
    pool = Pool(
        size=limits.jobs,
        timeout=limits.timeout,
        memory=limits.worker_memory,
        max_tasks=limits.max_tasks,
    )
    zip_limits = ZipLimits(limits.max_zip_members, limits.max_unzipped_bytes, limits.max_zip_ratio)
    readiness: dict[str, Any] = {}

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        registry.load_rules()
        starting = asyncio.create_task(pool.start())
        starting.add_done_callback(_report_start)
        try:
            yield
        finally:
            starting.cancel()
            await pool.close()

    app = FastAPI(
        title="urdflint",
        summary="A linter for robot descriptions (URDF and xacro), as a service",
        description=DESCRIPTION,
        version=__version__,
        lifespan=lifespan,
    )
    app.state.limits = limits
    app.state.pool = pool
    app.add_middleware(Guard, limits=limits)
    app.add_middleware(SecurityHeaders)

    @app.exception_handler(opts.OptionError)
    async def _option_error(request: Request, exc: opts.OptionError) -> JSONResponse:
        return _error(422, str(exc))

    # -- probes and metadata -------------------------------------------------------------

    @app.get("/healthz", tags=["probes"])
    async def healthz() -> dict[str, str]:
        """Liveness: the event loop answers. Touches nothing else."""
        return {"status": "ok"}

    @app.get("/readyz", tags=["probes"])
    async def readyz() -> JSONResponse:
        """Readiness: a worker builds a tiny Pinocchio model and loads a tiny mesh."""
        if not pool.ready:
            return _error(503, "the lint workers are starting", {"Retry-After": "1"})
        cached = readiness.get("answer")
        if cached is None or time.monotonic() - readiness.get("at", 0.0) > READY_TTL:
            folder = await run_in_threadpool(tempfile.mkdtemp, "", "urdflint-", limits.tmpdir)
            try:
                answer = await pool.run(ReadyJob(folder), wait=0.5)
            except Busy:
                if cached is None:
                    return _error(503, "every lint worker is busy", {"Retry-After": "1"})
                answer = cached
            except (JobTimeout, WorkerDied) as exc:
                return _error(503, f"the readiness check failed: {exc}")
            finally:
                await run_in_threadpool(shutil.rmtree, folder, True)
            if answer["status"] == 200:
                readiness.update(answer=answer, at=time.monotonic())
            cached = answer
        body = dict(cached["content"])
        body["workers"] = pool.stats()
        body["limits"] = limits.public()
        return JSONResponse(body, status_code=200 if cached["status"] == 200 else 503)

    @app.get("/version", tags=["probes"])
    async def version() -> dict[str, Any]:
        """Versions of urdflint and of the libraries it uses (for bug reports)."""
        return _versions()

    @app.get("/v1/rules", tags=["rules"])
    async def rules() -> dict[str, Any]:
        """Every rule: code, name, default severity, family, summary, needs, options."""
        found = registry.load_rules()
        return {"version": 1, "rules": [_rule_dict(r) for r in sorted(found.values(), key=_code)]}

    @app.get("/v1/rules/{code}", tags=["rules"], responses={404: {"description": "no such rule"}})
    async def rule(code: str) -> JSONResponse:
        """One rule (by code or name) and its documentation page as Markdown."""
        found = registry.lookup(code)
        if found is None:
            return _error(404, f"unknown rule {code!r}")
        data = _rule_dict(found)
        data["fix"] = found.fix
        data["sections"] = {
            h: found.section(h) for h in ("What it does", "Why is this bad?", "How to fix")
        }
        data["markdown"] = docs.page(found)
        return JSONResponse(data)

    # -- the check ----------------------------------------------------------------------------

    @app.post(
        "/v1/check",
        tags=["check"],
        openapi_extra={"requestBody": CHECK_BODY},
        responses={
            200: {"description": "linting ran: the findings document (even for a broken model)"},
            413: {"description": "the body, the URDF or the zip is over its limit"},
            415: {"description": "not XML or multipart, or not a .urdf/.xacro file"},
            422: {"description": "malformed request, option or archive (see detail)"},
            503: {"description": "every worker and queue place is taken; retry"},
            504: {"description": "the lint job overran the time limit"},
        },
    )
    async def check(
        request: Request,
        select: Annotated[
            list[str] | None, Query(description="rules to run (codes, names, families)")
        ] = None,
        ignore: Annotated[list[str] | None, Query(description="rules not to run")] = None,
        fail_on: Annotated[
            str | None, Query(description="error|warning|info|never: sets 'passed'")
        ] = None,
        target: Annotated[
            list[str] | None, Query(description="gazebo-classic|gz-sim|mujoco")
        ] = None,
        expect_mass: Annotated[str | None, Query(description="KG[±TOL], as --expect-mass")] = None,
        expect_com: Annotated[str | None, Query(description="X,Y,Z[±TOL], as --expect-com")] = None,
        xacro_args: Annotated[
            list[str] | None, Query(description="NAME:=VALUE[,NAME:=VALUE]")
        ] = None,
        q: Annotated[
            list[str] | None, Query(description="JOINT=VALUE positions for mass/COM")
        ] = None,
        config: Annotated[
            str | None, Query(description="JSON object of [tool.urdflint] keys")
        ] = None,
        format: Annotated[str, Query(description="json|sarif|text|github")] = "json",
        svg: Annotated[str | None, Query(description="true: add the kinematic tree as SVG")] = None,
        filename: Annotated[str | None, Query(description="name shown for a raw XML body")] = None,
    ) -> Response:
        """Lint one URDF or xacro file (and its meshes) with the CLI's rules and options."""
        kind = request.headers.get("content-type", "").split(";")[0].strip().lower()
        if kind == "multipart/form-data":
            return await _multipart(request)
        if kind in XML_TYPES or kind.endswith("+xml"):
            body = await request.body()
            if len(body) > limits.max_urdf_bytes:
                return _error(413, "the URDF is over the size limit")
            values = opts.merge(request.query_params.multi_items())
            options = opts.parse(values)
            try:
                name = urdf_name(options.filename)
            except ValueError as exc:
                return _error(415, str(exc))
            return await _lint(body, name, None, options)
        return _error(
            415,
            "send the URDF as application/xml or text/xml, or as multipart/form-data with "
            f"a 'urdf' part (got {kind or 'no content type'!r})",
        )

    async def _multipart(request: Request) -> Response:
        try:
            form = await request.form(max_files=2, max_fields=64, max_part_size=FORM_FIELD_BYTES)
        except HTTPException as exc:
            if exc.status_code == 400:
                return _error(422, f"malformed multipart body: {exc.detail}")
            raise
        try:
            urdf: Any = None
            meshes: UploadFile | None = None
            fields: list[tuple[str, str]] = []
            for key, value in form.multi_items():
                if key == "urdf":
                    if urdf is not None:
                        return _error(422, "send one 'urdf' part")
                    urdf = value
                elif key == "meshes":
                    if not isinstance(value, UploadFile):
                        if value:  # an empty field: a form whose file input was left empty
                            return _error(422, "'meshes' must be a file (a zip)")
                    elif value.filename or value.size:  # browsers send an empty part for none
                        meshes = value
                elif isinstance(value, UploadFile):
                    return _error(422, f"unexpected file part {key!r}")
                else:
                    fields.append((key, value))
            options = opts.parse(opts.merge(request.query_params.multi_items(), fields))
            if urdf is None or (
                isinstance(urdf, UploadFile) and not urdf.filename and not urdf.size
            ):
                return _error(422, "the form has no 'urdf' part (a .urdf or .xacro file)")
            if isinstance(urdf, UploadFile):
                if (urdf.size or 0) > limits.max_urdf_bytes:
                    return _error(413, "the URDF is over the size limit")
                try:
                    name = urdf_name(urdf.filename)
                except ValueError as exc:
                    return _error(415, str(exc))
                data = await urdf.read(limits.max_urdf_bytes + 1)
            else:
                data = str(urdf).encode("utf-8")
                try:
                    name = urdf_name(options.filename)
                except ValueError as exc:
                    return _error(415, str(exc))
            if len(data) > limits.max_urdf_bytes:
                return _error(413, "the URDF is over the size limit")
            if meshes is not None and (meshes.size or 0) > limits.max_zip_bytes:
                return _error(413, "the meshes zip is over the size limit")
            return await _lint(data, name, meshes, options)
        finally:
            await form.close()

    async def _lint(
        data: bytes, name: str, meshes: UploadFile | None, options: opts.Options
    ) -> Response:
        folder = await run_in_threadpool(tempfile.mkdtemp, "", "urdflint-", limits.tmpdir)
        try:
            archive = None
            if meshes is not None:
                archive = str(Path(folder) / "meshes.zip")
                size = await run_in_threadpool(_save, meshes, archive, limits.max_zip_bytes)
                if size > limits.max_zip_bytes:
                    return _error(413, "the meshes zip is over the size limit")
            job = CheckJob(
                folder, name, data, archive, options.settings, options.fmt, options.svg, zip_limits
            )
            try:
                answer = await pool.run(job)
            except Busy as exc:
                return _error(503, f"the server is busy ({exc})", {"Retry-After": "1"})
            except JobTimeout:
                return _error(
                    504, f"checking this input took over the {limits.timeout:g} s time limit"
                )
            except WorkerDied as exc:
                return _error(422, f"{exc}; the input cannot be checked")
        finally:
            await run_in_threadpool(shutil.rmtree, folder, True)
        status, content, media = answer["status"], answer["content"], answer["media_type"]
        if isinstance(content, (dict, list)):
            return JSONResponse(content, status_code=status)
        return Response(content, status_code=status, media_type=media)

    # -- the web page -----------------------------------------------------------------------

    @app.get("/", include_in_schema=False)
    async def index() -> Response:
        page = STATIC / "index.html"
        if page.is_file():
            return FileResponse(page, media_type="text/html", headers=PAGE_HEADERS)
        return PlainTextResponse("urdflint service: see /docs for the API\n")

    if STATIC.is_dir():
        from fastapi.staticfiles import StaticFiles

        app.mount("/static", StaticFiles(directory=STATIC), name="static")

        @app.middleware("http")
        async def revalidate_static(request: Request, call_next: Any) -> Response:
            response: Response = await call_next(request)
            if request.url.path.startswith("/static/"):
                response.headers["Cache-Control"] = "no-cache"  # a new release's app.js wins
            return response

    return app


# The page loads nothing from other hosts; this policy makes sure it never can.
PAGE_HEADERS = {
    "Content-Security-Policy": "default-src 'none'; script-src 'self'; style-src 'self'; "
    "img-src 'self' data:; connect-src 'self'; base-uri 'none'; form-action 'self'; "
    "frame-ancestors 'none'",
    "Cache-Control": "no-cache",
}


def _code(rule: registry.Rule) -> str:
    return rule.code


def _save(upload: UploadFile, target: str, limit: int) -> int:
    """Copy an upload to ``target`` (stops one byte over ``limit``); the bytes written."""
    upload.file.seek(0)
    written = 0
    with open(target, "xb") as out:
        while written <= limit:
            chunk = upload.file.read(1 << 20)
            if not chunk:
                break
            out.write(chunk)
            written += len(chunk)
    return written


def _report_start(task: asyncio.Task[None]) -> None:
    with suppress(asyncio.CancelledError):
        task.exception()  # retrieved (the pool logged it): a later request retries the start


app = create_app()
