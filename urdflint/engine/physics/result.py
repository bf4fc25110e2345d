"""What Pinocchio made of one document (:class:`Physics`), and how the P rules read it."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from lxml import etree

    from urdflint.model.document import Document

Vec = tuple[float, float, float]

MASS_RTOL = 1e-9
MASS_ATOL = 1e-12


@dataclass(frozen=True, slots=True)
class Blocker:
    """A static finding that stops the Pinocchio build."""

    code: str
    name: str
    message: str
    element: etree._Element | None
    line: int
    where: str  # "line 12", or "file.xacro:12" when the line is in another file


@dataclass(frozen=True, slots=True)
class QProblem:
    """A ``--q``/``expect.q`` entry that cannot be applied."""

    joint: str
    message: str
    element: etree._Element | None = None
    fix: str | None = None


@dataclass
class Physics:
    """What Pinocchio made of one document.

    ``built`` is false when a static error stopped the build (``blocker``: a kinematic
    loop), when Pinocchio refused the model (``reason`` translated, ``element`` named,
    ``blocker`` the static error that explains it, if any), when Pinocchio built it but
    misread it (``misread``: ``reason`` says what, ``blocker`` why), when the model is too
    deep or too large for Pinocchio (``limited``) or when Pinocchio is not installed
    (``missing``). Masses are in kg, positions in metres
    in the root link's frame.
    """

    built: bool
    reason: str | None = None
    element: etree._Element | None = None
    blocker: Blocker | None = None
    missing: bool = False
    limited: bool = False  # too large for Pinocchio: urdflint's limit, not a defect
    misread: bool = False  # built, but read differently from the file (``reason`` says how)
    name: str | None = None
    root: str | None = None
    dof: int = 0
    joint_names: list[str] = field(default_factory=list)  # Pinocchio joints, mimics included
    mimics: dict[str, tuple[str, float, float]] = field(default_factory=dict)
    urdf_mass: float = 0.0  # sum of the readable <mass> values
    mass: float = 0.0  # Pinocchio's total, inertias[0] included
    naive_mass: float = 0.0  # computeTotalMass on the fixed-base model
    universe_links: list[str] = field(default_factory=list)  # links on the universe joint
    link_masses: dict[str, float] = field(default_factory=dict)  # as Pinocchio holds them
    com: Vec | None = None
    com_problem: str | None = None
    q: dict[str, float] = field(default_factory=dict)  # applied positions, mimics included
    q_problems: list[QProblem] = field(default_factory=list)
    model: Any = None

    @property
    def mass_matches(self) -> bool:
        """Whether Pinocchio's total equals the sum of the URDF's ``<mass>`` values."""
        return close(self.mass, self.urdf_mass)


def close(a: float, b: float) -> bool:
    return abs(a - b) <= max(MASS_RTOL * max(abs(a), abs(b)), MASS_ATOL)


def unverifiable(doc: Document, physics: Physics) -> str | None:
    """Why an expectation cannot be checked, or ``None`` when P001 already reports it.

    A CI gate must not pass silently: when P001 is switched off for this file, or
    only warns (a model over urdflint's size limits), the rule whose expectation
    went unchecked says so itself.
    """
    settings = doc.settings
    if physics.missing or physics.limited or physics.reason is None:
        return physics.reason  # P001 only warns about urdflint's size limits
    if "P001" in settings.enabled() - settings.ignored_for(doc.path):
        return None
    return physics.reason
