"""What the N rules share: which profile is active and how each REP is cited."""

from __future__ import annotations

from typing import TYPE_CHECKING

from urdflint.model.structure import welded

if TYPE_CHECKING:
    from urdflint.model.document import Document, Link

MOBILE, INDUSTRIAL, HUMANOID = "mobile", "industrial", "humanoid"
EVERY = (MOBILE, INDUSTRIAL, HUMANOID)

# The REP that defines base_link for each profile.
BASE_LINK_REP = {
    MOBILE: "REP 105 (base_link)",
    HUMANOID: "REP 120 (base_link)",
    INDUSTRIAL: "REP 199 draft (base_link)",
}


def active(doc: Document, *profiles: str) -> str | None:
    """The run's profile when it is one of ``profiles``; ``None`` otherwise (no profile)."""
    profile = doc.settings.profile
    return profile if profile in profiles else None


def root_link(doc: Document) -> Link | None:
    root = doc.graph.root
    return doc.link_map.get(root) if root is not None else None


def root_body(doc: Document) -> list[str]:
    """The root link and every link welded to it by fixed joints."""
    root = doc.graph.root
    return welded(doc.graph, root) if root is not None else []


def has_geometry(link: Link) -> str | None:
    """``"<visual>"`` or ``"<collision>"`` when the link has one (visuals first)."""
    if link.visuals:
        return "<visual>"
    if link.collisions:
        return "<collision>"
    return None
