"""The probes and the rule catalogue: ``/healthz``, ``/readyz``, ``/version``, ``/v1/rules``.

``/readyz`` runs a :class:`ReadyJob` in a worker (a tiny Pinocchio model, a tiny mesh) and
reuses a successful answer for :data:`READY_TTL` seconds; the cache lives in the app's
``state.readiness``.
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
from urdflint.engine import docs, registry

from .jobs import ReadyJob
from .pool import Busy, JobTimeout, WorkerDied
from .routing import error, limits_of, pool_of

READY_TTL = 30.0  # seconds a successful readiness check is reused

router = APIRouter()


@router.get("/healthz", tags=["probes"])
async def healthz() -> dict[str, str]:
    """Liveness: the event loop answers. Touches nothing else."""
    return {"status": "ok"}


@router.get("/readyz", tags=["probes"])
async def readyz(request: Request) -> JSONResponse:
    """Readiness: a worker builds a tiny Pinocchio model and loads a tiny mesh."""
    pool, limits = pool_of(request), limits_of(request)
    readiness: dict[str, Any] = request.app.state.readiness
    if not pool.ready:
        return error(503, "the lint workers are starting", {"Retry-After": "1"})
    cached = readiness.get("answer")
    if cached is None or time.monotonic() - readiness.get("at", 0.0) > READY_TTL:
        folder = await run_in_threadpool(tempfile.mkdtemp, "", "urdflint-", limits.tmpdir)
        try:
            answer = await pool.run(ReadyJob(folder), wait=0.5)
        except Busy:
            if cached is None:
                return error(503, "every lint worker is busy", {"Retry-After": "1"})
            answer = cached
        except (JobTimeout, WorkerDied) as exc:
            return error(503, f"the readiness check failed: {exc}")
        finally:
            await run_in_threadpool(shutil.rmtree, folder, True)
        if answer["status"] == 200:
            readiness.update(answer=answer, at=time.monotonic())
        cached = answer
    body = dict(cached["content"])
    body["workers"] = pool.stats()
    body["limits"] = limits.public()
    return JSONResponse(body, status_code=200 if cached["status"] == 200 else 503)


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
    """One rule (by code or name) and its documentation page as Markdown."""
    found = registry.lookup(code)
    if found is None:
        return error(404, f"unknown rule {code!r}")
    data = _rule_dict(found)
    data["fix"] = found.fix
    data["sections"] = {
        h: found.section(h) for h in ("What it does", "Why is this bad?", "How to fix")
    }
    data["markdown"] = docs.page(found)
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
