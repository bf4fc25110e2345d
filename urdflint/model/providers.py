"""Document views computed by a higher layer, registered here so the model imports nothing
above it."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from urdflint.model.document import Document

# Views a higher layer computes for a document: "settings" and "context" (defaults when
# the caller gave none) and "physics" (the Pinocchio view). The engine registers them
# (urdflint.engine.views), so this module never imports above the model.
PROVIDERS: dict[str, Callable[[Document], Any]] = {}


def provide(name: str) -> Callable[[Callable[[Document], Any]], Callable[[Document], Any]]:
    """Register the function that computes the view ``name`` of a document."""

    def register(function: Callable[[Document], Any]) -> Callable[[Document], Any]:
        PROVIDERS[name] = function
        return function

    return register


def provided(name: str, doc: Document) -> Any:
    try:
        function = PROVIDERS[name]
    except KeyError:
        raise RuntimeError(
            f"no provider for the document view {name!r}: import urdflint.engine.views"
        ) from None
    return function(doc)
