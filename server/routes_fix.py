"""``POST /v1/fix``: apply the automatic fixes to one URDF or xacro file, in a worker.

The same request as ``POST /v1/check`` (``routes_check.py``: a raw XML body or a multipart
form with an optional meshes zip, the same options, limits and answers for bad input) plus
``unsafe_fixes``. The worker fixes the upload in rounds, as ``urdflint fix`` does, editing
only the uploaded file itself (``fixing.py``), and answers JSON: the check's document for
the fixed file (its remaining ``findings``, ``summary``, ``passed``...) with ``fixed`` (the
fixed file's text, the input itself when no fix applies), ``diff`` (a unified diff, empty
when nothing changed) and ``applied`` (how many fixes were applied).
"""

from __future__ import annotations

import copy
from typing import Annotated, Any

from fastapi import APIRouter, Query, Request
from fastapi.responses import Response

from .routes_check import CHECK_BODY, SCENE_HELP, STATICS_HELP, TARGET_HELP, handle


def _body() -> dict[str, Any]:
    body: dict[str, Any] = copy.deepcopy(CHECK_BODY)
    properties = body["content"]["multipart/form-data"]["schema"]["properties"]
    properties["unsafe_fixes"] = {
        "type": "boolean",
        "description": "also apply the fixes that change the physics (--unsafe-fixes)",
    }
    return body


FIX_BODY = _body()
FIX_ANSWER = (
    "the fixes ran: the check's JSON document for the fixed file (remaining findings, "
    "summary, passed...) plus 'fixed' (the fixed file's text; the input when no fix "
    "applies), 'diff' (unified diff, '' when nothing changed) and 'applied' (fixes applied)"
)

router = APIRouter()


@router.post(
    "/v1/fix",
    tags=["check"],
    openapi_extra={"requestBody": FIX_BODY},
    responses={
        200: {"description": FIX_ANSWER},
        413: {"description": "the body, the URDF or the zip is over its limit"},
        415: {"description": "not XML or multipart, or not a .urdf/.xacro file"},
        422: {"description": "malformed request, option or archive, or not UTF-8 (see detail)"},
        503: {"description": "every worker and queue place is taken; retry"},
        504: {"description": "the fix job overran the time limit"},
    },
)
async def fix(
    request: Request,
    unsafe_fixes: Annotated[
        str | None, Query(description="true: also the fixes that change the physics")
    ] = None,
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
    svg: Annotated[str | None, Query(description="true: add the kinematic tree as SVG")] = None,
    scene: Annotated[str | None, Query(description=SCENE_HELP)] = None,
    statics: Annotated[str | None, Query(description=STATICS_HELP)] = None,
    matrix: Annotated[
        str | None, Query(description="true: add what each target does with the model")
    ] = None,
    confirm: Annotated[
        list[str] | None,
        Query(description="engines to load the fixed model in (needs serve --allow-confirm)"),
    ] = None,
    filename: Annotated[str | None, Query(description="name shown for a raw XML body")] = None,
) -> Response:
    """Apply the automatic fixes (safe ones; unsafe ones too with ``unsafe_fixes``) to one
    URDF or xacro file, as ``urdflint fix``: the fixed file, its diff and what is left."""
    return await handle(request, fix=True)
