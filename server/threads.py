"""One BLAS/OpenMP thread per worker process: the pool gives the parallelism."""

from __future__ import annotations

import os

THREAD_VARS = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS")


def limit_threads() -> None:
    """Set each thread-count variable to 1 unless the operator set it."""
    for name in THREAD_VARS:
        os.environ.setdefault(name, "1")
