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


# -- what this run leaves out --------------------------------------------------------------
# Tests marked ``slow`` (a real browser, the real engines, the editors, packaging the VS Code
# extension, pre-commit's own environment, real packages end to end) run only with
# URDFLINT_SLOW=1 or --slow: README's test command stays a few minutes on 2 cores, and
# .ci/run sets URDFLINT_SLOW=1 so that CI runs everything.
SLOW_REASON = "slow: URDFLINT_SLOW=1 or --slow runs it (.ci/run does)"


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--slow", action="store_true", help="also run the tests marked slow")


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line(
        "markers",
        "slow: a browser, the engines, the editors, VS Code packaging, pre-commit's "
        "environment or real packages end to end (URDFLINT_SLOW=1 or --slow runs them)",
    )


def run_slow(config: pytest.Config) -> bool:
    return os.environ.get("URDFLINT_SLOW", "") not in ("", "0") or config.getoption("--slow")


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    if run_slow(config):
        return
    skip = pytest.mark.skip(reason=SLOW_REASON)
    for item in items:
        if "slow" in item.keywords:
            item.add_marker(skip)


def pytest_sessionstart(session: pytest.Session) -> None:
    """Before the first test, even with ``-q``: which tests this run skips, and why."""
    config = session.config
    reporter = config.pluginmanager.get_plugin("terminalreporter")
    if reporter is None or hasattr(config, "workerinput"):  # an xdist worker: the parent says
        return
    for line in _skipping(config):
        reporter.write_line(line)


def _skipping(config: pytest.Config) -> list[str]:
    """Which optional parts this run lacks, and so which tests it skips."""
    lines = []
    if not run_slow(config):
        lines.append("urdflint: tests marked slow are skipped: URDFLINT_SLOW=1 or --slow runs them")
    missing = [what for what, here in _optional_parts() if not here]
    if missing:
        lines.append("urdflint: not installed here, their tests skip: " + "; ".join(missing))
    return lines


def _optional_parts() -> list[tuple[str, bool]]:
    import importlib.util

    def module(name: str) -> bool:
        return importlib.util.find_spec(name) is not None

    def program(*names: str) -> bool:
        return all(shutil.which(n) for n in names)

    engines = [n for n in ("mujoco", "pybullet", "pydrake") if not module(n)]
    full = module("pinocchio") and module("trimesh")
    chromium = bool(shutil.which("chromium") or shutil.which("chromium-browser"))
    return [
        ("../shared/corpus (the real robots)", CORPUS.is_dir()),
        ("the engines " + ", ".join(engines) + " (pip install -e '.[engines]')", not engines),
        ("Pinocchio, trimesh (pip install -e '.[full,test]')", full),
        ("chromium, chromedriver (apt-get install chromium chromium-driver)",
         program("chromedriver") and chromium),
        ("sdformat 12, g++ (apt-get install libsdformat-dev g++ pkg-config)",
         program("g++", "pkg-config") and _pkg_config("sdformat12")),
        ("nvim (apt-get install neovim)", program("nvim")),
        ("emacs with eglot (apt-get install emacs-nox elpa-eglot)", program("emacs")),
        ("node, npm (apt-get install nodejs npm)", program("node", "npm")),
    ]  # fmt: skip


def _pkg_config(package: str) -> bool:
    import subprocess

    try:
        return subprocess.run(["pkg-config", "--exists", package], timeout=10).returncode == 0
    except (OSError, subprocess.SubprocessError):
        return False
