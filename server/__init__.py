"""HTTP validation service (a later issue)."""
