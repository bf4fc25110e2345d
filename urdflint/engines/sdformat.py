"""sdformat, Gazebo's URDF to SDFormat converter, as a confirmation engine (``--confirm sdformat``).

sdformat has no Python binding: :file:`sdformat_probe.cc` (shipped with the package) calls
``sdf::Root::Load`` on the URDF and prints the same JSON report as
:mod:`urdflint.engines.probe`. It is compiled with ``g++`` against the ``sdformat12``
found by ``pkg-config`` (Debian: ``apt-get install libsdformat-dev``) the first time a
model is confirmed with sdformat, into ``$XDG_CACHE_HOME/urdflint/`` (else
``~/.cache/urdflint/``), under a name keyed by the source, the library's version and its
flags; later runs reuse that binary. :func:`installed` only asks ``pkg-config`` (nothing is
compiled unless a model is confirmed with sdformat); a compile that fails makes the engine
"not installed", with the compiler's first error as the reason (:class:`Unavailable`).
"""

from __future__ import annotations

import functools
import hashlib
import os
import shutil
import subprocess
import tempfile
import threading
from pathlib import Path

PACKAGE = "sdformat12"  # the pkg-config name of libsdformat12 (Debian bookworm: 12.3)
SOURCE = Path(__file__).with_name("sdformat_probe.cc")
COMPILE_TIMEOUT = 600.0  # seconds
_LOCK = threading.Lock()


class Unavailable(Exception):
    """The probe cannot be built here; the message is a one-line reason."""


def _ask(*command: str) -> str | None:
    """The stripped output of a quick command, or ``None`` when it fails or is missing."""
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=30)
    except (OSError, subprocess.TimeoutExpired):
        return None
    return done.stdout.strip() if done.returncode == 0 else None


@functools.lru_cache(maxsize=1)
def library() -> tuple[str, tuple[str, ...]] | None:
    """``(version, compiler flags)`` of sdformat12 from ``pkg-config``; ``None`` without it."""
    if shutil.which("pkg-config") is None:
        return None
    version = _ask("pkg-config", "--modversion", PACKAGE)
    flags = _ask("pkg-config", "--cflags", "--libs", PACKAGE)
    if version is None or flags is None:
        return None
    return version, tuple(flags.split())


def compiler() -> str | None:
    return shutil.which(os.environ.get("CXX") or "g++")


def installed() -> bool:
    """Whether sdformat12 and a C++ compiler are there (cheap: the probe is not built)."""
    return compiler() is not None and library() is not None and _failed() is None


def cache_dir() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "urdflint"


def binary_path() -> Path:
    """Where the probe for this source and this sdformat is (or will be) compiled."""
    found = library()
    key = hashlib.sha256(SOURCE.read_bytes())
    key.update(repr(found).encode())
    return cache_dir() / f"sdformat_probe-{found[0] if found else 'none'}-{key.hexdigest()[:16]}"


_FAILURE: list[str] = []  # the reason the compile failed in this process (not retried)


def _failed() -> str | None:
    return _FAILURE[0] if _FAILURE else None


def binary() -> Path:
    """The compiled probe, built on first use (atomically: a temporary file, then a rename).

    Raises :class:`Unavailable` when sdformat12 or the compiler is missing or the compile
    fails; a failure is remembered for the rest of the process.
    """
    with _LOCK:
        if _failed() is not None:
            raise Unavailable(_failed())
        target = binary_path()
        if os.access(target, os.X_OK):
            return target
        try:
            _compile(target)
        except Unavailable as exc:
            _FAILURE.append(str(exc))
            raise
        return target


def _compile(target: Path) -> None:
    found, cxx = library(), compiler()
    if found is None or cxx is None:
        raise Unavailable(f"pkg-config does not know {PACKAGE}" if cxx else "there is no g++")
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        handle, temporary = tempfile.mkstemp(prefix=target.name + ".", dir=target.parent)
        os.close(handle)
    except OSError as exc:
        raise Unavailable(
            f"its probe cannot be written in {target.parent} ({exc.strerror})"
        ) from exc
    command = [cxx, "-O1", "-o", temporary, str(SOURCE), *found[1]]
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=COMPILE_TIMEOUT)
        if done.returncode != 0:
            raise Unavailable(f"its probe did not compile ({_first_error(done.stderr)})")
        os.chmod(temporary, 0o755)
        os.replace(temporary, target)
    except (OSError, subprocess.TimeoutExpired) as exc:
        raise Unavailable(f"its probe did not compile ({exc})") from exc
    finally:
        if os.path.exists(temporary):
            os.unlink(temporary)


def _first_error(printed: str) -> str:
    lines = [line.strip() for line in printed.splitlines() if line.strip()]
    errors = [line for line in lines if "error" in line.lower()]
    return (errors or lines or ["no message"])[0]


def command(model: Path, memory: int) -> list[str]:
    """The command line that loads ``model`` in sdformat (compiling the probe if needed)."""
    return [str(binary()), str(model), str(memory)]


def environment(folder: Path) -> dict[str, str]:
    """The probe's environment: ``HOME`` is ``folder``, where sdformat writes its log file
    (``~/.sdformat/sdformat.log``) instead of the user's home."""
    return {**os.environ, "HOME": str(folder)}
