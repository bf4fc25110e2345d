"""Shared test helpers: lint a file or string with chosen rules, read fixture expectations."""

from __future__ import annotations

import re
from pathlib import Path

from urdflint.engine import config, linter
from urdflint.model.finding import Finding

EXPECT_RE = re.compile(r"<!--\s*expect:\s*(.*?)\s*-->")


def lint_file(
    path: Path, select: tuple[str, ...] | None = None, settings: config.Settings | None = None
) -> list[Finding]:
    settings = settings or fixture_settings(path)
    if select is not None:
        settings = config.Settings(**{**settings.__dict__, "select": select})
    return linter.lint_path(path, str(path), settings).findings


def lint_text(text: str, select: tuple[str, ...] | None = None, **kwargs: object) -> list[Finding]:
    settings = config.from_mapping(dict(kwargs)) if kwargs else config.Settings()
    if select is not None:
        settings = config.Settings(**{**settings.__dict__, "select": select})
    return linter.lint_bytes(text.encode(), "test.urdf", settings).findings


def fixture_settings(path: Path) -> config.Settings:
    """``<stem>.toml`` beside a fixture, else the folder's ``config.toml``, else defaults."""
    for candidate in (path.with_suffix(".toml"), path.parent / "config.toml"):
        if candidate.is_file():
            return config.load(candidate)
    return config.Settings()


def expectations(path: Path) -> set[tuple[int, str, str]]:
    """``(line, code, element)`` from ``<!-- expect: CODE /robot/... -->`` comments.

    Several expectations on one line are separated by ``;`` or written as
    several comments.
    """
    found: set[tuple[int, str, str]] = set()
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        for match in EXPECT_RE.finditer(line):
            for entry in match.group(1).split(";"):
                code, _, element = entry.strip().partition(" ")
                found.add((number, code.strip(), element.strip()))
    return found
