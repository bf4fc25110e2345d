"""``urdflint report``: a dataset run's ``--format jsonl`` records summarised.

:mod:`.summary` aggregates the records as plain dicts (the ``--format json`` output) and
:mod:`.diff` compares two runs; :mod:`.text`, :mod:`.html` (one self-contained page with
:mod:`.plots`' inline SVG) and :mod:`.parquet` (``files.parquet``, ``findings.parquet``;
needs pyarrow) write them out. Nothing here imports more than the standard library until
a format asks for it.
"""

from __future__ import annotations

from urdflint.outputs.dataset.diff import compare, fingerprint
from urdflint.outputs.dataset.summary import load, summarize

__all__ = ["compare", "fingerprint", "load", "summarize"]
