"""The JSON envelope shared by the CLI and the HTTP API."""

from __future__ import annotations

import json
from collections.abc import Sequence

from urdflint.model.finding import Finding
from urdflint.outputs.formatters.run import RunInfo


def document(findings: Sequence[Finding], run: RunInfo) -> dict[str, object]:
    data: dict[str, object] = {
        "version": 1,
        "tool": {"name": "urdflint", "version": run.tool_version},
        "findings": [f.to_dict() for f in findings],
        "summary": run.summary(findings),
    }
    if run.models:
        data["models"] = run.models
    if run.matrix:
        data["matrix"] = list(run.matrix)
    return data


def render(findings: Sequence[Finding], run: RunInfo) -> str:
    return json.dumps(document(findings, run), indent=2) + "\n"
