"""``urdflint check --watch``: check, then check again whenever an input changes.

The inputs are what the run read, recorded as the analysis cache records them
(:mod:`urdflint.cache.deps`): the checked files, their xacro includes and YAML files, the
meshes, ``package.xml`` files, the configuration, the folders listed (a robot file added to a
checked folder), and the paths looked for and not found (a mesh that appears). A result
replayed from the cache brings the inputs recorded with it. They are polled every half
second by modification time and size (no dependency on a file-watching library). Runs are
in one process (``--jobs 1``): the inputs of a file checked in another process are not
seen. On a terminal the screen is cleared before each new run. Ctrl-C ends the watch with
exit code 0.
"""

from __future__ import annotations

import argparse
import copy
import os
import signal
import sys
import time
from collections.abc import Callable, Iterable
from pathlib import Path

from urdflint.cache import code_folders, deps, store
from urdflint.cli.common import EXIT_ERROR, EXIT_OK, UsageError, settings_here

POLL = 0.5  # s between two looks at the inputs
SETTLE = 0.1  # s: a change is run on once two looks this far apart agree (a save in parts)
CLEAR = "\x1b[2J\x1b[3J\x1b[H"
State = dict[str, tuple[int, int] | None]  # path -> (mtime ns, size), None: absent


def run(args: argparse.Namespace, check: Callable[[argparse.Namespace], int]) -> int:
    """Watch ``check(args)`` (the ``check`` command without ``--watch``) until Ctrl-C."""
    # Ctrl-C must stop the watch even when started with SIGINT ignored (a background job,
    # a test runner's worker): Python then installs no KeyboardInterrupt handler itself
    signal.signal(signal.SIGINT, signal.default_int_handler)
    once = copy.copy(args)
    once.watch = False
    once.jobs = 1
    terminal = sys.stdout.isatty()
    try:
        _, paths = _run(once, check, first=True)
        state = snapshot(paths)
        while True:
            _say(f"watching {_count(paths)} for changes (Ctrl-C stops)")
            state = _wait(state)
            if terminal:
                sys.stdout.write(CLEAR)
                sys.stdout.flush()
            _, more = _run(once, check, first=False)
            paths |= more  # a memo in this process may hide an input a later run reads
            state = {**snapshot(paths), **state}  # a change during the run: seen next
    except KeyboardInterrupt:
        sys.stderr.write("\n")
        return EXIT_OK


def _run(
    args: argparse.Namespace, check: Callable[[argparse.Namespace], int], first: bool
) -> tuple[int, set[str]]:
    """One check, and the inputs it read. A usage error (an invalid configuration just
    saved) ends the first run only; later, the watch goes on for its fix."""
    with deps.recording() as recorder:
        try:
            code = check(args)
        except UsageError as exc:
            if first:
                raise
            print(f"urdflint: error: {exc}", file=sys.stderr)
            code = EXIT_ERROR
    return code, inputs(recorder, args)


def inputs(recorder: deps.Recorder, args: argparse.Namespace) -> set[str]:
    """The files and folders a run read (recorded, or replayed with a cached result) and
    the paths it was given, without urdflint's own code, Python's and the cache's folder."""
    found = {*recorder.files, *recorder.dirs, *recorder.absent}
    found.update(name for (kind, name) in recorder.inherited if kind in ("file", "dir", "absent"))
    found.update(os.path.abspath(p) for p in args.paths if p != "-")
    skip = tuple(_skipped(args))
    return {path for path in found if not os.path.join(path, "").startswith(skip)}


def _skipped(args: argparse.Namespace) -> Iterable[str]:
    yield from ("/proc/", "/sys/", "/dev/")
    yield from code_folders()
    for prefix in {sys.prefix, sys.base_prefix, sys.exec_prefix}:
        yield os.path.join(prefix, "")
    settings = settings_here(args)
    for folder in (args.cache_dir, getattr(settings, "cache_dir", None), store.default_dir()):
        if folder is not None:
            yield os.path.join(os.path.abspath(folder), "")


def snapshot(paths: Iterable[str]) -> State:
    state: State = {}
    for path in paths:
        try:
            info = os.stat(path)
        except OSError:
            state[path] = None
            continue
        state[path] = (info.st_mtime_ns, info.st_size)
    return state


def _wait(state: State) -> State:
    """Sleep until an input changes, and until it stops changing; the new state."""
    while True:
        time.sleep(POLL)
        now = snapshot(state)
        if now != state:
            break
    while True:
        time.sleep(SETTLE)
        later = snapshot(state)
        if later == now:
            return later
        now = later


def _say(text: str) -> None:
    print(f"urdflint: {text}", file=sys.stderr, flush=True)


def _count(paths: set[str]) -> str:
    folders = sum(1 for p in paths if Path(p).is_dir())
    files = sum(1 for p in paths if Path(p).is_file())
    text = f"{files} file{'' if files == 1 else 's'}"
    return text + (f" and {folders} folder{'' if folders == 1 else 's'}" if folders else "")
