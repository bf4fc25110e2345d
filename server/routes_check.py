"""``POST /v1/check``: lint one URDF or xacro file (and its meshes zip) in a worker.

The URDF comes as a raw XML body (``application/xml``, ``text/xml``, ``*+xml``) or as the
``urdf`` part of a ``multipart/form-data`` form with an optional ``meshes`` zip; the options
as query parameters or form fields (``options.py``). Each job runs in a per-request
temporary folder that is removed afterwards; so do the engines of ``confirm``, which only
a server started with ``--allow-confirm`` accepts (``confirming.py``). ``POST /v1/fix``
(``routes_fix.py``) reads its request with the same code (:func:`handle`).
"""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path
from typing import Annotated, Any

from fastapi import APIRouter, Query, Request
from fastapi.responses import JSONResponse, Response
from starlette.concurrency import run_in_threadpool
from starlette.datastructures import UploadFile
from starlette.exceptions import HTTPException

from urdflint.model import targets

from . import options as opts
from .jobs import CheckJob
from .pool import Busy, JobTimeout, WorkerDied
from .routing import error, limits_of, pool_of
from .uploads import ZipLimits, urdf_name

XML_TYPES = ("application/xml", "text/xml")
SCENE_HELP = (
    "true: add the robot as a 3D scene at the zero pose (or q): link poses, visual and "
    "collision shapes, meshes (base64, within a triangle budget), centres of mass, "
    "equivalent inertia boxes, joint axes and which findings each link has"
)
STATICS_HELP = (
    "true: add what 'urdflint info --statics --format json' gives under 'statics': each "
    "actuated joint's largest gravity torque and where, its effort limit and margin, the "
    "weakest joint, the payload it allows; for a mobile base, the support polygon, the "
    "centre of mass over it, the stability margin, the tipping angle and the reach"
)
TARGET_HELP = "|".join((*targets.TARGETS, targets.ALL))
FORM_FIELD_BYTES = 128 * 1024
NOT_UTF8 = (
    "the file is not UTF-8 text: /v1/fix answers the fixed file as JSON text, so it fixes "
    "UTF-8 (or ASCII) files only; convert it, or lint it with /v1/check"
)

CHECK_BODY = {
    "required": True,
    "content": {
        "application/xml": {"schema": {"type": "string", "description": "the URDF itself"}},
        "multipart/form-data": {
            "schema": {
                "type": "object",
                "required": ["urdf"],
                "properties": {
                    "urdf": {
                        "type": "string",
                        "format": "binary",
                        "description": "a .urdf or .xacro file (or the XML as text)",
                    },
                    "meshes": {
                        "type": "string",
                        "format": "binary",
                        "description": "optional zip: its folders are the ROS packages",
                    },
                    "select": {"type": "string"},
                    "ignore": {"type": "string"},
                    "fail_on": {"type": "string"},
                    "target": {"type": "string"},
                    "expect_mass": {"type": "string"},
                    "expect_com": {"type": "string"},
                    "payload": {"type": "string", "description": "KG[@LINK], as --payload"},
                    "gravity": {"type": "string", "description": "X,Y,Z m/s², as --gravity"},
                    "xacro_args": {"type": "string"},
                    "config": {"type": "string", "description": "JSON, [tool.urdflint] keys"},
                    "svg": {"type": "boolean"},
                    "scene": {
                        "type": "boolean",
                        "description": "add the robot as a 3D scene (poses, shapes, meshes, "
                        "centres of mass, inertia boxes, joint axes) for the web page",
                    },
                    "statics": {
                        "type": "boolean",
                        "description": "add the gravity torques against the effort limits "
                        "and, for a mobile base, the support polygon and the stability margin",
                    },
                    "matrix": {
                        "type": "boolean",
                        "description": "add what each target does with the model",
                    },
                    "confirm": {
                        "type": "string",
                        "description": "engines to load the model in (mujoco, pybullet, drake, "
                        "pinocchio, all); needs urdflint serve --allow-confirm",
                    },
                },
            }
        },
    },
}

router = APIRouter()


@router.post(
    "/v1/check",
    tags=["check"],
    openapi_extra={"requestBody": CHECK_BODY},
    responses={
        200: {"description": "linting ran: the findings document (even for a broken model)"},
        413: {"description": "the body, the URDF or the zip is over its limit"},
        415: {"description": "not XML or multipart, or not a .urdf/.xacro file"},
        422: {"description": "malformed request, option or archive (see detail)"},
        503: {
            "description": "every worker and queue place is taken, or the worker checking "
            "this request died; retry (Retry-After)"
        },
        504: {"description": "the lint job overran the time limit"},
    },
)
async def check(
    request: Request,
    select: Annotated[
        list[str] | None, Query(description="rules to run (codes, names, families)")
    ] = None,
    ignore: Annotated[list[str] | None, Query(description="rules not to run")] = None,
    fail_on: Annotated[
        str | None, Query(description="error|warning|info|never: sets 'passed'")
    ] = None,
    target: Annotated[list[str] | None, Query(description=TARGET_HELP)] = None,
    expect_mass: Annotated[str | None, Query(description="KG[±TOL], as --expect-mass")] = None,
    expect_com: Annotated[str | None, Query(description="X,Y,Z[±TOL], as --expect-com")] = None,
    xacro_args: Annotated[list[str] | None, Query(description="NAME:=VALUE[,NAME:=VALUE]")] = None,
    q: Annotated[list[str] | None, Query(description="JOINT=VALUE positions for mass/COM")] = None,
    payload: Annotated[str | None, Query(description="KG[@LINK], as --payload (D rules)")] = None,
    gravity: Annotated[str | None, Query(description="X,Y,Z m/s², as --gravity")] = None,
    config: Annotated[str | None, Query(description="JSON object of [tool.urdflint] keys")] = None,
    format: Annotated[str, Query(description="json|sarif|text|github")] = "json",
    svg: Annotated[str | None, Query(description="true: add the kinematic tree as SVG")] = None,
    scene: Annotated[str | None, Query(description=SCENE_HELP)] = None,
    statics: Annotated[str | None, Query(description=STATICS_HELP)] = None,
    matrix: Annotated[
        str | None, Query(description="true: add what each target does with the model")
    ] = None,
    confirm: Annotated[
        list[str] | None,
        Query(description="engines to load the model in (needs serve --allow-confirm)"),
    ] = None,
    filename: Annotated[str | None, Query(description="name shown for a raw XML body")] = None,
) -> Response:
    """Lint one URDF or xacro file (and its meshes) with the CLI's rules and options."""
    return await handle(request)


async def handle(request: Request, fix: bool = False) -> Response:
    """``POST /v1/check``, or ``POST /v1/fix`` with ``fix``: the upload and the options read
    from the request (the endpoints' parameters only document them), then the job."""
    limits = limits_of(request)
    kind = request.headers.get("content-type", "").split(";")[0].strip().lower()
    if kind == "multipart/form-data":
        return await _multipart(request, fix)
    if kind in XML_TYPES or kind.endswith("+xml"):
        body = await request.body()
        if len(body) > limits.max_urdf_bytes:
            return error(413, "the URDF is over the size limit")
        values = opts.merge(request.query_params.multi_items())
        options = opts.parse(values, limits.allow_confirm, fix)
        try:
            name = urdf_name(options.filename)
        except ValueError as exc:
            return error(415, str(exc))
        return await _lint(request, body, name, None, options)
    return error(
        415,
        "send the URDF as application/xml or text/xml, or as multipart/form-data with "
        f"a 'urdf' part (got {kind or 'no content type'!r})",
    )


async def _multipart(request: Request, fix: bool) -> Response:
    """A ``multipart/form-data`` request: the ``urdf`` part, the ``meshes`` zip, the options."""
    limits = limits_of(request)
    try:
        form = await request.form(max_files=2, max_fields=64, max_part_size=FORM_FIELD_BYTES)
    except HTTPException as exc:
        if exc.status_code == 400:
            return error(422, f"malformed multipart body: {exc.detail}")
        raise
    try:
        urdf: Any = None
        meshes: UploadFile | None = None
        fields: list[tuple[str, str]] = []
        for key, value in form.multi_items():
            if key == "urdf":
                if urdf is not None:
                    return error(422, "send one 'urdf' part")
                urdf = value
            elif key == "meshes":
                if not isinstance(value, UploadFile):
                    if value:  # an empty field: a form whose file input was left empty
                        return error(422, "'meshes' must be a file (a zip)")
                elif value.filename or value.size:  # browsers send an empty part for none
                    meshes = value
            elif isinstance(value, UploadFile):
                return error(422, f"unexpected file part {key!r}")
            else:
                fields.append((key, value))
        values = opts.merge(request.query_params.multi_items(), fields)
        options = opts.parse(values, limits.allow_confirm, fix)
        if urdf is None or (isinstance(urdf, UploadFile) and not urdf.filename and not urdf.size):
            return error(422, "the form has no 'urdf' part (a .urdf or .xacro file)")
        if isinstance(urdf, UploadFile):
            if (urdf.size or 0) > limits.max_urdf_bytes:
                return error(413, "the URDF is over the size limit")
            try:
                name = urdf_name(urdf.filename)
            except ValueError as exc:
                return error(415, str(exc))
            data = await urdf.read(limits.max_urdf_bytes + 1)
        else:
            data = str(urdf).encode("utf-8")
            try:
                name = urdf_name(options.filename)
            except ValueError as exc:
                return error(415, str(exc))
        if len(data) > limits.max_urdf_bytes:
            return error(413, "the URDF is over the size limit")
        if meshes is not None and (meshes.size or 0) > limits.max_zip_bytes:
            return error(413, "the meshes zip is over the size limit")
        return await _lint(request, data, name, meshes, options)
    finally:
        await form.close()


async def _lint(
    request: Request, data: bytes, name: str, meshes: UploadFile | None, options: opts.Options
) -> Response:
    """Run one :class:`CheckJob` in a worker, in a temporary folder removed afterwards."""
    limits, pool = limits_of(request), pool_of(request)
    if options.fix and not _utf8(data):
        return error(422, NOT_UTF8)
    zip_limits = ZipLimits(limits.max_zip_members, limits.max_unzipped_bytes, limits.max_zip_ratio)
    folder = await run_in_threadpool(tempfile.mkdtemp, "", "urdflint-", limits.tmpdir)
    try:
        archive = None
        if meshes is not None:
            archive = str(Path(folder) / "meshes.zip")
            size = await run_in_threadpool(_save, meshes, archive, limits.max_zip_bytes)
            if size > limits.max_zip_bytes:
                return error(413, "the meshes zip is over the size limit")
        job = CheckJob(
            folder,
            name,
            data,
            archive,
            options.settings,
            options.fmt,
            options.svg,
            zip_limits,
            matrix=options.matrix,
            timeout=limits.timeout,
            fix=options.fix,
            unsafe_fixes=options.unsafe_fixes,
            scene=options.scene,
            statics=options.statics,
            docs_url=f"{str(request.base_url).rstrip('/')}/rules/{{code}}",
        )
        try:
            answer = await pool.run(job)
        except Busy as exc:
            if pool.problem is not None:  # not busy: the workers cannot start
                return error(503, "no lint worker can start (see /readyz)", {"Retry-After": "5"})
            return error(503, f"the server is busy ({exc})", {"Retry-After": "1"})
        except JobTimeout:
            return error(504, f"checking this input took over the {limits.timeout:g} s time limit")
        except WorkerDied as exc:  # not a verdict on the file: the same request may pass
            return error(503, f"{exc}; retry the request", {"Retry-After": "1"})
    finally:
        await run_in_threadpool(shutil.rmtree, folder, True)
    status, content, media = answer["status"], answer["content"], answer["media_type"]
    if isinstance(content, (dict, list)):
        return JSONResponse(content, status_code=status)
    return Response(content, status_code=status, media_type=media)


def _utf8(data: bytes) -> bool:
    try:
        data.decode("utf-8")
    except UnicodeDecodeError:
        return False
    return True


def _save(upload: UploadFile, target: str, limit: int) -> int:
    """Copy an upload to ``target`` (stops one byte over ``limit``); the bytes written."""
    upload.file.seek(0)
    written = 0
    with open(target, "xb") as out:
        while written <= limit:
            chunk = upload.file.read(1 << 20)
            if not chunk:
                break
            out.write(chunk)
            written += len(chunk)
    return written
