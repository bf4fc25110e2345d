"""Confirmation against the real simulation engines (``urdflint check --confirm ...``).

MuJoCo, PyBullet, Drake and Pinocchio each load the model in their own process
(:mod:`urdflint.engines.probe`, run by :mod:`urdflint.engines.runner`), and so does sdformat,
Gazebo's URDF converter (a compiled probe, :mod:`urdflint.engines.sdformat`); the E rules read
what they refused, printed, dropped or crashed on through the document view
``confirmation``, registered here. Nothing heavy is imported until a rule asks for it,
and nothing runs unless the settings name engines to confirm with.
"""

from __future__ import annotations

from typing import Any
from weakref import WeakKeyDictionary

from urdflint.model.document import Document
from urdflint.model.providers import provide

_DONE: WeakKeyDictionary[Document, list[Any]] = WeakKeyDictionary()


@provide("confirmation")
def confirmation(doc: Document) -> list[Any]:
    """One :class:`~urdflint.engines.runner.Outcome` per engine in ``settings.confirm``
    (computed once per document; empty without ``--confirm`` or on an unusable file)."""
    found = _DONE.get(doc)
    if found is None:
        engines = tuple(getattr(doc.settings, "confirm", ()))
        found = []
        if engines and doc.ok and not doc.library:
            from urdflint.engines.runner import confirm

            found = confirm(doc, engines)
        _DONE[doc] = found
    return found
