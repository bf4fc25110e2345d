"""Imported once by the worker pool's fork server, so every worker starts warm.

Workers are forked from a process that has already imported urdflint, its rules and the
optional heavy libraries (Pinocchio alone takes about 0.4 s and 77 MB to import), which
makes replacing a killed worker a matter of milliseconds and shares those pages
copy-on-write. BLAS and OpenMP are limited to one thread first: the pool is the parallelism.
"""

from __future__ import annotations

import contextlib
import importlib

from urdflint.server.threads import limit_threads

limit_threads()

from urdflint.engine import linter, registry  # noqa: E402,F401

registry.load_rules()

for _name in ("xacro", "numpy", "trimesh", "yourdfpy", "collada", "pinocchio",
              "urdflint.engine.physics", "urdflint.sources.meshes", "urdflint.sources.xacro",
              "urdflint.outputs.info", "urdflint.outputs.svg", "urdflint.outputs.formatters.json",
              "urdflint.outputs.scene", "urdflint.outputs.scene_meshes",
              "urdflint.sources.self_collision",
              "urdflint.outputs.formatters.sarif"):  # fmt: skip
    with contextlib.suppress(Exception):
        importlib.import_module(_name)
