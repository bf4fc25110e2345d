"""The static findings that explain Pinocchio's refusal of a model (cited by P001, and
carrying its effect when they are reported: one defect, one finding)."""

from __future__ import annotations

BLOCKING = (
    "X003",
    "X004",
    "X005",
    "X008",
    "X009",
    "S001",
    "S002",
    "S003",
    "S004",
    "S005",
    "S006",
    "S007",
    "S008",
    "S010",
    "J001",
    "J007",
    "J010",
    "J013",
    "I012",
)
