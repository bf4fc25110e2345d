"""The probes and the catalogue: ``/healthz``, ``/readyz``, ``/v1/capabilities``,
``/version``, ``/v1/rules``.

``/healthz`` is liveness only: 200 as long as the process answers, whatever the workers
do (restarting a server whose workers are busy would not help). ``/readyz`` runs a
:class:`ReadyJob` in a worker (a tiny Pinocchio model, a tiny mesh) and reuses a successful
answer for :data:`READY_TTL` seconds (the cache lives in the app's ``state.readiness``);
it answers 503 with ``{"ready": false, "reason": ...}`` while the workers start, when they
are all busy, and when they cannot start (the reason names the cause, e.g. an import
error in the worker; the server then exits, see ``app.py``).
Its ready answer also says whether ``confirm`` is allowed and which engines are installed,
as ``/v1/capabilities`` does without a worker (for the web page and clients).
"""

from __future__ import annotations

import platform
import shutil
import tempfile
import time
from importlib import metadata
from typing import Any

from fastapi import APIRouter, Request
from fastapi.responses import JSONResponse
from starlette.concurrency import run_in_threadpool

from urdflint import __version__
from urdflint.engine import config, docs, registry
from urdflint.model import targets

from . import options as opts
from .jobs import ReadyJob
from .limits import Limits
from .pool import Busy, JobTimeout, WorkerDied
from .routing import error, limits_of, pool_of

READY_TTL = 30.0  # seconds a successful readiness check is reused

router = APIRouter()


@router.get("/healthz", tags=["probes"])
async def healthz() -> dict[str, str]:
    """Liveness: 200 while the process serves requests. Touches nothing else, not even the
    lint workers (``/readyz`` reports those)."""
    return {"status": "ok"}


@router.get(
    "/readyz",
    tags=["probes"],
    responses={503: {"description": 'not ready: `{"ready": false, "reason": ...}`'}},
)
async def readyz(request: Request) -> JSONResponse:
    """Readiness: a worker builds a tiny Pinocchio model and loads a tiny mesh.

    503 with the reason while the lint workers start, when all are busy, or when they
    cannot start (then the server exits soon after, for its supervisor to restart it).
    """
    pool, limits = pool_of(request), limits_of(request)
    readiness: dict[str, Any] = request.app.state.readiness
    if pool.problem is not None:
        return _not_ready(request, pool.problem, retry=False)
    if not pool.ready:
        return _not_ready(request, "the lint workers are starting")
    load = getattr(request.app.state, "load", None)
    if load is not None and load.active >= limits.jobs + limits.queue:
        return _not_ready(request, "every lint worker and queue place is taken")
    cached = readiness.get("answer")
    if cached is None or time.monotonic() - readiness.get("at", 0.0) > READY_TTL:
        folder = await run_in_threadpool(tempfile.mkdtemp, "", "urdflint-", limits.tmpdir)
        try:
            answer = await pool.run(ReadyJob(folder), wait=0.5)
        except Busy:
            if cached is None:
                return _not_ready(request, pool.problem or "every lint worker is busy")
            answer = cached
        except (JobTimeout, WorkerDied) as exc:
            return _not_ready(request, f"the readiness check failed: {exc}", retry=False)
        finally:
            await run_in_threadpool(shutil.rmtree, folder, True)
        if answer["status"] == 200:
            readiness.update(answer=answer, at=time.monotonic())
        cached = answer
    body = dict(cached["content"])
    body["workers"] = pool.stats()
    body["limits"] = limits.public()
    body["confirm"] = confirm_info(limits)
    return JSONResponse(body, status_code=200 if cached["status"] == 200 else 503)


def _not_ready(request: Request, reason: str, retry: bool = True) -> JSONResponse:
    """503 ``{"ready": false, "reason": ..., "workers": ...}`` (``detail``: the reason too)."""
    body = {"ready": False, "reason": reason, "detail": reason}
    body["workers"] = pool_of(request).stats()
    return JSONResponse(body, status_code=503, headers={"Retry-After": "1"} if retry else None)


@router.get("/v1/capabilities", tags=["probes"])
async def capabilities(request: Request) -> dict[str, Any]:
    """What this server offers ``POST /v1/check``, without touching the lint workers: the
    targets, the formats, whether ``confirm`` is allowed (``urdflint serve
    --allow-confirm``) and which engines are installed, and the limits."""
    limits = limits_of(request)
    return {
        "version": __version__,
        "targets": [
            {"name": name, "label": targets.LABELS[name], "engine": targets.ENGINE[name]}
            for name in targets.TARGETS
        ],
        "formats": list(opts.FORMATS),
        "matrix": True,
        "fix": True,  # POST /v1/fix (unsafe_fixes: the fixes that change the physics too)
        "confirm": confirm_info(limits),
        "limits": limits.public(),
    }


def confirm_info(limits: Limits) -> dict[str, Any]:
    """``{"allowed": bool, "engines": {name: installed}}``: whether the ``confirm`` option is
    accepted, and which engines can load a model here (a cheap ``find_spec`` each).

    An engine with a compiled probe (sdformat: built with ``pkg-config`` and ``g++`` on
    first use) is never run by the service, whose workers may not compile or start other
    programs: it is reported as not installed, as its E007 note in an answer says.
    """
    from urdflint.engines import runner

    native = set(getattr(runner, "NATIVE", ()))
    engines: dict[str, bool] = {}
    for engine in config.ENGINES:
        try:
            engines[engine] = engine not in native and runner.installed(engine)
        except (KeyError, ImportError, ValueError):  # an engine the runner does not know yet
            engines[engine] = False
    return {"allowed": limits.allow_confirm, "engines": engines}


@router.get("/version", tags=["probes"])
async def version() -> dict[str, Any]:
    """Versions of urdflint and of the libraries it uses (for bug reports)."""
    return _versions()


@router.get("/v1/rules", tags=["rules"])
async def rules() -> dict[str, Any]:
    """Every rule: code, name, default severity, family, summary, needs, options."""
    found = registry.load_rules()
    return {"version": 1, "rules": [_rule_dict(r) for r in sorted(found.values(), key=_code)]}


@router.get("/v1/rules/{code}", tags=["rules"], responses={404: {"description": "no such rule"}})
async def rule(code: str) -> JSONResponse:
    """One rule (by code or name) and its documentation pages as Markdown: ``markdown`` the
    full page (``urdflint explain CODE --long``: every section, what each target does, every
    example; the web page shows it), ``short_markdown`` the short one (``urdflint explain
    CODE``)."""
    found = registry.lookup(code)
    if found is None:
        return error(404, f"unknown rule {code!r}")
    data = _rule_dict(found)
    data["fix"] = found.fix
    data["sections"] = {
        h: found.section(h) for h in ("What it does", "Why is this bad?", "How to fix")
    }
    data["markdown"] = docs.page(found)
    data["short_markdown"] = docs.short_page(found)
    return JSONResponse(data)


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


def _code(rule: registry.Rule) -> str:
    return rule.code
