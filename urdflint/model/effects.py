"""What each target does with a defect: the consequence, and the severity that follows.

A rule declares, per target, the :class:`Effect` its defect has in that consumer (MuJoCo
refuses a negative mass, PyBullet loads it as written, Drake substitutes another inertia).
Findings carry the effects for the targets of the run; the compatibility matrix
(``urdflint check --matrix``) sums them up per target as one :class:`Outcome`.

Effects on ``mujoco``, ``pybullet``, ``drake``, ``pinocchio`` and ``gz-sim`` were observed by
loading planted defects in the engines (``bench/engine_agreement.py``; ``--confirm`` does
the same for a user's model); ``gazebo-classic``, ``isaac`` and ``ros`` cannot run here and
follow their source code and documentation (each rule's page names the source).
"""

from __future__ import annotations

import enum
from collections.abc import Mapping
from dataclasses import dataclass

from urdflint.model.finding import Severity


class Outcome(enum.IntEnum):
    """A target's verdict on a whole model, ordered from best to worst."""

    LOADS = 0
    CHANGES = 1
    REFUSED = 2
    CRASHES = 3

    @property
    def key(self) -> str:  # the JSON spelling
        return ("loads", "changes", "refused", "crashes")[self]

    @property
    def label(self) -> str:
        return ("loads", "loads with changes", "refused", "crashes")[self]


class Consequence(enum.Enum):
    """What a consumer does with one defect: ``(key, phrase, outcome, severity)``."""

    CRASH = ("crash", "crashes", Outcome.CRASHES, Severity.ERROR)
    REFUSED = ("refused", "refuses the model", Outcome.REFUSED, Severity.ERROR)
    LINK_DROPPED = ("link dropped", "drops the link", Outcome.CHANGES, Severity.ERROR)
    JOINT_CHANGED = ("joint changed", "builds another joint", Outcome.CHANGES, Severity.ERROR)
    JOINT_UNLIMITED = (
        "joint unlimited",
        "makes the joint unlimited",
        Outcome.CHANGES,
        Severity.ERROR,
    )
    LIMITS_CHANGED = (
        "limits changed",
        "changes the joint's limits",
        Outcome.CHANGES,
        Severity.ERROR,
    )
    INERTIA_SUBSTITUTED = (
        "inertia substituted",
        "substitutes another mass or inertia",
        Outcome.CHANGES,
        Severity.WARNING,
    )
    GEOMETRY_DROPPED = ("geometry dropped", "drops the geometry", Outcome.CHANGES, Severity.WARNING)
    TAG_IGNORED = ("tag ignored", "ignores it", Outcome.CHANGES, Severity.INFO)
    WARNS = ("warns", "warns and loads it as written", Outcome.LOADS, Severity.WARNING)
    AS_WRITTEN = ("as written", "loads it as written, silently", Outcome.LOADS, Severity.WARNING)

    @property
    def key(self) -> str:
        return str(self.value[0])

    @property
    def phrase(self) -> str:
        return str(self.value[1])

    @property
    def outcome(self) -> Outcome:
        return Outcome(self.value[2])

    @property
    def severity(self) -> Severity:
        return Severity(self.value[3])

    @classmethod
    def parse(cls, key: str) -> Consequence:
        for member in cls:
            if member.key == key:
                return member
        raise ValueError(f"unknown consequence {key!r}")


# Consequences an engine's load can show (--confirm): the agreement suite compares these.
MEASURABLE = frozenset(
    {
        Consequence.CRASH,
        Consequence.REFUSED,
        Consequence.LINK_DROPPED,
        Consequence.JOINT_UNLIMITED,
        Consequence.LIMITS_CHANGED,
        Consequence.INERTIA_SUBSTITUTED,
    }
)


@dataclass(frozen=True, slots=True)
class Effect:
    """One consumer's reaction to one defect; ``detail`` says what it does, in its words
    (a message it prints, the value it substitutes), ``severity`` overrides the
    consequence's own when the rule knows better."""

    consequence: Consequence
    detail: str = ""
    severity: Severity | None = None

    @property
    def level(self) -> Severity:
        return self.severity or self.consequence.severity

    def __reduce__(self) -> tuple[type, tuple[object, ...]]:
        return (Effect, (self.consequence, self.detail, self.severity))  # pickled fast

    def sentence(self, label: str) -> str:
        """``MuJoCo refuses the model (mass must be positive)``."""
        text = f"{label} {self.consequence.phrase}"
        return f"{text} ({self.detail})" if self.detail else text


# variant ("" when the rule has one) -> target -> effect
Effects = Mapping[str, Mapping[str, Effect]]


def crash(detail: str = "") -> Effect:
    return Effect(Consequence.CRASH, detail)


def refused(detail: str = "") -> Effect:
    return Effect(Consequence.REFUSED, detail)


def dropped(detail: str = "") -> Effect:
    return Effect(Consequence.LINK_DROPPED, detail)


def changed(detail: str = "") -> Effect:
    return Effect(Consequence.JOINT_CHANGED, detail)


def unlimited(detail: str = "") -> Effect:
    return Effect(Consequence.JOINT_UNLIMITED, detail)


def limits_changed(detail: str = "") -> Effect:
    return Effect(Consequence.LIMITS_CHANGED, detail)


def substituted(detail: str = "") -> Effect:
    return Effect(Consequence.INERTIA_SUBSTITUTED, detail)


def no_geometry(detail: str = "", severity: Severity | None = None) -> Effect:
    return Effect(Consequence.GEOMETRY_DROPPED, detail, severity)


def ignored(detail: str = "", severity: Severity | None = None) -> Effect:
    return Effect(Consequence.TAG_IGNORED, detail, severity)


def warns(detail: str = "", severity: Severity | None = None) -> Effect:
    return Effect(Consequence.WARNS, detail, severity)


def kept(detail: str = "", severity: Severity | None = None) -> Effect:
    return Effect(Consequence.AS_WRITTEN, detail, severity)


def single(table: Mapping[str, Effect]) -> Effects:
    """The effects of a rule whose defect has one variant."""
    return {"": dict(table)}


def for_targets(
    effects: Effects, variant: str, targets: frozenset[str] | tuple[str, ...]
) -> tuple[tuple[str, Effect], ...]:
    """The effects of ``variant`` on the selected ``targets``, in the targets' order."""
    table = effects[variant] if variant in effects else effects.get("", {})
    return tuple((t, table[t]) for t in targets if t in table)
