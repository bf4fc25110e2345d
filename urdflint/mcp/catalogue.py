"""The resources: the rule catalogue (``urdflint://rules``, ``urdflint rules --format json``)
and one page per rule (``urdflint://rules/{code}``, ``urdflint explain CODE --long``)."""

from __future__ import annotations

import json
from typing import Any

from urdflint.mcp.roots import Refused

CATALOGUE = "urdflint://rules"
PAGE = "urdflint://rules/{code}"
RESOURCES = [
    {
        "uri": CATALOGUE,
        "name": "rules",
        "title": "urdflint rules",
        "description": "Every rule: code, name, default severity, family, summary, options "
        "(urdflint rules --format json).",
        "mime_type": "application/json",
    }
]
TEMPLATES = [
    {
        "uri_template": PAGE,
        "name": "rule",
        "title": "urdflint rule page",
        "description": "A rule's full page, by code or name: what, why, how to fix, what each "
        "simulator does, examples (urdflint explain CODE --long).",
        "mime_type": "text/markdown",
    }
]


def read(uri: str) -> tuple[str, str]:
    """The resource's text and MIME type; :class:`Refused` for an unknown one."""
    from urdflint.engine import docs, registry

    if uri == CATALOGUE:
        return json.dumps({"version": 1, "rules": rules()}, indent=2) + "\n", "application/json"
    prefix = CATALOGUE + "/"
    if uri.startswith(prefix):
        found = registry.lookup(uri[len(prefix) :])
        if found is not None:
            return docs.page(found), "text/markdown"
    raise Refused(f"no resource {uri!r} (urdflint://rules, urdflint://rules/CODE)")


def rules() -> list[dict[str, Any]]:
    """The rules as ``urdflint rules --format json`` lists them."""
    from urdflint.engine import registry

    return registry.catalogue()
