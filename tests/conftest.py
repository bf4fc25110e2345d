from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
FIXTURES = ROOT / "fixtures"
SHARED = Path(os.environ.get("URDFLINT_SHARED", ROOT.parent / "shared"))
CORPUS = SHARED / "corpus" / "robots"


def corpus_models() -> list[Path]:
    return sorted(CORPUS.glob("*/model.urdf")) if CORPUS.is_dir() else []


needs_corpus = pytest.mark.skipif(not CORPUS.is_dir(), reason="../shared/corpus is not present")


@pytest.fixture
def urdflint_cmd() -> list[str]:
    return [sys.executable, "-m", "urdflint"]
