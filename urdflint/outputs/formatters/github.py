"""GitHub Actions workflow commands: one annotation per finding, grouped per file."""

from __future__ import annotations

from collections.abc import Sequence
from itertools import groupby

from urdflint.model.finding import Finding, Severity
from urdflint.outputs.formatters.run import RunInfo, summary_line

LEVEL = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "notice"}


def _data(text: str) -> str:
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def _prop(text: str) -> str:
    return _data(text).replace(":", "%3A").replace(",", "%2C")


def render(findings: Sequence[Finding], run: RunInfo) -> str:
    out: list[str] = []
    for path, group in groupby(findings, key=lambda f: f.path):
        out.append(f"::group::{_data(path)}")
        for f in group:
            props = (
                f"file={_prop(f.path)},line={f.line},endLine={f.line},col={f.column},"
                f"title={_prop(f'urdflint ({f.code})')}"
            )
            text = f"{f.code} {f.name}: {f.message}" + "".join(f"\n{c}" for c in f.trace)
            out.append(f"::{LEVEL[f.severity]} {props}::{_data(text)}")
        out.append("::endgroup::")
    if not run.quiet:
        out.append(summary_line(findings, run))
    return "\n".join(out) + "\n" if out else ""
