"""``urdflint check --show-packages``: which folder each package name resolves to, and why.

Written to stderr before the files are linted, so the report and the exit code are those of
the same run without the option. Lists every package a checked file could name: the
package paths (command line and configuration) and the workspace's packages (every
``package.xml`` below the checked paths and their git root), each with the folder each
checked file gets and how it was chosen; a name with several packages lists the others.
Names found only through ``ROS_PACKAGE_PATH``, ``AMENT_PREFIX_PATH`` or a ``package.xml``
above a file are resolved the same way but not listed (they are not known in advance).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import IO, Any

from urdflint.sources.resolve import Lookup, candidates

MAX_FILES_SHOWN = 3  # files named per answer when the checked files do not all agree
ORDER = (
    "--package-path, package-paths in the configuration, the package holding the file, "
    "the workspace's package nearest to the file, ROS_PACKAGE_PATH, AMENT_PREFIX_PATH, "
    "a package.xml above the file"
)


def write(files: Sequence[str], context: Any, finder: Any, out: IO[str]) -> None:
    out.write(render(files, context, finder))
    out.flush()


def render(files: Sequence[str], context: Any, finder: Any) -> str:
    """The listing for ``files`` (a ``check`` run's files after discovery)."""
    checked = [f for f in files if f != "-"]
    folders = [Path(f).parent for f in checked] or [Path.cwd()]
    resolvers = [context.resolver(folder, finder.for_folder(folder)) for folder in folders]
    names = sorted({name for r in resolvers for name in r.package_paths} | set(context.workspace))
    lines = [f"urdflint: packages for {len(checked)} file(s), in this order: {ORDER}"]
    for name in names:
        answers: dict[tuple[str, str, tuple[str, ...]], list[str]] = {}
        for file, resolver in zip(checked or ["-"], resolvers, strict=True):
            found = resolver.lookup(name)
            answers.setdefault(answer(found, context), []).append(file)
        lines.extend(_lines(name, answers, len(resolvers), context))
    if not names:
        lines.append("  (no package.xml below the checked paths or their git root)")
    return "\n".join(lines) + "\n"


def answer(found: Lookup, context: Any) -> tuple[str, str, tuple[str, ...]]:
    """A lookup as listed: its folder (or ``not found``), how it was chosen (or where it was
    looked for), and the packages as near (also ``check --show-settings``)."""
    folder = _shown(found.folder) if found.folder is not None else "not found"
    how = found.how or "; ".join(found.tried)
    if how == "package path":
        how = "--package-path" if found.name in context.package_paths else "package-paths"
    return folder, how, tuple(_shown(t) for t in found.ties)


def _lines(
    name: str, answers: dict[tuple[str, str, tuple[str, ...]], list[str]], total: int, context: Any
) -> list[str]:
    listed = {f for folder, _, ties in answers for f in (folder, *ties)}
    others = [_shown(f) for f in candidates(context.workspace, name) if _shown(f) not in listed]
    out: list[str] = []
    for (folder, how, ties), files in answers.items():
        text = f"  {name}: {folder} ({how}"
        if ties:
            text += f"; as near: {', '.join(ties)} (C017)"
        text += ")"
        if len(answers) > 1 or len(files) < total:
            named = ", ".join(files[:MAX_FILES_SHOWN])
            more = len(files) - MAX_FILES_SHOWN
            text += f" for {named}" + (f" and {more} more" if more > 0 else "")
        out.append(text)
    if others:
        out.append(f"    also named {name}, not used: {', '.join(others)}")
    return out


def _shown(folder: Path) -> str:
    """``folder`` relative to the working folder when it is below it."""
    full = os.path.abspath(folder)
    here = os.getcwd()
    return os.path.relpath(full, here) if full.startswith(here + os.sep) else full
