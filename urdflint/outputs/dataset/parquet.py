"""A dataset run as two Parquet tables (``urdflint report --parquet FOLDER``; needs pyarrow).

``files.parquet``: one row per file: ``path``, ``hash``, ``errors``, ``warnings``,
``infos``, ``links``, ``joints``, ``mass``, ``crashed``, ``error`` (why it could not be
read), then one column per target with its predicted outcome (``predicted_gazebo_classic``,
...: ``loads``, ``changes``, ``refused``, ``crashes``, null without a matrix) and one per
``--confirm`` engine with its outcome (``confirmed_mujoco``, ...).

``findings.parquet``: one row per finding: ``path`` (the checked file's, the key into
``files``), ``code``, ``name``, ``severity``, ``line``, ``column``, ``file`` (the file the
finding is in: an included xacro file, a mesh), ``element``, ``message``, ``engine``
(for the E findings of ``--confirm``) and ``fingerprint`` (path, code, element).
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from urdflint.outputs.dataset.diff import fingerprint
from urdflint.outputs.dataset.summary import File, engines, normalize, target_order

FILES, FINDINGS = "files.parquet", "findings.parquet"


def column(prefix: str, name: str) -> str:
    """A column name that SQL takes unquoted: ``predicted_gazebo_classic``."""
    return f"{prefix}_" + re.sub(r"[^0-9A-Za-z_]", "_", name)


def write(items: Iterable[dict[str, Any]], folder: Path) -> list[Path]:
    """Write both tables into ``folder`` (made if missing); the paths written."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    files = [normalize(r) for r in items]
    folder.mkdir(parents=True, exist_ok=True)
    written = []
    for name, table in ((FILES, _files(files, pa)), (FINDINGS, _findings(files, pa))):
        pq.write_table(table, folder / name)
        written.append(folder / name)
    return written


def _files(files: list[File], pa: Any) -> Any:
    targets = target_order({t for f in files for t in f.predicted})
    names = [x["engine"] for x in engines(files)]
    fields = [
        ("path", pa.string(), lambda f: f.path),
        ("hash", pa.string(), lambda f: f.hash),
        ("errors", pa.int64(), lambda f: f.counts.get("error", 0)),
        ("warnings", pa.int64(), lambda f: f.counts.get("warning", 0)),
        ("infos", pa.int64(), lambda f: f.counts.get("info", 0)),
        ("links", pa.int64(), lambda f: f.links),
        ("joints", pa.int64(), lambda f: f.joints),
        ("mass", pa.float64(), lambda f: f.mass),
        ("crashed", pa.bool_(), lambda f: f.crashed),
        ("error", pa.string(), lambda f: f.error),
    ]
    for t in targets:
        fields.append((column("predicted", t), pa.string(), lambda f, t=t: f.predicted.get(t)))
    for engine in names:
        fields.append(
            (
                column("confirmed", engine),
                pa.string(),
                lambda f, engine=engine: f.confirmed.get(engine),
            )
        )
    schema = pa.schema([(name, kind) for name, kind, _ in fields])
    data = {name: [get(f) for f in files] for name, _, get in fields}
    return pa.table(data, schema=schema)


def _int(value: Any) -> int | None:
    return value if isinstance(value, int) and not isinstance(value, bool) else None


def _str(value: Any) -> str | None:
    return None if value is None else str(value)


def _findings(files: list[File], pa: Any) -> Any:
    schema = pa.schema(
        [
            ("path", pa.string()),
            ("code", pa.string()),
            ("name", pa.string()),
            ("severity", pa.string()),
            ("line", pa.int64()),
            ("column", pa.int64()),
            ("file", pa.string()),
            ("element", pa.string()),
            ("message", pa.string()),
            ("engine", pa.string()),
            ("fingerprint", pa.string()),
        ]
    )
    data: dict[str, list[Any]] = {name: [] for name in schema.names}
    for f in files:
        for x in f.findings:
            data["path"].append(f.path)
            data["code"].append(_str(x.get("code")))
            data["name"].append(_str(x.get("name")))
            data["severity"].append(_str(x.get("severity")))
            data["line"].append(_int(x.get("line")))
            data["column"].append(_int(x.get("column")))
            data["file"].append(_str(x.get("path")))
            data["element"].append(_str(x.get("element")))
            data["message"].append(_str(x.get("message")))
            data["engine"].append(_str(x.get("engine")))
            data["fingerprint"].append(fingerprint(x))
    return pa.table(data, schema=schema)
