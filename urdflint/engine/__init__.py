"""The linter: rule registry, configuration, run context, suppressions, baselines, physics.

Imports :mod:`urdflint.model` and :mod:`urdflint.sources`; rules plug in through the
registry (``RULE_PACKAGES``), never by a static import.
"""
