"""Output formats: pure functions ``render(findings, run) -> str``."""

from __future__ import annotations

from collections.abc import Callable, Sequence

from urdflint.model.finding import Finding
from urdflint.outputs.formatters.run import RunInfo, summary_line

__all__ = ["NAMES", "RunInfo", "get", "summary_line"]


def get(name: str) -> Callable[[Sequence[Finding], RunInfo], str]:
    from urdflint.outputs.formatters import github, json, junit, sarif, text

    return {
        "text": text.render,
        "json": json.render,
        "github": github.render,
        "sarif": sarif.render,
        "junit": junit.render,
    }[name]


NAMES = ("text", "json", "github", "sarif", "junit")
