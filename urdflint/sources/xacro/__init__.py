"""Xacro input: expand ``*.xacro`` in-process with the PyPI ``xacro`` package, no ROS needed.

``document()`` returns the expanded :class:`~urdflint.document.Document`. What it adds
to plain xacro:

- ``$(find pkg)`` resolves through urdflint's package paths (``--package-path``, the
  configuration's ``package-paths``, ``ROS_PACKAGE_PATH``, ``AMENT_PREFIX_PATH``, a
  ``package.xml`` upward search), the same as ``package://`` meshes;
- xacro's global state is reset for every file and its console output is captured,
  so several files in one run do not leak into each other and stdout stays a report;
- every file xacro opens is refused when it declares a DOCTYPE or entities (X002),
  is over 64 MiB, or (with ``context.root`` set, the HTTP service) lies outside the
  root; in that confined mode the environment is hidden from ``$(env)``/``$(optenv)``
  and the expression evaluator refuses the known ways out of its sandbox;
- an expansion error (undefined property, missing include, bad XML in an include,
  runaway recursion...) becomes one X010 finding instead of a traceback, naming the xacro
  argument behind it when one is empty or missing (:mod:`.arguments`); a file that
  only fails because it is a fragment of another file (it uses names its includer
  defines) is a library (X011), and so is a file with no ``<link>`` after expansion;
- ``Document.origin`` maps each element of the expanded document back to the line
  of the source file where it is written literally (see :class:`LineMap`).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from urdflint.model.document import Document, Origin, XmlProblem, children
from urdflint.sources.xacro.expansion import Expansion
from urdflint.sources.xacro.sourcemap import SourceMap

if TYPE_CHECKING:
    from urdflint.engine.config import Settings
    from urdflint.engine.context import Context

__all__ = ["Expansion", "Origin", "document"]


def document(path: Path, shown: str, settings: Settings, context: Context) -> Document:
    """``path`` expanded by xacro, as a document whose findings name ``shown`` (kept in the
    analysis cache, and patched after a value edit: :mod:`urdflint.sources.xacro.kept`)."""
    common: dict[str, Any] = {
        "targets": frozenset(settings.targets),
        "settings": settings,
        "context": context,
        "base_dir": path.parent,
    }
    if getattr(context, "cache", None) is None or context.overlay:
        # (an editor's buffers: the language server patches its own last expansion)
        return _expanded(path, shown, settings, context, common)
    from urdflint.sources.xacro import kept

    def expand() -> Document:
        return _expanded(path, shown, settings, context, common)

    return kept.document(path, shown, settings, context, expand, common)


def _expanded(
    path: Path, shown: str, settings: Settings, context: Context, common: dict[str, Any]
) -> Document:
    expansion = Expansion(path, shown, settings, context)
    outcome = expansion.run()
    if isinstance(outcome, XmlProblem):
        return Document(shown, b"", problem=outcome, library=outcome.code == "X011", **common)
    doc = Document(
        shown,
        outcome,
        origin=SourceMap(expansion.tracker.files, expansion.dom, shown, outcome),
        **common,
    )
    if doc.ok and not children(doc.robot, "link"):
        doc.library = True
    return doc
