"""U: rules about urdflint itself (produced by the engine, not by a check)."""

from urdflint.rules.meta import (  # noqa: F401
    u001_internal_error,
    u002_unused_suppression,
    u003_invalid_suppression,
    u004_rule_skipped,
    u005_stale_baseline_entry,
)
