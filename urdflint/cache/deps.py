"""What an analysis read, and whether any of it changed since.

While a cached computation runs, a :class:`Recorder` collects its inputs:

- every file Python opens for reading (a PEP 578 audit hook on ``open``, installed once per
  process and idle unless a recorder is active in the current thread or task): the file,
  xacro's includes and YAML files, ``package.xml`` files, an SRDF, a mesh trimesh reads;
- every folder listed (``os.listdir``/``os.scandir`` events): a file added or removed there
  changes the folder's modification time;
- what the code says explicitly: paths looked for and not found (``absent``: a mesh that is
  added later), the content of an editor's unsaved buffer (``content``), environment
  variables xacro's ``$(env)`` read, the package index a lookup used, a mesh whose facts
  came from the cache instead of the file.

A recorded input is a :class:`Dep`. :func:`unchanged` checks them all: a file whose size
and modification time are as recorded is unchanged without being read (unless it was
written less than ``RACY`` seconds before it was recorded: then its content is compared,
as git does for "racily clean" files); otherwise its content digest decides, so a file that
was only touched (a ``git checkout``) still hits.
"""

from __future__ import annotations

import contextlib
import contextvars
import hashlib
import os
import stat
import sys
import threading
import time
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from typing import Any

CODE_SUFFIXES = (".py", ".pyc", ".so", ".pth", "__pycache__")  # imports, not inputs
RACY = 2.0  # s: a file written this shortly before it was recorded is compared by content
READ_LIMIT = 256 * 2**20  # files over this are compared by size and time only

_CURRENT: contextvars.ContextVar[Recorder | None] = contextvars.ContextVar(
    "urdflint_recorder", default=None
)
_HOOKED = False
_HOOK_LOCK = threading.Lock()
_WRITE_FLAGS = os.O_WRONLY | os.O_RDWR | os.O_CREAT | os.O_TRUNC | os.O_APPEND


def digest_bytes(data: bytes) -> str:
    return hashlib.blake2b(data, digest_size=16).hexdigest()


def digest_file(path: str) -> str | None:
    """The content digest of a file, or ``None`` when it cannot be read."""
    try:
        h = hashlib.blake2b(digest_size=16)
        with open(path, "rb") as handle:
            while chunk := handle.read(1 << 20):
                h.update(chunk)
        return h.hexdigest()
    except OSError:
        return None


# -- digests, with a memo by file identity -----------------------------------------------------

_MEMO: dict[tuple[str, int, int, int], str] = {}
_MEMO_MAX = 20_000


def file_digest(path: str, info: os.stat_result | None = None) -> str | None:
    """The content digest of ``path``, read once per process for one (size, mtime, inode)
    unless the file was written in the last ``RACY`` seconds."""
    if info is None:
        try:
            info = os.stat(path)
        except OSError:
            return None
    key = (path, info.st_size, info.st_mtime_ns, info.st_ino)
    found = _MEMO.get(key)
    if found is not None:
        return found
    found = digest_file(path)
    if found is not None and time.time() - info.st_mtime > RACY:
        if len(_MEMO) >= _MEMO_MAX:
            _MEMO.clear()
        _MEMO[key] = found
    return found


# -- what a computation read -------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Dep:
    """One input: ``kind`` is ``file``, ``dir``, ``absent``, ``content``, ``env`` or
    ``packages``; ``value`` is what was seen (size, time and digest for a file, the
    modification time for a folder, the digest of a buffer, the variable's value...)."""

    kind: str
    name: str
    value: Any


class Recorder:
    """The inputs of one computation (see the module docstring)."""

    def __init__(self, ignore: tuple[str, ...] = ()) -> None:
        self.files: dict[str, None] = {}
        self.dirs: dict[str, None] = {}
        self.absent: dict[str, None] = {}
        self.contents: dict[str, str] = {}
        self.environ: dict[str, str | None] = {}
        self.extra: dict[tuple[str, str], Any] = {}
        self.inherited: dict[tuple[str, str], Dep] = {}
        self.ignore = ignore
        self.started = time.time()
        # what the import system opens and lists while a lazy import runs: code, not input
        self.imports = frozenset(os.path.abspath(p) for p in sys.path if p)

    def keep(self, path: str) -> bool:
        inside = (path + os.sep).startswith(self.ignore)  # a folder itself, or below one
        return not inside and not path.endswith(CODE_SUFFIXES) and path not in self.imports

    def inherit(self, deps: tuple[Dep, ...]) -> None:
        """The inputs of a cached computation that ran (or was replayed) inside this one."""
        for dep in deps:
            self.inherited.setdefault((dep.kind, dep.name), dep)

    def deps(self) -> tuple[Dep, ...]:
        """The recorded inputs as they are now (call right after the computation)."""
        found: list[Dep] = list(self.inherited.values())
        for path in self.contents:
            found.append(Dep("content", path, self.contents[path]))
        for path in self.files:
            if path in self.contents:
                continue
            found.append(_file_dep(path))
        for path in self.dirs:
            try:
                found.append(Dep("dir", path, os.stat(path).st_mtime_ns))
            except OSError:
                found.append(Dep("absent", path, None))
        for path in self.absent:
            if path not in self.files and path not in self.dirs:
                found.append(Dep("absent", path, None))
        for name, value in self.environ.items():
            found.append(Dep("env", name, value))
        for (kind, name), value in self.extra.items():
            found.append(Dep(kind, name, value))
        return tuple(found)


def _file_dep(path: str) -> Dep:
    try:
        info = os.stat(path)
    except OSError:
        return Dep("absent", path, None)
    if stat.S_ISDIR(info.st_mode):
        return Dep("dir", path, info.st_mtime_ns)
    racy = time.time() - info.st_mtime <= RACY
    digest = file_digest(path, info) if info.st_size <= READ_LIMIT else None
    return Dep("file", path, (info.st_size, info.st_mtime_ns, digest, racy))


def current() -> Recorder | None:
    return _CURRENT.get()


class recording:
    """``with recording() as rec:`` collects the inputs of what runs inside."""

    def __init__(self, ignore: tuple[str, ...] = ()) -> None:
        self.recorder = Recorder(ignore)
        self._token: contextvars.Token[Recorder | None] | None = None

    def __enter__(self) -> Recorder:
        _install()
        self._token = _CURRENT.set(self.recorder)
        return self.recorder

    def __exit__(self, *exc: object) -> None:
        assert self._token is not None
        _CURRENT.reset(self._token)


@contextlib.contextmanager
def unrecorded() -> Iterator[None]:
    """No recording in this block (what the cache itself reads is not an input)."""
    token = _CURRENT.set(None)
    try:
        yield
    finally:
        _CURRENT.reset(token)


# -- what the code tells -----------------------------------------------------------------------


def note_file(path: str | os.PathLike[str]) -> None:
    rec = _CURRENT.get()
    if rec is not None:
        full = os.path.abspath(path)
        if rec.keep(full):
            rec.files[full] = None


def note_absent(path: str | os.PathLike[str]) -> None:
    rec = _CURRENT.get()
    if rec is not None:
        rec.absent[os.path.abspath(path)] = None


def note_content(path: str | os.PathLike[str], data: bytes) -> None:
    """A file's text came from an editor's buffer: the buffer's content is the input."""
    rec = _CURRENT.get()
    if rec is not None:
        rec.contents[os.path.abspath(path)] = digest_bytes(data)


def note_env(name: str, value: str | None) -> None:
    rec = _CURRENT.get()
    if rec is not None:
        rec.environ[name] = value


def note(kind: str, name: str, value: Any) -> None:
    """Any other input that a checker registered with :func:`register` can check again."""
    rec = _CURRENT.get()
    if rec is not None:
        rec.extra[(kind, name)] = value


class WatchedEnviron(Mapping[str, str]):
    """An environment whose reads are inputs (xacro's ``$(env)`` and ``$(optenv)``)."""

    def __init__(self, environ: Mapping[str, str]) -> None:
        self._environ = environ

    def __getitem__(self, name: str) -> str:
        value = self._environ.get(name)
        note_env(name, value)
        if value is None:
            raise KeyError(name)
        return value

    def __iter__(self) -> Iterator[str]:
        return iter(self._environ)

    def __len__(self) -> int:
        return len(self._environ)


# -- the audit hook ----------------------------------------------------------------------------


def _install() -> None:
    global _HOOKED
    if _HOOKED:
        return
    with _HOOK_LOCK:
        if not _HOOKED:
            sys.addaudithook(_hook)
            _HOOKED = True


def _hook(event: str, args: tuple[Any, ...]) -> None:
    if event == "open":
        rec = _CURRENT.get()
        if rec is None:
            return
        path, mode, flags = args
        if path is None or isinstance(path, int):
            return
        if mode is not None:
            if any(c in mode for c in "wax+"):
                return
        elif isinstance(flags, int) and flags & _WRITE_FLAGS:
            return
        try:
            full = os.path.abspath(os.fsdecode(path))
        except (TypeError, ValueError):
            return
        if rec.keep(full):
            rec.files[full] = None
    elif event == "os.listdir" or event == "os.scandir":
        rec = _CURRENT.get()
        if rec is None:
            return
        path = args[0]
        if path is None or isinstance(path, int):
            path = "."
        try:
            full = os.path.abspath(os.fsdecode(path))
        except (TypeError, ValueError):
            return
        if rec.keep(full):
            rec.dirs[full] = None


# -- checking again ----------------------------------------------------------------------------

Checker = Callable[[str, Any], bool]  # (name, recorded value) -> still the same?
_CHECKERS: dict[str, Checker] = {}


def register(kind: str, checker: Checker) -> None:
    _CHECKERS[kind] = checker


def unchanged(
    deps: tuple[Dep, ...],
    overlay: Mapping[str, bytes] | None = None,
    environ: Mapping[str, str] | None = None,
    checkers: Mapping[str, Checker] | None = None,
) -> bool:
    """Whether every input is as it was recorded."""
    return not changes(deps, overlay, environ, checkers, limit=1)


def changes(
    deps: tuple[Dep, ...],
    overlay: Mapping[str, bytes] | None = None,
    environ: Mapping[str, str] | None = None,
    checkers: Mapping[str, Checker] | None = None,
    limit: int = 1,
) -> list[Dep]:
    """The inputs that are no longer as recorded (at most ``limit`` of them)."""
    found: list[Dep] = []
    for dep in deps:
        if not _same(dep, overlay or {}, os.environ if environ is None else environ, checkers):
            found.append(dep)
            if len(found) >= limit:
                break
    return found


def now(dep: Dep, overlay: Mapping[str, bytes] | None = None) -> Dep:
    """``dep`` as the file or buffer is now (a ``file`` or ``content`` input)."""
    data = (overlay or {}).get(dep.name)
    if data is not None:
        return Dep("content", dep.name, digest_bytes(data))
    return _file_dep(dep.name)


def _same(
    dep: Dep,
    overlay: Mapping[str, bytes],
    env: Mapping[str, str],
    checkers: Mapping[str, Checker] | None,
) -> bool:
    """Whether one input is as it was recorded."""
    kind = dep.kind
    if kind == "file":
        if dep.name in overlay:
            return False  # now an unsaved buffer: recorded as a file on disk
        size, mtime, digest, racy = dep.value
        try:
            info = os.stat(dep.name)
        except OSError:
            return False
        if info.st_size != size:
            return False
        if info.st_mtime_ns == mtime and not racy:
            return True
        return digest is not None and file_digest(dep.name, info) == digest
    if kind == "dir":
        try:
            return os.stat(dep.name).st_mtime_ns == dep.value
        except OSError:
            return False
    if kind == "absent":
        return dep.name not in overlay and not os.path.lexists(dep.name)
    if kind == "content":
        data = overlay.get(dep.name)
        if data is not None:
            return digest_bytes(data) == dep.value
        return file_digest(dep.name) == dep.value
    if kind == "env":
        return env.get(dep.name) == dep.value
    checker = (checkers or {}).get(kind) or _CHECKERS.get(kind)
    return checker is not None and bool(checker(dep.name, dep.value))
