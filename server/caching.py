"""The analysis cache in the service's lint workers.

Every worker opens the same cache folder (``URDFLINT_CACHE_DIR``, ``urdflint serve
--cache-dir``; none with ``URDFLINT_NO_CACHE=1``) on its first job. A request whose meshes
were seen before costs no mesh work (the meshes' facts are kept by content), and a request
identical to an earlier one (the same URDF and zip bytes, name and options) is answered
from the cache without linting. Nothing of one upload reaches another request's answer
except through identical content. The fence (``fence.py``) lets a job use the cache folder,
whose paths are digests that no request names.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from .jobs import CheckJob

log = logging.getLogger("urdflint.server.worker")

_CACHE: list[Any] = []  # the worker's analysis cache, opened on its first job


def worker_cache() -> Any:
    """The analysis cache the workers share (``URDFLINT_CACHE_DIR``, ``urdflint serve
    --cache-dir``; none with ``URDFLINT_NO_CACHE=1``): the facts of meshes seen before, and
    the answers to requests seen before, by the content of their files and options."""
    if not _CACHE:
        found = None
        if os.environ.get("URDFLINT_NO_CACHE", "") in ("", "0"):
            try:
                from urdflint.cache import DEFAULT_MAX_BYTES, Cache, parse_size

                size = os.environ.get("URDFLINT_CACHE_MAX_SIZE")
                found = Cache(None, parse_size(size) if size else DEFAULT_MAX_BYTES)
                found = found if found.usable else None
            except (OSError, ValueError):
                log.warning("the analysis cache cannot be used", exc_info=True)
                found = None
        if found is not None:
            from .fence import FENCE

            FENCE.cache = os.path.realpath(found.folder)
        _CACHE.append(found)
    return _CACHE[0]


def answered(job: CheckJob, check: Callable[[CheckJob, Any], dict[str, Any]]) -> dict[str, Any]:
    """``check(job, cache)``'s answer, or the answer stored for the same request (the same
    URDF and zip bytes, name and options; not with ``confirm``, whose engines are not in the
    key)."""
    cache = worker_cache()
    if cache is None or job.settings.confirm:
        return check(job, None)
    from urdflint.cache import deps, keys

    parts = (
        deps.digest_bytes(job.urdf),
        deps.digest_file(job.zip) if job.zip is not None else None,
        job.name,
        keys.settings_key(job.settings),
        job.fmt, job.svg, job.matrix, job.fix, job.unsafe_fixes, job.scene, job.statics,
        keys.canonical(job.zip_limits),
    )  # fmt: skip
    found = cache.get("response", *parts)
    if isinstance(found, dict) and found.get("status") == 200:
        return found
    answer = check(job, cache)
    if answer.get("status") == 200:
        cache.put("response", answer, *parts)
    cache.finish()
    return answer
