"""Run each engine's probe in its own process and read what it built and printed.

The model is written to a temporary folder first: the document's own bytes (for xacro, the
expanded document), with every mesh that resolves rewritten to its absolute path, so that
each engine finds the meshes the run found (package paths, workspace packages, relative
files). Elements keep their line numbers, so an engine's ``line N`` is a line of the
document. Each probe runs with a timeout and a memory limit, from the temporary folder
(MuJoCo writes its ``MUJOCO_LOG.TXT`` in the working folder). The Python engines run
``python -m urdflint.engines.probe``; sdformat runs a compiled probe
(:mod:`urdflint.engines.sdformat`, built on first use), with ``HOME`` pointing at the
temporary folder (where sdformat writes its log file).
"""

from __future__ import annotations

import copy
import importlib.util
import json
import signal
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from lxml import etree

from urdflint.engine.config import ENGINES
from urdflint.engines import output, sdformat
from urdflint.engines.output import Message
from urdflint.model.document import Document

__all__ = ["ENGINES", "Outcome", "confirm", "installed", "write_model"]
MODULES = {"mujoco": "mujoco", "pybullet": "pybullet", "drake": "pydrake", "pinocchio": "pinocchio"}
NATIVE = ("sdformat",)  # a compiled probe (:mod:`urdflint.engines.sdformat`), not Python
TIMEOUT = 60.0  # seconds per engine
MEMORY = 3 << 30  # bytes of address space per engine (POSIX)


@dataclass
class Outcome:
    """What one engine did with the model.

    ``installed`` is false when the engine's module is not importable, or its probe could
    not be built (nothing ran; ``reason`` says why when there is more to say);
    ``crash`` says how the process died (a signal, the timeout, no report); ``refusal``
    is the engine's reason when it raised or refused to load; ``bodies`` and ``joints``
    are the names in the model it built; ``limits`` maps each revolute or prismatic joint to
    its ``(type, lower, upper)`` as built (``None``: unlimited) and ``inertias`` each body to
    its ``(mass, principal moments)`` as built.
    """

    engine: str
    installed: bool = True
    reason: str | None = None
    built: bool = False
    crash: str | None = None
    refusal: Message | None = None
    warnings: list[Message] = field(default_factory=list)
    bodies: tuple[str, ...] = ()
    joints: tuple[str, ...] = ()
    limits: dict[str, tuple[str, float | None, float | None]] = field(default_factory=dict)
    inertias: dict[str, tuple[float, tuple[float, ...]]] = field(default_factory=dict)


def installed(engine: str) -> bool:
    """Whether ``engine`` can run here (cheap: nothing is imported or compiled)."""
    if engine in NATIVE:
        return sdformat.installed()
    return importlib.util.find_spec(MODULES[engine]) is not None


def probe(engine: str, path: Path) -> tuple[list[str], dict[str, str] | None]:
    """The command line and environment (``None``: this one) that load ``path`` in ``engine``.

    Raises :class:`~urdflint.engines.sdformat.Unavailable` when sdformat's probe cannot be
    compiled."""
    if engine in NATIVE:
        return sdformat.command(path, MEMORY), sdformat.environment(path.parent)
    return [sys.executable, "-m", "urdflint.engines.probe", engine, str(path), str(MEMORY)], None


def confirm(doc: Document, engines: tuple[str, ...], timeout: float = TIMEOUT) -> list[Outcome]:
    """Load ``doc`` in each of ``engines`` (in parallel, one process each)."""
    wanted = [e for e in dict.fromkeys(engines) if e in ENGINES]
    with tempfile.TemporaryDirectory(prefix="urdflint-engines-") as folder:
        path = write_model(doc, Path(folder))
        with ThreadPoolExecutor(max_workers=max(len(wanted), 1)) as pool:
            return list(pool.map(lambda e: run(doc, e, path, timeout), wanted))


def write_model(doc: Document, folder: Path) -> Path:
    """The model as the engines read it: meshes absolute, lines unchanged."""
    from urdflint.sources.meshes import references, resolved

    robot = copy.deepcopy(doc.robot)
    twins = dict(zip(doc.robot.iter(), robot.iter(), strict=True))
    for ref in references(doc):
        found = resolved(doc, ref.uri)
        if found.found and found.path is not None:
            twins[ref.element].set("filename", str(found.path.resolve()))
    _mujoco_keeps_paths(robot)
    line = doc.start_of(doc.robot)[0]
    text = "\n" * (line - 1) + etree.tostring(robot, encoding="unicode")
    name = Path(doc.path).name.removesuffix(".xacro")
    path = folder / (name if name.endswith(".urdf") else f"{name or 'robot'}.urdf")
    path.write_text(text, encoding="utf-8")
    return path


def _mujoco_keeps_paths(robot: etree._Element) -> None:
    """MuJoCo's URDF import keeps only a mesh's file name unless ``strippath="false"``."""
    extension = robot.find("mujoco")
    if extension is None:
        extension = etree.SubElement(robot, "mujoco")
    compiler = extension.find("compiler")
    if compiler is None:
        compiler = etree.SubElement(extension, "compiler")
    compiler.set("strippath", "false")


def run(doc: Document, engine: str, path: Path, timeout: float) -> Outcome:
    if not installed(engine):
        return Outcome(engine, installed=False)
    try:
        command, env = probe(engine, path)
    except sdformat.Unavailable as exc:
        return Outcome(engine, installed=False, reason=str(exc))
    try:
        proc = subprocess.run(
            command, capture_output=True, timeout=timeout, cwd=path.parent, env=env
        )
    except subprocess.TimeoutExpired:
        return Outcome(engine, crash=f"did not finish loading the model within {timeout:g} s")
    except OSError as exc:  # the probe could not be started (missing, not allowed)
        return Outcome(engine, crash=f"could not be started ({exc.strerror or exc})")
    printed = proc.stderr.decode("utf-8", "replace")
    log = path.parent / "MUJOCO_LOG.TXT"
    if engine == "mujoco" and log.is_file():
        printed += "\n" + log.read_text(encoding="utf-8", errors="replace")
        log.unlink()
    lines = output.clean(printed, str(path), doc.path)
    warnings, errors = output.classify(doc, engine, lines)
    report = _report(proc.stdout.decode("utf-8", "replace"))
    if proc.returncode != 0 or report is None:
        return Outcome(engine, crash=_death(proc.returncode, errors), warnings=warnings)
    outcome = Outcome(engine, built=bool(report["ok"]), warnings=warnings,
                      bodies=tuple(report["bodies"]), joints=tuple(report["joints"]))  # fmt: skip
    outcome.limits = {k: (v[0], v[1], v[2]) for k, v in report.get("limits", {}).items()}
    outcome.inertias = {k: (v[0], tuple(v[1])) for k, v in report.get("inertias", {}).items()}
    if not outcome.built:
        raised = output.clean(str(report["error"]), str(path), doc.path)
        outcome.refusal = output.refusal(doc, errors, raised)
    return outcome


def _report(stdout: str) -> dict[str, Any] | None:
    for line in reversed(stdout.splitlines()):
        try:
            found = json.loads(line)
        except ValueError:
            continue
        if isinstance(found, dict) and "ok" in found:
            return found
    return None


def _death(code: int, errors: list[Message]) -> str:
    if code < 0:
        try:
            name = signal.Signals(-code).name
        except ValueError:
            name = f"signal {-code}"
        why = f"was killed by {name}"
    else:
        why = f"exited with status {code} without building the model"
    if errors:
        why += f" after printing {errors[0].text!r}"
    return why
