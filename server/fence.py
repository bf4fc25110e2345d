"""The fence around a lint job: an audit hook (PEP 578) and resource limits.

While a job runs (inside :func:`fenced`), the audit hook refuses, in the job's thread:

- opening or listing anything outside the request's folder and the Python installation
  (the interpreter's prefixes and the folders urdflint itself is imported from);
- creating sockets, resolving host names, connecting (no network, ever);
- starting processes (``subprocess``, ``os.system``, ``exec*``, ``fork``), in any thread of
  the worker, except the commands the job allows (:attr:`_Fence.commands`: with ``confirm``,
  the engine probe, started from inside the request's folder; see ``confirming.py``).

Temporary files a library makes during the job (Pinocchio's captured output) go to the
request's folder too (``tempfile.tempdir``), so they are removed with it.

A refused access raises ``PermissionError`` where it happens, which urdflint reports like
any unreadable file. :func:`set_memory_limit` gives a worker an address-space limit
(``RLIMIT_AS``) and :func:`set_cpu_limit`, per job, a CPU-time limit (``RLIMIT_CPU``): a
second fence behind the pool's wall-clock kill.
"""

from __future__ import annotations

import contextlib
import importlib.util
import logging
import os
import sys
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import Any

# the worker's logger: refused accesses are reported as the worker's
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
SPAWN_EVENTS = frozenset(
    {"subprocess.Popen", "os.system", "os.exec", "os.posix_spawn", "os.spawn", "os.fork",
     "os.forkpty", "pty.spawn"}
)  # fmt: skip
PATH_EVENTS = frozenset({"open", "os.listdir", "os.scandir", "glob.glob", "shutil.copyfile"})
WRITE_FLAGS = os.O_WRONLY | os.O_RDWR | os.O_CREAT | os.O_APPEND | os.O_TRUNC
DEVICES = ("/dev/null", "/dev/urandom", "/dev/random")
# the installed packages whose folders a job may read (an editable install maps them elsewhere)
READABLE_PACKAGES = ("urdflint.rules", "urdflint.server", "urdflint.fixtures")


class _Fence:
    """State of the audit hook: inactive between jobs, confined to ``root`` during one."""

    def __init__(self) -> None:
        self.root: str | None = None
        self.readable: tuple[str, ...] = ()
        self.importable: frozenset[str] = frozenset()
        self.denied: list[str] = []
        self.thread: int | None = None
        self.commands: tuple[tuple[str, ...], ...] = ()  # command prefixes the job may start
        self.cache: str | None = None  # the analysis cache folder (keys are digests)

    def allowed_path(self, raw: Any, write: bool) -> bool:
        """Whether the job may open ``raw`` (for writing when ``write``)."""
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
        if self.cache is not None and path.startswith(self.cache + os.sep):
            return True  # urdflint's own cache: the job names no path there
        if any(path == d.rstrip("/") or path.startswith(d) for d in DEVICES):
            return not write or path == "/dev/null"
        if write:
            return False
        return any(path == p or path.startswith(p + os.sep) for p in self.readable)

    def allowed_command(self, event: str, args: tuple[Any, ...]) -> bool:
        """Whether ``subprocess.Popen`` starts one of :attr:`commands` from inside the root."""
        if event != "subprocess.Popen" or not self.commands or len(args) < 3:
            return False
        executable, argv, cwd = args[:3]
        if not isinstance(argv, (list, tuple)) or cwd is None:
            return False
        try:
            words = [os.fsdecode(word) for word in argv]
            program = os.fsdecode(executable) if executable is not None else words[0]
        except (TypeError, IndexError):
            return False
        where, root = _real(cwd), self.root or ""
        if program != words[0] or not (root and where.startswith(root + os.sep)):
            return False  # started from inside the root, where the model was written
        return any(tuple(words[: len(prefix)]) == prefix for prefix in self.commands)

    def hook(self, event: str, args: tuple[Any, ...]) -> None:
        """The audit hook: raises ``PermissionError`` for what the running job may not do."""
        if self.root is None:
            return
        if event in SPAWN_EVENTS and not self.allowed_command(event, args):
            self.denied.append(event)  # any thread: the engines run from a thread pool
            raise PermissionError(f"urdflint service: {event} is not allowed while linting")
        if threading.get_ident() != self.thread:
            return
        if event in DENIED_ALWAYS and event not in SPAWN_EVENTS:
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
    for name in READABLE_PACKAGES:
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
        FENCE.commands = ()
        tempfile.tempdir = saved
        if FENCE.denied:
            log.warning("refused during the job: %s", "; ".join(FENCE.denied[:20]))


def set_memory_limit(limit: int) -> None:
    """Limit this process's address space to ``limit`` bytes (``RLIMIT_AS``; 0: no limit)."""
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
