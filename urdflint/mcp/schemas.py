"""The tools as MCP lists them: name, description, JSON Schema of the arguments and of the
structured content, and hints (read-only or not)."""

from __future__ import annotations

from typing import Any

INSTRUCTIONS = (
    "urdflint lints robot descriptions (URDF and xacro): every problem with its file, line, "
    "rule code, fix, machine-applicable edits and what each simulator does with the model. "
    "After each edit of a .urdf or .xacro file, call check; apply the automatic fixes with "
    "fix (write=false shows the edits and the diff, write=true writes them inside the roots), "
    "look a rule up with explain, check again until no error is left. Paths are relative to "
    "the first root; nothing outside the client's roots is read or written."
)

_STRINGS = {"type": "array", "items": {"type": "string"}}
MODEL = {
    "paths": {
        **_STRINGS,
        "description": "URDF or xacro files, or folders (every *.urdf and entry *.xacro "
        "below), inside the roots; relative paths are relative to the first root",
    },
    "text": {
        "type": "string",
        "description": "the file's text, instead of paths (unsaved content); needs name",
    },
    "name": {
        "type": "string",
        "description": "with text: the file's path (its extension says URDF or xacro; "
        "meshes and includes resolve from its folder, inside the roots)",
    },
    "targets": {
        **_STRINGS,
        "description": "consumers the model is meant for: gz-sim, gazebo-classic, ros, mujoco, "
        "pybullet, drake, isaac, pinocchio or all (default: inferred from the model and its "
        "package)",
    },
    "select": {**_STRINGS, "description": "run only these rules: codes, names or families"},
    "ignore": {**_STRINGS, "description": "do not run these rules"},
    "xacro_args": {
        "type": "object",
        "additionalProperties": {"type": ["string", "number", "boolean"]},
        "description": "xacro arguments, NAME: VALUE",
    },
    "package_paths": {
        "type": "object",
        "additionalProperties": {"type": "string"},
        "description": "where package NAME is (package:// and $(find NAME)), inside the roots",
    },
}
ENVELOPE = {
    "type": "object",
    "properties": {
        "version": {"type": "integer"},
        "findings": {"type": "array", "items": {"type": "object"}},
        "summary": {"type": "object"},
    },
    "required": ["findings"],
}


def _tool(
    name: str, title: str, description: str, properties: dict[str, Any], **more: Any
) -> dict[str, Any]:
    """A tool as ``tools/list`` gives it (``mcp.types.Tool``'s fields)."""
    hints = {"title": title, "readOnlyHint": more.get("read_only", True), "openWorldHint": False}
    return {
        "name": name,
        "title": title,
        "description": description,
        "input_schema": {"type": "object", "properties": properties, **more.get("input", {})},
        "output_schema": more.get("output"),
        "annotations": hints,
    }


TOOLS = [
    _tool(
        "check",
        "Lint a robot description",
        "Lint URDF or xacro files (or a text): the findings exactly as `urdflint check "
        "--format json` gives them (path, line, code, message, fix, autofix edits, effects "
        "per simulator) and a short text summary.",
        MODEL,
        output=ENVELOPE,
    ),
    _tool(
        "fix",
        "Fix a robot description",
        "The automatic fixes of the findings: with write=false (default) their edits and a "
        "unified diff, nothing written; with write=true the files are fixed (inside the "
        "roots only, rounds until nothing changes) and what remains is returned. unsafe=true "
        "also applies fixes that change the physics (inertias, limits).",
        {
            **MODEL,
            "write": {"type": "boolean", "default": False, "description": "write the files"},
            "unsafe": {"type": "boolean", "default": False, "description": "unsafe fixes too"},
        },
        output={"type": "object", "properties": {"diff": {"type": "string"}}},
        read_only=False,
    ),
    _tool(
        "explain",
        "Explain a rule",
        "A rule's page: what it checks, why it matters, how to fix it, a bad and a good "
        "example (long=true: every section in full and what each simulator does).",
        {
            "rule": {"type": "string", "description": "a rule code or name, e.g. J009"},
            "long": {"type": "boolean", "default": False, "description": "the full page"},
        },
        input={"required": ["rule"]},
    ),
    _tool(
        "info",
        "Describe a robot model",
        "The model as `urdflint info --format json` gives it: kinematic tree, per-link "
        "masses, total mass, centre of mass, DOF; statics=true adds each joint's gravity "
        "torque against its effort limit.",
        {
            "path": {"type": "string", "description": "a URDF or xacro file inside the roots"},
            **{key: MODEL[key] for key in ("text", "name", "xacro_args", "package_paths")},
            "q": {
                "type": "object",
                "additionalProperties": {"type": "number"},
                "description": "joint positions for the mass and COM computation, JOINT: VALUE",
            },
            "statics": {"type": "boolean", "default": False, "description": "gravity loads"},
        },
        output={"type": "object"},
    ),
    _tool(
        "matrix",
        "What each simulator does with a model",
        "One row per target (Gazebo, ROS, MuJoCo, PyBullet, Drake, Isaac...): whether it "
        "loads the model, loads it with changes, refuses it or crashes, and the findings "
        "that decide it (`urdflint check --matrix`).",
        MODEL,
        output={"type": "object", "properties": {"matrix": {"type": "array"}}},
    ),
]
