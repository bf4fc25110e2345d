"""Output formats: pure functions ``render(findings, run) -> str``."""

from __future__ import annotations

from collections.abc import Callable, Sequence

from urdflint.model.finding import Finding
from urdflint.outputs.formatters.run import RunInfo, summary_line

__all__ = ["NAMES", "RunInfo", "get", "summary_line"]


def get(name: str) -> Callable[[Sequence[Finding], RunInfo], str]:
    import importlib

    if name not in NAMES:
        raise KeyError(name)
    module = importlib.import_module(f"urdflint.outputs.formatters.{name}")  # only the one used
    render: Callable[[Sequence[Finding], RunInfo], str] = module.render
    return render


NAMES = ("text", "json", "github", "sarif", "junit")
