"""The options of ``POST /v1/check`` and ``/v1/fix``, from the query string and form fields, as
CLI settings.

Every option may come as a query parameter or (multipart requests) as a form field; list
options (``select``, ``ignore``, ``target``, ``xacro_args``, ``q``) take repeated values,
comma-separated lists, or both, and query and form values add up; for the other options a
form field wins over the query. They mean what the CLI flags of the same name mean, and
are applied by the CLI's own :class:`~urdflint.engine.options.SettingsFinder`, so the service and
``urdflint check --isolated`` agree exactly:

``select``, ``ignore``    rule codes, names or family letters
``fail_on``              error | warning | info | never  (decides ``passed``)
``target``               gazebo-classic | gz-sim | mujoco | drake | pybullet | isaac |
                         pinocchio | ros | all (every one); default gazebo-classic, or
                         every target with ``matrix``
``expect_mass``          ``KG[±TOL]``, e.g. ``12.3`` or ``12.3±2%``
``expect_com``           ``X,Y,Z[±TOL]``
``xacro_args``           ``NAME:=VALUE`` pairs, e.g. ``a:=1,b:=2`` (a comma inside a value is
                         kept when what follows has no ``:=``)
``q``                    ``JOINT=VALUE`` joint positions for the mass and COM
``payload``              ``KG[@LINK]``, as ``--payload``: a point mass for the statics (D001,
                         D002), e.g. ``2@tool0`` (no link: the end of the longest chain)
``gravity``              ``X,Y,Z`` m/s² in the root link's frame, as ``--gravity`` (default
                         ``0,0,-9.81``)
``config``               JSON object with ``[tool.urdflint]`` keys (``select``, ``severity``,
                         ``rules``, ``expect``, ``per-file-ignores``...). ``package-paths`` is
                         refused: packages come from the meshes zip, never from the
                         server's disk
``format``               json (default) | sarif | text | github
``svg``                  true to add ``"svg": {file: "<svg ...>"}`` (the kinematic tree)
``scene``                true to add ``"scene": {file: {...}}``: the robot in 3D at the zero
                         pose (or ``q``) for the web page's view: each link's world pose,
                         visual and collision shapes (meshes from the zip as base64
                         float32 vertices and uint16/uint32 triangles, simplified past a
                         total triangle budget), centre of mass, equivalent inertia box,
                         the joints' axes and the indices of each one's findings
                         (``urdflint.outputs.scene``)
``statics``              true to add ``"statics": {file: {...}}``: what ``urdflint info
                         --statics --format json`` gives under ``statics`` (each actuated
                         joint's largest gravity load and where, its effort and margin, the
                         weakest joint, the payload it allows; for a mobile base the support
                         polygon, the centre of mass over it, the stability margin, the
                         tipping angle and the reach), from the same Pinocchio model
``matrix``               true to add ``"matrix"``: one row per target saying whether it loads
                         the model, loads it with changes, refuses it or crashes, and the
                         findings that decide it (as ``urdflint check --matrix``; without a
                         ``target`` option every target is selected)
``confirm``              engines to load the model in, as ``--confirm``: ``mujoco``,
                         ``pybullet``, ``drake``, ``pinocchio`` or ``all``, comma-separated
                         (E rules; with ``matrix``, each row's ``confirmed``; an engine with
                         a compiled probe, sdformat, is never run here and says it is not
                         installed; ``/v1/capabilities`` lists what runs). Refused (422)
                         unless the server was started with ``urdflint serve
                         --allow-confirm``: engines are heavy native code loading untrusted
                         input. Each runs in its own process, with the worker's memory limit
                         and a timeout, on a copy of the model whose file references point
                         only into the upload; their time counts against the job's
                         ``URDFLINT_TIMEOUT``. The ``confirm`` key of ``config`` is the same
``filename``             the name to show for a raw XML body (default ``robot.urdf``; a
                         ``.xacro`` name makes it a xacro file)
``unsafe_fixes``         ``POST /v1/fix`` only: true to also apply the fixes that change the
                         model's physics, as ``--unsafe-fixes`` (refused by ``/v1/check``,
                         which changes nothing; ``/v1/fix`` answers JSON only)

Unknown form fields are refused (422), so a misspelt option never goes unnoticed.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from urdflint.engine import config, statics_settings
from urdflint.engine import options as values_of
from urdflint.engine.config import Settings
from urdflint.model import targets

LISTS = ("select", "ignore", "target", "xacro_args", "q", "confirm")
SCALARS = (
    "fail_on", "expect_mass", "expect_com", "config", "format", "svg", "matrix", "filename",
    "unsafe_fixes", "scene", "payload", "gravity", "statics",
)  # fmt: skip
ALIASES = {"targets": "target", "xacro_arg": "xacro_args", "fail": "fail_on"}
FORMATS = ("json", "sarif", "text", "github")
TRUE = ("1", "true", "yes", "on")
FALSE = ("0", "false", "no", "off", "")
MAX_CONFIG_CHARS = 64 * 1024
NO_CONFIRM = (
    "confirm: this server does not load models in simulation engines (they are heavy native "
    "code loading untrusted input); it must be started with 'urdflint serve --allow-confirm'"
)


class OptionError(ValueError):
    """A malformed option; the message names it (answered with 422)."""


@dataclass(frozen=True)
class Options:
    settings: Settings
    fmt: str = "json"
    svg: bool = False
    filename: str | None = None
    matrix: bool = False
    fix: bool = False  # POST /v1/fix: apply the automatic fixes to the upload
    unsafe_fixes: bool = False  # ... the ones that change the physics too
    scene: bool = False  # add the 3D scene (``scene`` option)
    statics: bool = False  # add the gravity loads and the base's stability (``statics``)


def canonical(name: str) -> str | None:
    key = name.strip().lower().replace("-", "_")
    key = ALIASES.get(key, key)
    return key if key in LISTS or key in SCALARS else None


def merge(
    query: Iterable[tuple[str, str]], form: Iterable[tuple[str, str]] = ()
) -> dict[str, list[str]]:
    """``{option: [values]}`` from the query (unknown names ignored) and the form (refused)."""
    values: dict[str, list[str]] = {}
    for name, value in query:
        key = canonical(name)
        if key is not None:
            values.setdefault(key, []).append(value)
    from_form: dict[str, list[str]] = {}
    for name, value in form:
        key = canonical(name)
        if key is None:
            raise OptionError(f"unknown form field {name!r}")
        from_form.setdefault(key, []).append(value)
    for key, found in from_form.items():
        values[key] = values.get(key, []) + found if key in LISTS else found
    return values


def _split(values: Iterable[str]) -> list[str]:
    return [part.strip() for value in values for part in value.split(",") if part.strip()]


def _xacro_pairs(values: Iterable[str]) -> list[tuple[str, str]]:
    pairs: list[tuple[str, str]] = []
    for value in values:
        for piece in value.split(","):
            if ":=" in piece or not pairs:
                name, found, arg = piece.partition(":=")
                if not found or not name.strip():
                    raise OptionError(f"xacro_args: expected NAME:=VALUE, got {piece!r}")
                pairs.append((name.strip(), arg.strip()))
            else:  # a comma inside the previous value
                name, arg = pairs[-1]
                pairs[-1] = (name, f"{arg},{piece.strip()}")
    return pairs


def _last(values: Mapping[str, list[str]], key: str) -> str | None:
    found = values.get(key)
    return found[-1].strip() if found else None


def _typed(key: str, text: str | None, parse: Any) -> Any:
    if text is None:
        return None
    try:
        return parse(text)
    except argparse.ArgumentTypeError as exc:
        raise OptionError(f"{key}: {exc}") from None


def _base(text: str | None) -> Settings:
    if text is None or not text.strip():
        return Settings()
    if len(text) > MAX_CONFIG_CHARS:
        raise OptionError(f"config: over {MAX_CONFIG_CHARS} characters")
    try:
        data = json.loads(text)
    except (ValueError, RecursionError) as exc:
        raise OptionError(f"config: not valid JSON ({exc})") from None
    if isinstance(data, dict) and isinstance(data.get("tool"), dict):
        data = data["tool"].get("urdflint", {})  # a whole pyproject-like object
    if isinstance(data, dict) and "package-paths" in data:
        raise OptionError(
            "config: 'package-paths' is not accepted by the service; upload the packages in "
            "the meshes zip (its top-level folders and package.xml files are the packages)"
        )
    for key in ("cache-dir", "cache-max-size"):
        if isinstance(data, dict) and key in data:
            raise OptionError(
                f"config: '{key}' is not accepted by the service: its cache is the server's"
            )
    rules = data.get("rules") if isinstance(data, dict) else None
    c001 = rules.get("C001") if isinstance(rules, dict) else None
    if isinstance(c001, dict) and "write_meshes" in c001:
        raise OptionError(
            "config: 'rules.C001.write_meshes' is not accepted by the service: it "
            "writes files beside the meshes; run urdflint fix --write-meshes locally"
        )
    try:
        return config.from_mapping(data)
    except config.ConfigError as exc:
        raise OptionError(f"config: {exc}") from None


def _flag(values: Mapping[str, list[str]], key: str) -> bool:
    text = (_last(values, key) or "").lower()
    if text not in TRUE + FALSE:
        raise OptionError(f"{key}: expected true or false, not {text!r}")
    return text in TRUE


def _engines(values: Mapping[str, list[str]]) -> list[tuple[str, ...]]:
    """``confirm``: the engines, as ``--confirm`` groups (``[]`` when none are named)."""
    names = _split(values.get("confirm", ()))
    if not names:
        return []
    try:
        return [values_of.engine_list(",".join(names))]
    except argparse.ArgumentTypeError as exc:
        raise OptionError(f"confirm: {exc}") from None


def parse(
    values: Mapping[str, list[str]], allow_confirm: bool = False, fix: bool = False
) -> Options:
    """Validate the options and build the settings exactly as ``urdflint check`` would.

    ``allow_confirm``: whether the server runs engines (``urdflint serve --allow-confirm``);
    without it, engines named by ``confirm`` or the config's ``confirm`` key are a 422.
    ``fix``: the options of ``POST /v1/fix`` (``unsafe_fixes``; JSON answers only).
    """
    fmt = (_last(values, "format") or "json").lower()
    if fmt not in FORMATS:
        raise OptionError(f"format: must be one of {', '.join(FORMATS)}, not {fmt!r}")
    if fix and fmt != "json":
        raise OptionError(f"format: POST /v1/fix answers JSON only, not {fmt!r}")
    unsafe = _flag(values, "unsafe_fixes")
    if unsafe and not fix:
        raise OptionError("unsafe_fixes: /v1/check changes nothing; POST /v1/fix applies fixes")
    if fmt == "sarif" and importlib.util.find_spec("urdflint.outputs.formatters.sarif") is None:
        raise OptionError("format: sarif is not available on this server")
    svg, matrix = _flag(values, "svg"), _flag(values, "matrix")
    fail_on = _last(values, "fail_on")
    if fail_on is not None and fail_on not in config.FAIL_ON:
        raise OptionError(f"fail_on: must be one of {', '.join(config.FAIL_ON)}, not {fail_on!r}")
    target = _split(values.get("target", ()))
    try:
        targets.validate(target)
    except ValueError as exc:
        raise OptionError(f"target: {exc}") from None
    q = [_typed("q", part, values_of.joint_value) for part in _split(values.get("q", ()))]
    args = argparse.Namespace(
        command="check",
        select=[_split(values["select"])] if "select" in values else [],
        ignore=[_split(values["ignore"])] if "ignore" in values else [],
        exit_zero=False,
        fail_on=fail_on,
        target=[tuple(target)] if target else [],  # as --target gives them
        xacro_arg=_xacro_pairs(values.get("xacro_args", ())),
        expect_mass=_typed("expect_mass", _last(values, "expect_mass"), values_of.expect_mass),
        expect_com=_typed("expect_com", _last(values, "expect_com"), values_of.expect_com),
        q=q,
        payload=_typed("payload", _last(values, "payload"), statics_settings.payload_option),
        gravity=_typed("gravity", _last(values, "gravity"), statics_settings.gravity_option),
        confirm=_engines(values),
        isolated=True,
        config=None,
    )
    base = _base(_last(values, "config"))
    try:
        finder = values_of.SettingsFinder(args)
    except values_of.UsageError as exc:
        raise OptionError(str(exc).replace("--", "", 1)) from None
    settings = finder._apply(base)
    if settings.confirm and not allow_confirm:
        raise OptionError(NO_CONFIRM)
    scene, statics = _flag(values, "scene"), _flag(values, "statics")
    name = _last(values, "filename")
    return Options(settings, fmt, svg, name, matrix, fix, unsafe, scene, statics)
