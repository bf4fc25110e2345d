"""``confirm`` in the service: the simulation engines load the upload, and only the upload.

Off unless the server was started with ``urdflint serve --allow-confirm``
(``URDFLINT_ALLOW_CONFIRM``): the engines (MuJoCo, PyBullet, Drake, Pinocchio) are large
native libraries and the model is untrusted input. ``urdflint.engines.runner`` already
runs each one in its own process (``python -m urdflint.engines.probe``) with an
address-space limit and a timeout; while a job confirms, :func:`confined` adds what a
server needs around it:

- the probes are new processes, ended with the job (``warm=False``): a warm probe, kept
  from one model to the next as the command line keeps it, would outlive the job's
  folder and its fence, and serve the next job's upload after this one's;
- the model the engines read is written inside the job's folder (``runner`` makes its
  temporary folder in ``tempfile.tempdir``, which :func:`~.fence.fenced` points there),
  and every ``filename``/``file`` attribute in it that does not name a file of the upload
  is pointed at a missing file of that folder: an engine never opens ``/etc/passwd``, a
  device or a path climbing out of the upload, it reports the mesh as missing (as
  urdflint did); the messages show the reference as written (:attr:`Confinement.shown`);
- the fence lets the job start exactly that probe command, from inside the job's folder,
  and nothing else (:attr:`~.fence._Fence.commands`), in whichever thread;
- the engines' timeout is what is left of the job's time limit, less a margin for the
  rules that follow, so a slow engine is reported (E005) rather than turning the whole
  answer into a 504; when the pool kills an overrunning worker anyway, its process group
  goes with it, engines included (``pool.Worker.kill``).

The engine processes themselves are not under the audit hook (a new interpreter): they
read the Python installation and the model, within the runner's memory limit and timeout.
Engines with a compiled probe (sdformat: ``pkg-config`` and ``g++`` on first use, a binary
in the user's cache) are not run: the fence refuses those commands, so the runner finds
the engine not installed and says so (E007).
"""

from __future__ import annotations

import contextlib
import os
import re
import sys
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from lxml import etree

from .fence import FENCE

PROBE = ("-m", "urdflint.engines.probe")  # what runner.run starts, after sys.executable
FILE_ATTRIBUTES = ("filename", "file")
MISSING = "unresolved"  # the folder (never created) missing references point into
SAFE_NAME = re.compile(r"[^A-Za-z0-9._-]+")


def margin(timeout: float) -> float:
    """Seconds of the job's time limit kept for the rules after the engines."""
    return max(1.0, min(10.0, timeout * 0.2))


@dataclass
class Confinement:
    """One job's confirmation: its folders, its deadline, the references it replaced."""

    root: Path  # the upload's files
    deadline: float  # time.monotonic() by which the engines must be done
    shown: dict[str, str] = field(default_factory=dict)  # replacement path -> as written

    def budget(self, asked: float) -> float:
        """The engines' timeout: ``asked``, or what is left before the deadline (>= 1 s)."""
        return max(1.0, min(asked, self.deadline - time.monotonic()))

    def inside(self, raw: str) -> bool:
        """Whether ``raw`` is an absolute path to a file of the upload."""
        if not os.path.isabs(raw):
            return False
        real = os.path.realpath(raw)
        roots = {str(self.root), os.path.realpath(self.root)}
        return any(real.startswith(r + os.sep) for r in roots) and os.path.isfile(real)

    def confine(self, model: Path) -> None:
        """Point every file reference of the written ``model`` outside the upload at a
        missing file next to it; line numbers are kept (the leading newlines)."""
        text = model.read_text(encoding="utf-8")
        lead = len(text) - len(text.lstrip("\n"))
        parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=True)
        robot = etree.fromstring(text[lead:].encode("utf-8"), parser)
        changed = False
        for index, element in enumerate(robot.iter()):
            for name in FILE_ATTRIBUTES:
                raw = element.get(name) if isinstance(element.tag, str) else None
                if raw is None or self.inside(raw):
                    continue
                base = SAFE_NAME.sub("_", raw.replace("\\", "/").rsplit("/", 1)[-1]) or "file"
                missing = model.parent / MISSING / f"{index}-{base}"
                element.set(name, str(missing))
                self.shown[str(missing)] = raw
                # the runner shows paths in its temporary folder relative to the document
                self.shown[f"{MISSING}/{index}-{base}"] = raw
                changed = True
        if changed:
            body = etree.tostring(robot, encoding="unicode")
            model.write_text("\n" * lead + body, encoding="utf-8")


@contextlib.contextmanager
def confined(root: Path, timeout: float) -> Iterator[Confinement]:
    """While linting with engines: confine what they read and when they must be done.

    Wraps ``runner.write_model`` (the written model is confined) and ``runner.confirm``
    (its timeout shrinks to the job's remaining time), and lets the fence start the probe.
    """
    from urdflint.engines import runner

    job = Confinement(root, time.monotonic() + timeout - margin(timeout))
    write_model, confirm = runner.write_model, runner.confirm

    def confined_model(doc: Any, folder: Path) -> Path:
        path = write_model(doc, folder)
        job.confine(path)
        return path

    def timed_confirm(doc: Any, engines: tuple[str, ...], timeout: float = runner.TIMEOUT) -> Any:
        return confirm(doc, engines, job.budget(timeout), warm=False)

    saved = FENCE.commands
    runner.write_model, runner.confirm = confined_model, timed_confirm
    FENCE.commands = ((sys.executable, *PROBE),)
    try:
        yield job
    finally:
        runner.write_model, runner.confirm = write_model, confirm
        FENCE.commands = saved
