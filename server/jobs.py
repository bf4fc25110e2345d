"""The lint jobs a worker runs, inside the fence (``fence.py``).

:class:`CheckJob` is one ``POST /v1/check``: the upload is written to the request's folder,
the meshes zip extracted next to it, and the model linted with urdflint confined to that
folder (``Context(root=...)``); paths in the findings are made relative to it. With ``fix``
(``POST /v1/fix``) the upload is fixed in rounds first (``fixing.py``) and the answer has
the fixed text and its diff. Linting runs with that folder as the current folder, so the
file names findings and fixes use (the upload's name, an include's path in the zip) name
the upload's files, and the engine's cache of source files is emptied before and after
each lint: a job never sees another job's bytes.
:class:`ReadyJob` is one ``GET /readyz``: a tiny model built with Pinocchio and a tiny mesh
loaded with trimesh. :func:`run` does either and always answers: a status, a content and
a media type, which the app turns into the response.
"""

from __future__ import annotations

import contextlib
import logging
import os
import traceback
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .fence import fenced

if TYPE_CHECKING:
    from urdflint.engine.config import Settings
    from urdflint.engine.context import Context
    from urdflint.engine.linter import Result

    from .uploads import ZipLimits

# the worker's logger: a job's errors are reported as the worker's
log = logging.getLogger("urdflint.server.worker")


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
    matrix: bool = False  # add the compatibility matrix (``matrix`` option)
    timeout: float = 60.0  # the job's time limit: the engines (``confirm``) must fit in it
    fix: bool = False  # POST /v1/fix: fix the upload first, answer the fixed text and diff
    unsafe_fixes: bool = False  # ... with the fixes that change the physics too
    scene: bool = False  # add the robot as a 3D scene (``scene`` option)
    statics: bool = False  # add the gravity loads and the base's stability (``statics``)
    docs_url: str | None = None  # SARIF helpUri: this service's rule pages, /rules/{code}


@dataclass(frozen=True)
class ReadyJob:
    """``GET /readyz``: build a tiny model with Pinocchio, load a tiny mesh."""

    folder: str


def reply(status: int, content: Any, media_type: str = "application/json") -> dict[str, Any]:
    """A job's answer, as the app expects it back from the worker."""
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
    """Lint (or fix) the upload inside the fence: the findings document, or a rendered format;
    an identical request is answered from the analysis cache (``caching.py``)."""
    from .caching import answered

    return answered(job, _check)


def _check(job: CheckJob, cache: Any) -> dict[str, Any]:
    from urdflint.engine.context import Context

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
        context = Context(package_paths=packages, root=root, environ={}, cache=cache)
        return _checked(job, root, target, context)


def _checked(job: CheckJob, root: Path, target: Path, context: Context) -> dict[str, Any]:
    """Fix the written upload (``fix``), lint it (with the engines for ``confirm``); the
    answer in the job's format."""
    from . import fixing

    result = None
    if job.fix:  # the rounds without the engines: only the last lint needs them
        quick = replace(job.settings, confirm=())
        result, original, applied = fixing.rounds(
            lambda: _lint_file(job, root, target, context, quick),
            target,
            job.name,
            job.unsafe_fixes,
        )

    def relint(wider: Settings) -> list[Any]:  # the matrix's rows for the other targets
        return _lint_file(job, root, target, context, wider).findings

    if not job.settings.confirm:
        if result is None:
            result = _lint_file(job, root, target, context, job.settings)
        answer = _answer(job, result, Scrub(root, Path(job.folder)), relint)
    else:
        from .confirming import confined

        with confined(root, job.timeout) as engines:
            result = _lint_file(job, root, target, context, job.settings)
            answer = _answer(job, result, Scrub(root, Path(job.folder), engines.shown), relint)
    if job.fix:
        fixing.answer(answer, job.name, original, applied, target.read_bytes())
    return answer


def _lint_file(
    job: CheckJob, root: Path, target: Path, context: Context, settings: Settings
) -> Result:
    """Lint the written upload from inside its folder (see the module's docstring)."""
    from urdflint.engine import fixes, linter

    fixes.forget_files()
    try:
        with contextlib.chdir(root):
            return linter.lint_path(target, job.name, settings, context)
    finally:
        fixes.forget_files()


def _answer(
    job: CheckJob, result: Result, scrub: Scrub, relint: Callable[[Settings], list[Any]]
) -> dict[str, Any]:
    """The linted upload's answer in the job's format."""
    from urdflint import __version__
    from urdflint.engine import matrix
    from urdflint.model.finding import Finding
    from urdflint.outputs import formatters
    from urdflint.outputs.report import FAIL_LEVEL, model_summary, skipped_note

    from . import extras

    settings = job.settings
    scrubbed: list[Finding] = [scrub.finding(f) for f in result.findings]
    findings = list(scrubbed)
    skipped = dict(result.skipped)
    expects = settings.expect.mass is not None or settings.expect.com is not None
    gate = expects and bool({"P003", "P004"} & set(skipped))
    if skipped and (gate or "U004" in settings.enabled()):
        findings.append(skipped_note(job.name, skipped, expects))
    findings.sort(key=Finding.sort_key)
    rows: list[dict[str, Any]] = []
    doc = result.document
    if job.matrix and doc is not None and doc.root is not None:

        def wider(more: Settings) -> list[Finding]:
            return [scrub.finding(f) for f in relint(more)]

        chosen = result.targets.names if result.targets else settings.targets
        found = matrix.every_target(scrubbed, replace(settings, targets=chosen), wider)
        rows = [scrub.value({"path": job.name, **row}) for row in found]
    models = {job.name: model_summary(result)} if job.fmt == "json" else {}
    chosen_targets = {}
    if result.targets and doc is not None and doc.root is not None:  # as the CLI's
        chosen_targets = {job.name: scrub.value(result.targets.to_dict())}
    run_info = formatters.RunInfo(
        __version__,
        (job.name,),
        models,
        matrix=tuple(rows),
        targets=chosen_targets,
        docs_url=job.docs_url,
    )
    if job.fmt != "json":
        return _rendered(job.fmt, findings, run_info)
    from urdflint.outputs.formatters.json import document

    data = document(findings, run_info)
    threshold = FAIL_LEVEL.get(settings.fail_on)
    failing = threshold is not None and any(f.severity >= threshold for f in findings)
    data["passed"] = not (failing or result.crashed)
    data.update(extras.added(job, doc, findings, scrub))  # svg, scene, statics
    return reply(200, data)


def _rendered(fmt: str, findings: list[Any], run_info: Any) -> dict[str, Any]:
    """The findings in a format other than json (sarif, text, github)."""
    from urdflint.outputs import formatters

    if fmt == "sarif":
        try:
            from urdflint.outputs.formatters import sarif  # type: ignore[attr-defined,unused-ignore]
        except ImportError:
            return reply(422, {"detail": "the sarif format is not available on this server"})
        return reply(200, sarif.render(findings, run_info), "application/sarif+json")
    return reply(200, formatters.get(fmt)(findings, run_info), "text/plain; charset=utf-8")


class Scrub:
    """Answers never show the server's folders: paths inside the upload become relative,
    the rest of the job's folder (the engines' copy of the model) ``.``-relative, and the
    file references ``confirm`` pointed away from the server's disk read as written."""

    def __init__(self, root: Path, folder: Path, shown: Mapping[str, str] | None = None) -> None:
        self.shown = shown if shown is not None else {}
        found = {str(root), os.path.realpath(root)}
        self.prefixes = sorted(found, key=len, reverse=True)
        outer = {str(folder), os.path.realpath(folder)}
        self.prefixes += sorted(outer, key=len, reverse=True)

    def text(self, text: str) -> str:
        for replaced, written in sorted(self.shown.items(), key=lambda kv: -len(kv[0])):
            text = text.replace(replaced, written)
        for prefix in self.prefixes:
            text = text.replace(prefix + os.sep, "").replace(prefix, ".")
        return text

    def finding(self, finding: Any) -> Any:
        fields: dict[str, str | None] = {}
        for name in ("path", "message", "fix"):
            value = getattr(finding, name)
            cleaned = None if value is None else self.text(value)
            if cleaned != value:
                fields[name] = cleaned
        autofix = finding.autofix
        if autofix is not None and autofix.edits:
            edits = tuple(replace(e, path=self.text(e.path)) for e in autofix.edits)
            if edits != autofix.edits:
                return replace(finding, **fields, autofix=replace(autofix, edits=edits))
        return replace(finding, **fields) if fields else finding

    def value(self, value: Any) -> Any:
        """Every string in a JSON-like value (a matrix row), scrubbed."""
        if isinstance(value, str):
            return self.text(value)
        if isinstance(value, dict):
            return {key: self.value(item) for key, item in value.items()}
        if isinstance(value, (list, tuple)):
            return [self.value(item) for item in value]
        return value


# a tetrahedron (ASCII STL) and a one-joint robot that shows it: the readiness model
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
    """Build :data:`TINY` with Pinocchio and load :data:`TETRA`: the optional capabilities."""
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
