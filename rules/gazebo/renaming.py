"""The safe fix G005 and G006 share: rename a Gazebo key in place."""

from __future__ import annotations

from lxml import etree

from urdflint.model.document import Document
from urdflint.model.edits import RenameElement, Repair
from urdflint.model.gazebo_spec import keys_of


def rename_key(doc: Document, el: etree._Element, target: str | None) -> Repair | None:
    """Rename the key ``el`` to ``target``, unless a block of the same element already sets
    ``target`` (the rename would give it two values, and which one sdformat keeps would
    change)."""
    gazebo = el.getparent()
    if target is None or gazebo is None:
        return None
    ref = gazebo.get("reference") or ""
    blocks = [g for g in doc.gazebo if (g.get("reference") or "") == ref]
    if any(k.tag == target for g in blocks for k in keys_of(g)):
        return None
    return Repair("safe", f"rename <{el.tag}> to <{target}>", (RenameElement(el, target),))
