"""Run each engine's probe in its own process and read what it built and printed.

The model is written to a temporary folder first: the document's own bytes (for xacro, the
expanded document), with every mesh that resolves rewritten to its absolute path, so that
each engine finds the meshes the run found (package paths, workspace packages, relative
files). Elements keep their line numbers, so an engine's ``line N`` is a line of the
document. Each probe runs with a timeout and a memory limit. The Python engines run
``python -m urdflint.engines.probe``, kept warm from one model to the next
(:mod:`urdflint.engines.warm`: a model a probe dies on is tried once more in a new
process); sdformat runs a compiled probe (:mod:`urdflint.engines.sdformat`, built on
first use) once per model, from the model's folder with ``HOME`` pointing at it (where
sdformat writes its log file).

:func:`confirm` loads one document in several engines (one probe each, in parallel);
:func:`confirm_batch` loads many documents in one engine, in one process
(:mod:`urdflint.engines.batch`: a process that crashes is restarted after the file it
crashed on; sdformat's probe runs once per file), and :func:`remember` hands such outcomes
to the E rules for a document, so that linting it with ``confirm`` runs no engine.
"""

from __future__ import annotations

import copy
import importlib.util
import signal
import sys
import tempfile
from collections.abc import Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field, replace
from pathlib import Path
from weakref import WeakKeyDictionary

from lxml import etree

from urdflint.engine.config import ENGINES
from urdflint.engines import batch, output, sdformat
from urdflint.engines.output import Message
from urdflint.model.document import Document

__all__ = ["ENGINES", "Outcome", "confirm", "confirm_batch", "confirm_many", "died",
           "installed", "remember", "write_model"]  # fmt: skip
MODULES = {"mujoco": "mujoco", "pybullet": "pybullet", "drake": "pydrake", "pinocchio": "pinocchio"}
NATIVE = ("sdformat",)  # a compiled probe (:mod:`urdflint.engines.sdformat`), not Python
TIMEOUT = 60.0  # seconds per engine
MEMORY = 3 << 30  # bytes of address space per engine (POSIX)
NATIVE_WORKERS = 4  # sdformat's probes (one file each) run at a time in confirm_batch


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


_REMEMBERED: WeakKeyDictionary[Document, list[Outcome]] = WeakKeyDictionary()  # remember()


def installed(engine: str) -> bool:
    """Whether ``engine`` can run here (cheap: nothing is imported or compiled)."""
    if engine in NATIVE:
        return sdformat.installed()
    return importlib.util.find_spec(MODULES[engine]) is not None


def command(engine: str) -> batch.Command:
    """The command line that loads the given files in ``engine`` (sdformat: the first)."""
    if engine in NATIVE:
        return lambda paths: sdformat.command(paths[0], MEMORY)
    probe = [sys.executable, "-m", "urdflint.engines.probe", engine, str(MEMORY)]
    return lambda paths: [*probe, *map(str, paths)]


def confirm(
    doc: Document, engines: tuple[str, ...], timeout: float = TIMEOUT, warm: bool = True
) -> list[Outcome]:
    """Load ``doc`` in each of ``engines`` (in parallel, one probe each), but for the
    outcomes :func:`remember`-ed for it; ``warm=False``: in new probe processes, ended
    with the call (the service: no engine process outlives a job)."""
    wanted = [e for e in dict.fromkeys(engines) if e in ENGINES]
    known = {o.engine: o for o in _REMEMBERED.get(doc, ())}
    missing = [e for e in wanted if e not in known]
    if missing:
        with tempfile.TemporaryDirectory(prefix="urdflint-engines-") as folder:
            path = write_model(doc, Path(folder))
            with ThreadPoolExecutor(max_workers=len(missing)) as pool:
                found = pool.map(lambda e: run(doc, e, path, timeout, warm), missing)
                known.update(zip(missing, found, strict=True))
    return [known[e] for e in wanted]


def died(answer: Outcome | batch.Loaded) -> bool:
    """Whether the engine's process died or hung on the model."""
    if isinstance(answer, Outcome):
        return False
    return answer.hung or answer.status is not None or answer.report is None


def confirm_batch(docs: Sequence[Document], engine: str, timeout: float = TIMEOUT) -> list[Outcome]:
    """Load each of ``docs`` in ``engine``: one process for them all (a new one after a
    crash; sdformat: one per document), each model in its own folder; ``timeout`` is per
    document. The outcomes are those :func:`run` gives, in order."""
    unusable = _unusable(engine)
    if unusable is not None:
        return [replace(unusable) for _ in docs]
    with tempfile.TemporaryDirectory(prefix="urdflint-engines-") as folder:
        paths = []
        for index, doc in enumerate(docs):
            (Path(folder) / str(index)).mkdir()
            paths.append(write_model(doc, Path(folder) / str(index)))
        found = _load(engine, paths, timeout, Path(folder))
        pairs = zip(docs, found, strict=True)
        return [outcome(doc, engine, loaded, timeout) for doc, loaded in pairs]


def confirm_many(
    docs: Sequence[Document], engines: Sequence[str], timeout: float = TIMEOUT
) -> list[list[Outcome]]:
    """Each document's outcomes in ``engines`` (in that order): one :func:`confirm_batch`
    per engine, the engines in parallel; each document's are :func:`remember`-ed."""
    wanted = [e for e in dict.fromkeys(engines) if e in ENGINES]
    with ThreadPoolExecutor(max_workers=max(len(wanted), 1)) as pool:
        per_engine = list(pool.map(lambda e: confirm_batch(docs, e, timeout), wanted))
    found = [[outcomes[i] for outcomes in per_engine] for i in range(len(docs))]
    for doc, outcomes in zip(docs, found, strict=True):
        remember(doc, outcomes)
    return found


def remember(doc: Document, outcomes: Sequence[Outcome]) -> None:
    """Make ``outcomes`` what :func:`confirm` gives for ``doc`` in their engines, without
    starting them: linting the document with ``confirm`` settings (before it is linted
    with them otherwise) has the E rules report these."""
    _REMEMBERED[doc] = list(outcomes)


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


def run(doc: Document, engine: str, path: Path, timeout: float, warm: bool = True) -> Outcome:
    """Load the model written at ``path`` in ``engine`` (its own process, from its folder)."""
    unusable = _unusable(engine)
    if unusable is not None:
        return unusable
    return outcome(doc, engine, _load_one(engine, path, timeout, warm), timeout)


def _unusable(engine: str) -> Outcome | None:
    """The outcome of an engine that cannot run here (``None``: it can)."""
    if not installed(engine):
        return Outcome(engine, installed=False)
    if engine in NATIVE:
        try:
            sdformat.binary()  # compiled on first use
        except sdformat.Unavailable as exc:
            return Outcome(engine, installed=False, reason=str(exc))
    return None


def _load(engine: str, paths: list[Path], timeout: float, folder: Path) -> list[batch.Loaded]:
    """Run the probe over ``paths`` (sdformat: once per path, ``HOME`` its folder, a few
    at a time)."""
    if engine not in NATIVE:
        return batch.load(command(engine), paths, timeout, folder)

    def one(path: Path) -> batch.Loaded:
        env = sdformat.environment(path.parent)
        return batch.load(command(engine), [path], timeout, path.parent, env)[0]

    if len(paths) == 1:
        return [one(paths[0])]
    with ThreadPoolExecutor(max_workers=NATIVE_WORKERS) as pool:
        return list(pool.map(one, paths))


def _load_one(engine: str, path: Path, timeout: float, warm: bool = True) -> batch.Loaded:
    """Load one model: for the Python engines in a warm probe (:mod:`urdflint.engines.warm`;
    ``warm=False``: a new process), tried once more in a new process when the probe died
    on it (a crash that does not come back was not the model's); sdformat's probe, once."""
    if engine in NATIVE:
        return _load(engine, [path], timeout, path.parent)[0]
    loaded = _probe(engine, path, timeout, warm)
    if died(loaded) and not loaded.hung and loaded.failed is None:
        loaded = _probe(engine, path, timeout, warm)  # once more, in a new process
    return loaded


def _probe(engine: str, path: Path, timeout: float, kept: bool) -> batch.Loaded:
    from urdflint.engines import warm

    if not kept:
        return _load(engine, [path], timeout, path.parent)[0]
    with warm.borrowed(engine, MEMORY) as probe:
        return probe.load(path, timeout)


def outcome(doc: Document, engine: str, loaded: batch.Loaded, timeout: float) -> Outcome:
    """What the probe's answer on one file says ``engine`` did with ``doc``."""
    if loaded.failed is not None:
        return Outcome(engine, crash=f"could not be started ({loaded.failed})")
    if loaded.hung:
        return Outcome(engine, crash=f"did not finish loading the model within {timeout:g} s")
    lines = output.clean(loaded.printed, str(loaded.path), doc.path)
    warnings, errors = output.classify(doc, engine, lines)
    report = loaded.report
    if loaded.status is not None or report is None:
        return Outcome(engine, crash=_death(loaded.status or 0, errors), warnings=warnings)
    found = Outcome(engine, built=bool(report["ok"]), warnings=warnings,
                    bodies=tuple(report["bodies"]), joints=tuple(report["joints"]))  # fmt: skip
    found.limits = {k: (v[0], v[1], v[2]) for k, v in report.get("limits", {}).items()}
    found.inertias = {k: (v[0], tuple(v[1])) for k, v in report.get("inertias", {}).items()}
    if not found.built:
        raised = output.clean(str(report["error"]), str(loaded.path), doc.path)
        found.refusal = output.refusal(doc, errors, raised)
    return found


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
