"""``[tool.urdflint.stability]``: what the stability analysis (D003, ``info --statics``) uses.

```toml
[tool.urdflint.stability]
contact-links = ["wheel_fl", "wheel_fr", "caster"]   # default: found (urdflint.engine.stability)
contact-tolerance = 0.01                             # m above the lowest point that still touches
samples = 512                                        # configurations sampled for D003 and reach
```

:func:`parse_stability` raises the error class ``config`` hands it (``ConfigError``) with a message
naming the key. No heavy import here: ``config`` imports this module.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

KEYS = frozenset({"contact-links", "contact-tolerance", "samples"})
MAX_SAMPLES = 20000


@dataclass(frozen=True)
class StabilitySettings:
    """The contact links (empty: found by the heuristic), how far above the lowest point a
    contact may be (m), and how many configurations are sampled."""

    contact_links: tuple[str, ...] = ()
    contact_tolerance: float = 0.01
    samples: int = 512


def parse_stability(table: Any, error: type[Exception] = ValueError) -> StabilitySettings:
    """Validate a ``[tool.urdflint.stability]`` table; ``error`` is raised when it is invalid."""
    if not isinstance(table, dict):
        raise error("'stability' must be a table (contact-links, contact-tolerance, samples)")
    unknown = sorted(set(table) - KEYS)
    if unknown:
        raise error(
            f"unknown configuration key 'stability.{unknown[0]}' (known: {', '.join(sorted(KEYS))})"
        )
    found = StabilitySettings()
    if "contact-links" in table:
        links = table["contact-links"]
        if isinstance(links, str):
            links = [links]
        if not isinstance(links, list) or not all(isinstance(v, str) and v for v in links):
            raise error("'stability.contact-links' must be a list of link names")
        found = replace(found, contact_links=tuple(links))
    if "contact-tolerance" in table:
        value = table["contact-tolerance"]
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not 0 <= value <= 0.5:
            raise error("'stability.contact-tolerance' must be a number of metres, 0 to 0.5")
        found = replace(found, contact_tolerance=float(value))
    if "samples" in table:
        value = table["samples"]
        if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= MAX_SAMPLES:
            raise error(f"'stability.samples' must be a whole number from 0 to {MAX_SAMPLES}")
        found = replace(found, samples=value)
    return found
