from __future__ import annotations

import atexit
import os
import shutil
import sys
import tempfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
FIXTURES = ROOT / "fixtures"
SHARED = Path(os.environ.get("URDFLINT_SHARED", ROOT.parent / "shared"))
CORPUS = SHARED / "corpus" / "robots"


# The analysis cache of every urdflint the tests run (in this process and in subprocesses)
# lives in a folder of this test process, never in the user's cache.
CACHE_DIR = Path(tempfile.mkdtemp(prefix="urdflint-test-cache-"))
os.environ["URDFLINT_CACHE_DIR"] = str(CACHE_DIR)
atexit.register(shutil.rmtree, CACHE_DIR, ignore_errors=True)


def corpus_models() -> list[Path]:
    return sorted(CORPUS.glob("*/model.urdf")) if CORPUS.is_dir() else []


needs_corpus = pytest.mark.skipif(not CORPUS.is_dir(), reason="../shared/corpus is not present")


@pytest.fixture
def urdflint_cmd() -> list[str]:
    return [sys.executable, "-m", "urdflint"]
