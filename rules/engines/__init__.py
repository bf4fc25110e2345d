"""E: confirmation against the real simulation engines (``urdflint check --confirm``)."""

from urdflint.rules.engines import (  # noqa: F401
    e001_engine_refused,
    e002_engine_dropped_link,
    e003_engine_unlimited_joint,
    e004_engine_replaced_inertia,
    e005_engine_crashed,
    e006_engine_warning,
    e007_engine_unavailable,
)
