"""The lint jobs a worker runs, inside the fence (``fence.py``).

:class:`CheckJob` is one ``POST /v1/check``: the upload is written to the request's folder,
the meshes zip extracted next to it, and the model linted with urdflint confined to that
folder (``Context(root=...)``); paths in the findings are made relative to it.
:class:`ReadyJob` is one ``GET /readyz``: a tiny model built with Pinocchio and a tiny mesh
loaded with trimesh. :func:`run` does either and always answers: a status, a content and
a media type, which the app turns into the response.
"""

from __future__ import annotations

import contextlib
import logging
import os
import traceback
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .fence import fenced

if TYPE_CHECKING:
    from urdflint.engine.config import Settings

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
    """Lint the upload inside the fence: the findings document, or a rendered format."""
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
    """The findings in a format other than json (sarif, text, github)."""
    from urdflint.outputs import formatters

    if fmt == "sarif":
        try:
            from urdflint.outputs.formatters import sarif  # type: ignore[attr-defined,unused-ignore]
        except ImportError:
            return reply(422, {"detail": "the sarif format is not available on this server"})
        return reply(200, sarif.render(findings, run_info), "application/sarif+json")
    return reply(200, formatters.get(fmt)(findings, run_info), "text/plain; charset=utf-8")


def _svg(doc: Any, findings: list[Any]) -> str | None:
    """The kinematic tree as SVG, or ``None`` when it cannot be drawn."""
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
