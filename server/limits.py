"""The service's limits, read once from the environment, and the ASGI guard enforcing them.

Environment variables (sizes accept a ``K``/``M``/``G`` suffix, powers of 1024):

``URDFLINT_MAX_URDF_BYTES``    largest URDF or xacro upload (default 5M)
``URDFLINT_MAX_ZIP_BYTES``     largest meshes zip as uploaded (default 100M)
``URDFLINT_MAX_UNZIPPED_BYTES`` total size the zip may expand to (default 512M)
``URDFLINT_MAX_ZIP_MEMBERS``   files and folders in the zip (default 5000)
``URDFLINT_MAX_ZIP_RATIO``     uncompressed:compressed ratio allowed per member over 1 MiB
                               (default 100)
``URDFLINT_TIMEOUT``           seconds one lint job may run before its worker is killed (504),
                               and the longest a request waits for a free worker (503)
                               (default 60)
``URDFLINT_JOBS``              lint worker processes = concurrent lint jobs per server process
                               (default: the CPUs this process may use)
``URDFLINT_QUEUE``             requests that may wait for a worker; more get 503 at once
                               (default 16)
``URDFLINT_WORKER_MEMORY``     address-space limit of each worker (RLIMIT_AS), 0 = none
                               (default 3G)
``URDFLINT_MAX_TASKS``         jobs a worker runs before it is replaced (default 500)
``URDFLINT_TMPDIR``            where per-request folders are made (default: the system's
                               temporary folder, i.e. ``TMPDIR``)
``URDFLINT_ALLOW_CONFIRM``     1 to accept the ``confirm`` option of ``/v1/check`` (load the
                               upload in the installed simulation engines); what
                               ``urdflint serve --allow-confirm`` sets (default 0: refused)

The guard is a pure ASGI middleware, because FastAPI and Starlette put no limit on a
request body (ecosystem notes §7.2): it refuses a ``Content-Length`` over the limit before
reading anything and counts the bytes of a chunked body as they arrive (413). It also
admits at most ``jobs + queue`` lint (and fix) requests at a time (503 with ``Retry-After``), before
their bodies are read, so a flood of uploads cannot fill the disk.
"""

from __future__ import annotations

import json
import os
import re
from collections.abc import Awaitable, Callable, Mapping, MutableMapping
from dataclasses import dataclass
from typing import Any

from starlette.exceptions import HTTPException

Scope = MutableMapping[str, Any]
Message = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[Message]]
Send = Callable[[Message], Awaitable[None]]
ASGIApp = Callable[[Scope, Receive, Send], Awaitable[None]]

MiB = 2**20
FORM_SLACK = MiB  # multipart boundaries, part headers and the option fields
SIZE_RE = re.compile(r"^\s*(\d+)\s*([kmg]?)(?:i?b)?\s*$", re.I)
LINT_PATHS = ("/v1/check", "/v1/fix")  # the requests that upload a model and run a job


class LimitError(ValueError):
    """An environment variable with a value the service cannot use."""


def _cpus() -> int:
    try:
        return max(len(os.sched_getaffinity(0)), 1)
    except (AttributeError, OSError):  # pragma: no cover - not Linux
        return max(os.cpu_count() or 1, 1)


def parse_size(text: str) -> int:
    """``"5M"`` -> 5242880; plain digits are bytes."""
    match = SIZE_RE.match(text)
    if not match:
        raise ValueError(f"{text!r} is not a size (bytes, or a number with K, M or G)")
    return int(match.group(1)) * 1024 ** " kmg".index((match.group(2) or " ").lower())


@dataclass(frozen=True)
class Limits:
    max_urdf_bytes: int = 5 * MiB
    max_zip_bytes: int = 100 * MiB
    max_unzipped_bytes: int = 512 * MiB
    max_zip_members: int = 5000
    max_zip_ratio: float = 100.0
    timeout: float = 60.0
    jobs: int = 0  # 0: one per usable CPU
    queue: int = 16
    worker_memory: int = 3 * 1024 * MiB
    max_tasks: int = 500
    tmpdir: str | None = None
    allow_confirm: bool = False  # run the simulation engines on uploads (``confirm``)

    def __post_init__(self) -> None:
        if self.jobs <= 0:
            object.__setattr__(self, "jobs", _cpus())

    @classmethod
    def from_env(cls, environ: Mapping[str, str] | None = None) -> Limits:
        env = os.environ if environ is None else environ
        values: dict[str, Any] = {}
        for key, kind in ENV.items():
            name = f"URDFLINT_{key.upper()}"
            raw = env.get(name, "").strip()
            if not raw:
                continue
            try:
                value: Any = kind(raw)
            except ValueError as exc:
                raise LimitError(f"{name}: {exc}") from None
            if isinstance(value, (int, float)) and value < 0:
                raise LimitError(f"{name} must not be negative, got {raw!r}")
            values[key] = value
        if "max_urdf_bytes" in values and values["max_urdf_bytes"] == 0:
            raise LimitError("URDFLINT_MAX_URDF_BYTES must be positive")
        if values.get("timeout", 1) <= 0:
            raise LimitError("URDFLINT_TIMEOUT must be positive")
        return cls(**values)

    def body_limit(self, content_type: str) -> int:
        """The most bytes a ``/v1/check`` (or ``/v1/fix``) body of this type may have."""
        if content_type.split(";")[0].strip().lower() == "multipart/form-data":
            return self.max_urdf_bytes + self.max_zip_bytes + FORM_SLACK
        return self.max_urdf_bytes

    def public(self) -> dict[str, Any]:
        """What ``/readyz`` tells clients about the limits."""
        return {
            "max_urdf_bytes": self.max_urdf_bytes,
            "max_zip_bytes": self.max_zip_bytes,
            "max_unzipped_bytes": self.max_unzipped_bytes,
            "max_zip_members": self.max_zip_members,
            "timeout": self.timeout,
            "jobs": self.jobs,
            "queue": self.queue,
        }


def _float(text: str) -> float:
    return float(text)


def _flag(text: str) -> bool:
    value = text.strip().lower()
    if value in ("1", "true", "yes", "on"):
        return True
    if value in ("0", "false", "no", "off"):
        return False
    raise ValueError(f"expected 1 or 0 (true or false), got {text!r}")


ENV: dict[str, Callable[[str], Any]] = {
    "max_urdf_bytes": parse_size,
    "max_zip_bytes": parse_size,
    "max_unzipped_bytes": parse_size,
    "max_zip_members": int,
    "max_zip_ratio": _float,
    "timeout": _float,
    "jobs": int,
    "queue": int,
    "worker_memory": parse_size,
    "max_tasks": int,
    "tmpdir": str,
    "allow_confirm": _flag,
}


async def _reply(send: Send, status: int, detail: str, headers: list[tuple[bytes, bytes]]) -> None:
    body = json.dumps({"detail": detail}, separators=(",", ":")).encode()
    await send(
        {
            "type": "http.response.start",
            "status": status,
            "headers": [
                (b"content-type", b"application/json"),
                (b"content-length", str(len(body)).encode()),
                (b"connection", b"close"),
                *headers,
            ],
        }
    )
    await send({"type": "http.response.body", "body": body})


class Load:
    """The lint requests admitted and not yet answered (``/readyz`` reads it)."""

    def __init__(self) -> None:
        self.active = 0


class Guard:
    """Body size limits for every request, and admission control for ``/v1/check`` and
    ``/v1/fix``."""

    def __init__(self, app: ASGIApp, limits: Limits, load: Load | None = None) -> None:
        self.app = app
        self.limits = limits
        self.load = load if load is not None else Load()

    @property
    def active(self) -> int:
        """Lint requests admitted and not yet answered (shared with ``/readyz``)."""
        return self.load.active

    @active.setter
    def active(self, value: int) -> None:
        self.load.active = value

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        headers = dict(scope.get("headers") or ())
        content_type = headers.get(b"content-type", b"").decode("latin-1")
        is_check = scope.get("path", "").rstrip("/") in LINT_PATHS
        limit = self.limits.body_limit(content_type) if is_check else 64 * 1024
        length = headers.get(b"content-length")
        if length is not None and (not length.strip().isdigit() or int(length) > limit):
            await _reply(send, 413, f"request body over the {_size(limit)} limit", [])
            return
        if is_check and self.load.active >= self.limits.jobs + self.limits.queue:
            await _reply(
                send,
                503,
                "the server is busy: every lint worker and queue place is taken",
                [(b"retry-after", b"1")],
            )
            return
        received = 0

        async def limited() -> Message:
            nonlocal received
            message = await receive()
            if message["type"] == "http.request":
                received += len(message.get("body", b""))
                if received > limit:
                    raise HTTPException(413, f"request body over the {_size(limit)} limit")
            return message

        if not is_check:
            await self.app(scope, limited, send)
            return
        self.load.active += 1
        try:
            await self.app(scope, limited, send)
        finally:
            self.load.active -= 1


def _size(n: int) -> str:
    if n % MiB == 0 or n >= 10 * MiB:
        return f"{n / MiB:.0f} MiB"
    if n >= MiB:
        return f"{n / MiB:.1f} MiB"
    return f"{n} bytes"
