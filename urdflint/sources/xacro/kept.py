"""Xacro expansions kept in the analysis cache, and patched when one value changed.

With ``context.cache`` (:mod:`urdflint.cache`), the expansion of an entry file is stored
with its source map (the files xacro read, as bytes, and the mark of every element in
document order) and every input the expansion read: each include and YAML file, each
``package.xml`` of a ``$(find)``, the paths looked for and not found, the environment
variables ``$(env)`` read. A later run gets:

- the stored expansion, when none of those inputs changed (no xacro at all);
- when exactly one file it read changed, and the change is a value typed into a plain
  element's attribute (the common edit: a mass, an origin), the stored expansion patched by
  :mod:`urdflint.sources.xacro.patch`, which proves the result is what xacro would write;
- otherwise a full expansion, stored for next time.

Only expansions that produced a robot or a library are stored; an expansion error (X010...)
is computed again each time.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from urdflint.cache import deps, keys
from urdflint.model.document import Document
from urdflint.sources.xacro.sourcemap import SourceFile, SourceMap

if TYPE_CHECKING:
    from urdflint.engine.config import Settings
    from urdflint.engine.context import Context

KIND = "xacro"


def document(
    path: Path,
    shown: str,
    settings: Settings,
    context: Context,
    expand: Callable[[], Document],
    common: dict[str, Any],
) -> Document:
    """``expand()``'s document, or the stored one (patched when it can be)."""
    cache = context.cache
    if cache is None or not getattr(cache, "usable", False):
        return expand()
    full = os.path.abspath(path)
    parts = (
        full,
        shown,
        keys.canonical(settings.xacro_args_for(str(path))),
        keys.canonical(settings.package_paths),
        keys.context_key(context),
    )
    outer = deps.current()
    entry = cache.entry(KIND, parts)
    if entry is not None:
        inputs, value = entry
        found = _stored(entry, shown, common, context, outer)
        if found is not None:
            return found
        doc = _patched(inputs, value, shown, common, context)
        if doc is not None:
            changed = deps.changes(inputs, context.overlay, context.environ, limit=1)
            fresh = tuple(deps.now(d, context.overlay) if d in changed else d for d in inputs)
            _keep(cache, parts, fresh, doc)
            if outer is not None:
                outer.inherit(fresh)
            return doc
    with deps.recording(cache.ignore) as recorder:
        doc = expand()
        inputs = recorder.deps()
    if outer is not None:
        outer.inherit(inputs)
    _keep(cache, parts, inputs, doc)
    return doc


def _stored(
    entry: tuple[Any, Any], shown: str, common: dict[str, Any], context: Context, outer: Any
) -> Document | None:
    """The stored document, when nothing it read changed."""
    inputs, value = entry
    with deps.unrecorded():
        fresh = deps.unchanged(inputs, context.overlay, context.environ)
    if not fresh:
        return None
    if outer is not None:
        outer.inherit(inputs)
    return _rebuilt(value, shown, common)


def _patched(
    inputs: tuple[Any, ...], value: Any, shown: str, common: dict[str, Any], context: Context
) -> Document | None:
    """The stored document patched for the one file that changed, if it can be."""
    with deps.unrecorded():
        changed = deps.changes(inputs, context.overlay, context.environ, limit=2)
        if len(changed) != 1 or changed[0].kind not in ("file", "content"):
            return None
        name = changed[0].name
        files = {path: data for path, _shown, data in value[1]}
        if name not in files:
            return None
        new = context.overlay.get(name)
        try:
            new = new if new is not None else Path(name).read_bytes()
        except OSError:
            return None
    from urdflint.sources.xacro import patch

    previous = _rebuilt(value, shown, common)
    return patch.apply(previous, name, files[name], new, context)


def _keep(cache: Any, parts: tuple[Any, ...], inputs: tuple[Any, ...], doc: Document) -> None:
    origin = doc.origin
    if not doc.ok or doc.root is None or not isinstance(origin, SourceMap):
        return
    order = origin.sequence(doc.root)
    if order is None:
        return
    files = [(f.path, f.shown, f.data) for f in origin.files]
    cache.keep(KIND, parts, inputs, (doc.source, files, order, doc.library))


def _rebuilt(value: Any, shown: str, common: dict[str, Any]) -> Document:
    source, files, order, library = value
    sources = [SourceFile(path, seen, data) for path, seen, data in files]
    origin = SourceMap(sources, None, shown, source, order=list(order))
    doc = Document(shown, source, origin=origin, **common)
    doc.library = library
    return doc
