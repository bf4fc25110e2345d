"""What the command line and the service add to a run's findings and JSON."""

from __future__ import annotations

from typing import Any

from urdflint.engine import registry
from urdflint.model.finding import Finding, Severity

FAIL_LEVEL = {"error": Severity.ERROR, "warning": Severity.WARNING, "info": Severity.INFO}


def model_summary(result: Any) -> Any:
    """The per-file ``model`` object of the JSON output (``None`` unless Pinocchio built it)."""
    doc = result.document
    if doc is None or "physics" not in doc.__dict__:
        return None  # never import Pinocchio just for the summary
    from urdflint.outputs.info import summary

    return summary(doc)


def skipped_note(path: str, skipped: dict[str, tuple[str, ...]], expects: bool) -> Finding:
    """One note for the run; an error when mass/COM expectations could not be checked."""
    from urdflint.model.optional import EXTRAS, install_command

    rule = registry.RULES["U004"]
    gate = expects and bool({"P003", "P004"} & set(skipped))
    modules = sorted({m for missing in skipped.values() for m in missing})
    extras = sorted({EXTRAS.get(m, m) for m in modules})
    message = (
        f"{len(skipped)} rule(s) skipped ({', '.join(sorted(skipped))}): "
        f"{', '.join(modules)} not installed; install the extra {','.join(extras)}"
    )
    if gate:
        message += "; the mass and COM expectations were NOT checked"
    return Finding(
        path,
        1,
        1,
        rule.code,
        rule.name,
        Severity.ERROR if gate else rule.severity,
        message,
        "/robot",
        install_command(",".join(extras)),
    )
