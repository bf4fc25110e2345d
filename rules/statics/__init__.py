"""D: statics, computed with Pinocchio (needs the dynamics extra): gravity torques against
effort limits, and whether a mobile base tips over."""

from urdflint.rules.statics import (  # noqa: F401
    d001_effort_cannot_hold,
    d002_implausible_effort,
    d003_tips_over,
)
