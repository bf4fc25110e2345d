"""A lint worker process: runs one job at a time, fenced off from files, network and children.

The pool (``pool.py``) starts each worker with :func:`main`, sends it jobs over a pipe
and kills it when a job overruns the request's time limit. Inside, besides urdflint's own
confinement (``Context(root=...)``: the resolver, the mesh cache and xacro only see the
request's folder), every job runs under an audit hook (PEP 578) that refuses, while the job
runs:

- opening or listing anything outside the request's folder and the Python installation
  (the interpreter's prefixes and the folders urdflint itself is imported from);
- creating sockets, resolving host names, connecting (no network, ever);
- starting processes (``subprocess``, ``os.system``, ``exec*``, ``fork``).

Temporary files a library makes during the job (Pinocchio's captured output) go to the
request's folder too (``tempfile.tempdir``), so they are removed with it.

A refused access raises ``PermissionError`` where it happens, which urdflint reports like
any unreadable file. Each worker also gets an address-space limit (``RLIMIT_AS``) and, per
job, a CPU-time limit (``RLIMIT_CPU``) a little over the request timeout, as a second fence
behind the pool's wall-clock kill.
"""

from __future__ import annotations

import contextlib
import importlib.util
import logging
import os
import sys
import threading
import traceback
from collections.abc import Iterator
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from urdflint.server.threads import limit_threads

if TYPE_CHECKING:
    from multiprocessing.connection import Connection

    from urdflint.engine.config import Settings

    from .uploads import ZipLimits

log = logging.getLogger("urdflint.server.worker")

DENIED_ALWAYS = frozenset(
    {
        "socket.__new__",
        "socket.bind",
        "socket.connect",
        "socket.getaddrinfo",
        "socket.gethostbyname",
        "socket.gethostbyaddr",
        "socket.sendto",
        "subprocess.Popen",
        "os.system",
        "os.exec",
        "os.posix_spawn",
        "os.spawn",
        "os.fork",
        "os.forkpty",
        "pty.spawn",
        "webbrowser.open",
        "urllib.Request",
        "ftplib.connect",
        "http.client.connect",
        "smtplib.connect",
    }
)
PATH_EVENTS = frozenset({"open", "os.listdir", "os.scandir", "glob.glob", "shutil.copyfile"})
WRITE_FLAGS = os.O_WRONLY | os.O_RDWR | os.O_CREAT | os.O_APPEND | os.O_TRUNC
DEVICES = ("/dev/null", "/dev/urandom", "/dev/random")


# -- the fence ----------------------------------------------------------------------------


class _Fence:
    """State of the audit hook: inactive between jobs, confined to ``root`` during one."""

    def __init__(self) -> None:
        self.root: str | None = None
        self.readable: tuple[str, ...] = ()
        self.importable: frozenset[str] = frozenset()
        self.denied: list[str] = []
        self.thread: int | None = None

    def allowed_path(self, raw: Any, write: bool) -> bool:
        if isinstance(raw, int):
            return True  # an already open descriptor
        try:
            text = os.fsdecode(raw)
        except TypeError:
            return True
        path = os.path.realpath(os.path.abspath(text))
        assert self.root is not None
        if path == self.root or path.startswith(self.root + os.sep):
            return True
        if any(path == d.rstrip("/") or path.startswith(d) for d in DEVICES):
            return not write or path == "/dev/null"
        if write:
            return False
        return any(path == p or path.startswith(p + os.sep) for p in self.readable)

    def hook(self, event: str, args: tuple[Any, ...]) -> None:
        if self.root is None or threading.get_ident() != self.thread:
            return
        if event in DENIED_ALWAYS:
            self.denied.append(event)
            raise PermissionError(f"urdflint service: {event} is not allowed while linting")
        if event not in PATH_EVENTS or not args:
            return
        write = False
        if event == "open":
            mode, flags = (*args, None, 0)[1:3]
            write = bool(
                (isinstance(mode, str) and any(c in mode for c in "wax+"))
                or (isinstance(flags, int) and flags & WRITE_FLAGS)
            )
        target = args[1] if event == "shutil.copyfile" else args[0]
        if target is None or self.allowed_path(target, write):
            return
        if event in ("os.listdir", "os.scandir") and _real(target) in self.importable:
            return  # the import system lists sys.path folders (names only, no content)
        self.denied.append(f"{event} {target!r}")
        raise PermissionError(f"urdflint service: {os.fsdecode(target)} is outside the upload")


def _real(raw: Any) -> str:
    if isinstance(raw, int):
        return ""
    return os.path.realpath(os.path.abspath(os.fsdecode(raw)))


FENCE = _Fence()
_installed = False


def _readable_prefixes() -> tuple[str, ...]:
    import urdflint

    found = {sys.prefix, sys.base_prefix, sys.exec_prefix, sys.base_exec_prefix}
    found.add(str(Path(urdflint.__file__).parent))
    for name in ("urdflint.rules", "urdflint.server", "urdflint.fixtures"):
        with contextlib.suppress(ImportError, ValueError):
            spec = importlib.util.find_spec(name)  # an editable install maps these elsewhere
            found.update(spec.submodule_search_locations or () if spec else ())
    for entry in sys.path:
        # site-packages folders (editable installs and .pth files add others); never the
        # current folder, which is where the server happened to be started.
        if entry and "-packages" in entry:
            found.add(entry)
    return tuple(sorted(os.path.realpath(p) for p in found if p))


def install_fence() -> None:
    """Add the audit hook (once per process; audit hooks cannot be removed)."""
    global _installed
    if not _installed:
        FENCE.readable = _readable_prefixes()
        FENCE.importable = frozenset(_real(p or os.curdir) for p in sys.path)
        sys.addaudithook(FENCE.hook)
        _installed = True


@contextlib.contextmanager
def fenced(root: Path) -> Iterator[list[str]]:
    """Run the body confined to ``root``; yields the list of refused accesses."""
    import tempfile

    install_fence()
    scratch = root / "tmp"
    scratch.mkdir(mode=0o700, exist_ok=True)
    saved, tempfile.tempdir = tempfile.tempdir, str(scratch)  # temporary files stay inside
    FENCE.root = os.path.realpath(root)
    FENCE.thread = threading.get_ident()
    FENCE.denied = []
    try:
        yield FENCE.denied
    finally:
        FENCE.root = None
        FENCE.thread = None
        tempfile.tempdir = saved
        if FENCE.denied:
            log.warning("refused during the job: %s", "; ".join(FENCE.denied[:20]))


def set_memory_limit(limit: int) -> None:
    if limit <= 0:
        return
    import resource

    with contextlib.suppress(ValueError, OSError):
        _soft, hard = resource.getrlimit(resource.RLIMIT_AS)
        cap = limit if hard == resource.RLIM_INFINITY else min(limit, hard)
        resource.setrlimit(resource.RLIMIT_AS, (cap, hard))


def set_cpu_limit(seconds: float) -> None:
    """Let this process use ``seconds`` more CPU time, then SIGXCPU ends it."""
    import resource

    usage = resource.getrusage(resource.RUSAGE_SELF)
    soft = int(usage.ru_utime + usage.ru_stime + seconds) + 1
    with contextlib.suppress(ValueError, OSError):
        _soft, hard = resource.getrlimit(resource.RLIMIT_CPU)
        if hard != resource.RLIM_INFINITY:
            soft = min(soft, hard)
        resource.setrlimit(resource.RLIMIT_CPU, (soft, hard))


# -- jobs -----------------------------------------------------------------------------------


@dataclass(frozen=True)
class CheckJob:
    """One ``POST /v1/check``: the files are in ``folder``, which the app removes after."""

    folder: str
    name: str  # the URDF's file name, as findings show it
    urdf: bytes
    zip: str | None  # the uploaded meshes zip (inside folder), if any
    settings: Settings
    fmt: str = "json"
    svg: bool = False
    zip_limits: ZipLimits | None = None


@dataclass(frozen=True)
class ReadyJob:
    """``GET /readyz``: build a tiny model with Pinocchio, load a tiny mesh."""

    folder: str


def reply(status: int, content: Any, media_type: str = "application/json") -> dict[str, Any]:
    return {"status": status, "content": content, "media_type": media_type}


def run(job: CheckJob | ReadyJob) -> dict[str, Any]:
    """Do one job; never raises (an unexpected error is a 500 with no details)."""
    try:
        if isinstance(job, ReadyJob):
            return ready(job)
        return check(job)
    except MemoryError:
        return reply(422, {"detail": "checking this input needs more memory than allowed"})
    except RecursionError:
        return reply(422, {"detail": "the input is nested too deeply to check"})
    except Exception:
        log.error("lint job failed:\n%s", traceback.format_exc())
        return reply(500, {"detail": "internal error while linting (see the server log)"})


def check(job: CheckJob) -> dict[str, Any]:
    from urdflint import __version__
    from urdflint.engine import linter
    from urdflint.engine.context import Context
    from urdflint.model.finding import Finding
    from urdflint.outputs import formatters
    from urdflint.outputs.report import FAIL_LEVEL, model_summary, skipped_note

    from .uploads import Rejected, ZipLimits, extract

    root = Path(job.folder) / "files"
    root.mkdir(mode=0o700)
    with fenced(Path(job.folder)):
        packages: dict[str, Path] = {}
        if job.zip is not None:
            try:
                packages = extract(Path(job.zip), root, job.zip_limits or ZipLimits())
            except Rejected as exc:
                return reply(422, {"detail": str(exc)})
        target = root / job.name
        if target.is_dir():
            return reply(422, {"detail": f"the zip has a folder named like the URDF {job.name!r}"})
        target.unlink(missing_ok=True)
        fd = os.open(target, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o600)
        with os.fdopen(fd, "wb") as out:
            out.write(job.urdf)
        settings = job.settings
        context = Context(package_paths=packages, root=root, environ={})
        result = linter.lint_path(target, job.name, settings, context)
        findings: list[Finding] = list(result.findings)
        skipped = dict(result.skipped)
        expects = settings.expect.mass is not None or settings.expect.com is not None
        gate = expects and bool({"P003", "P004"} & set(skipped))
        if skipped and (gate or "U004" in settings.enabled()):
            findings.append(skipped_note(job.name, skipped, expects))
        findings = sorted((_scrub(f, root) for f in findings), key=Finding.sort_key)
        models = {job.name: model_summary(result)} if job.fmt == "json" else {}
        run_info = formatters.RunInfo(__version__, (job.name,), models)
        if job.fmt != "json":
            return _rendered(job.fmt, findings, run_info)
        from urdflint.outputs.formatters.json import document

        data = document(findings, run_info)
        threshold = FAIL_LEVEL.get(settings.fail_on)
        failing = threshold is not None and any(f.severity >= threshold for f in findings)
        data["passed"] = not (failing or result.crashed)
        if job.svg and result.document is not None:
            picture = _svg(result.document, findings)
            if picture is not None:
                data["svg"] = {job.name: picture}
        return reply(200, data)


def _rendered(fmt: str, findings: list[Any], run_info: Any) -> dict[str, Any]:
    from urdflint.outputs import formatters

    if fmt == "sarif":
        try:
            from urdflint.outputs.formatters import sarif  # type: ignore[attr-defined,unused-ignore]
        except ImportError:
            return reply(422, {"detail": "the sarif format is not available on this server"})
        return reply(200, sarif.render(findings, run_info), "application/sarif+json")
    return reply(200, formatters.get(fmt)(findings, run_info), "text/plain; charset=utf-8")


def _svg(doc: Any, findings: list[Any]) -> str | None:
    try:
        from urdflint.outputs.svg import render_tree  # type: ignore[attr-defined,unused-ignore]
    except ImportError:
        return None
    try:
        return str(render_tree(doc, findings))
    except Exception:  # a picture must never cost the findings
        log.warning("the kinematic tree picture failed:\n%s", traceback.format_exc())
        return None


def _scrub(finding: Any, root: Path) -> Any:
    """Findings never show the server's folders: paths inside the upload become relative."""
    prefixes = sorted({str(root), os.path.realpath(root)}, key=len, reverse=True)

    def clean(text: str | None) -> str | None:
        if text is None:
            return None
        for prefix in prefixes:
            text = text.replace(prefix + os.sep, "").replace(prefix, ".")
        return text

    fields: dict[str, str | None] = {}
    for name in ("path", "message", "fix"):
        value = getattr(finding, name)
        cleaned = clean(value)
        if cleaned != value:
            fields[name] = cleaned
    return replace(finding, **fields) if fields else finding


TETRA = """solid t
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 0.1 0 0
  vertex 0 0.1 0
 endloop
endfacet
facet normal 0 -1 0
 outer loop
  vertex 0 0 0
  vertex 0 0 0.1
  vertex 0.1 0 0
 endloop
endfacet
facet normal -1 0 0
 outer loop
  vertex 0 0 0
  vertex 0 0.1 0
  vertex 0 0 0.1
 endloop
endfacet
facet normal 1 1 1
 outer loop
  vertex 0.1 0 0
  vertex 0 0 0.1
  vertex 0 0.1 0
 endloop
endfacet
endsolid t
"""

TINY = b"""<robot name="ready">
  <link name="base"/>
  <joint name="j" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <link name="arm">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
    </inertial>
    <visual><geometry><mesh filename="tetra.stl"/></geometry></visual>
  </link>
</robot>
"""


def ready(job: ReadyJob) -> dict[str, Any]:
    from importlib import metadata

    from urdflint.engine.context import Context
    from urdflint.model import optional
    from urdflint.model.document import Document

    root = Path(job.folder) / "ready"
    root.mkdir(mode=0o700)
    (root / "tetra.stl").write_text(TETRA)
    caps: dict[str, Any] = {}
    ok = True
    with fenced(Path(job.folder)):
        context = Context(root=root, environ={})
        doc = Document("ready.urdf", TINY, context=context, base_dir=root)
        for module, dist in (("pinocchio", "pin"), ("trimesh", "trimesh"), ("xacro", "xacro")):
            entry: dict[str, Any] = {"available": optional.available(module)}
            with contextlib.suppress(metadata.PackageNotFoundError):
                entry["version"] = metadata.version(dist)
            caps[module] = entry
        if caps["pinocchio"]["available"]:
            physics = doc.physics
            caps["pinocchio"]["works"] = bool(physics.built and physics.dof == 1)
            if not caps["pinocchio"]["works"]:
                caps["pinocchio"]["error"] = physics.reason
                ok = False
        if caps["trimesh"]["available"]:
            info = context.meshes.load(root / "tetra.stl")
            caps["trimesh"]["works"] = bool(info.ok and info.faces == 4)
            if not caps["trimesh"]["works"]:
                caps["trimesh"]["error"] = info.error
                ok = False
        caps["collada"] = {"available": optional.available("collada")}
    return reply(200 if ok else 503, {"ready": ok, "capabilities": caps})


# -- the process -----------------------------------------------------------------------------


@dataclass(frozen=True)
class WorkerConfig:
    memory: int = 0
    timeout: float = 60.0


def main(conn: Connection, config: WorkerConfig) -> None:
    """The worker loop: receive a job, send its reply; ``None`` ends the loop."""
    limit_threads()
    set_memory_limit(config.memory)
    with contextlib.suppress(ImportError):
        from . import _preload  # noqa: F401  (already imported when forked from the forkserver)
    install_fence()
    conn.send("ready")
    while True:
        try:
            job = conn.recv()
        except (EOFError, OSError):
            return
        if job is None:
            return
        set_cpu_limit(config.timeout * 1.5 + 5)
        answer = run(job)
        try:
            conn.send(answer)
        except (OSError, ValueError):
            return
