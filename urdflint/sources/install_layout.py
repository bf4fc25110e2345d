"""Files a ROS 2 package includes as they will be installed, found in its source tree.

A description package's xacro often includes `$(find pkg)/ros2_control/x.xacro` while the
file sits in `description/ros2_control/` of the source tree: its CMakeLists.txt installs
`install(DIRECTORY description/ros2_control DESTINATION share/${PROJECT_NAME})`, and
`$(find pkg)` in a workspace that is not built is the source folder. This module maps an
installed path back to its source file by reading those `install(DIRECTORY ...)` rules,
so `urdflint check src/` works before `colcon build` (ros2_control_demos is laid out this
way).
"""

from __future__ import annotations

import os
import re
from functools import lru_cache
from pathlib import Path

MAX_CMAKE_BYTES = 2**20
MAX_DEPTH = 8  # folders between a package's root and a file it installs
INSTALL_RE = re.compile(r"install\s*\(\s*DIRECTORY\s+(.*?)\s+DESTINATION\s+([^\s)]+)", re.S | re.I)
SHARE_RE = re.compile(r"^share/(?:\$\{PROJECT_NAME\}|[A-Za-z0-9_.-]+)(/.*)?$")


def source_file(path: str) -> str | None:
    """The source file that ``path`` (a file below a package folder, missing) is installed
    from, when the package's CMakeLists.txt installs a folder holding it; else ``None``."""
    folder = Path(path).parent
    for _ in range(MAX_DEPTH):
        if (folder / "package.xml").is_file():
            break
        if folder.parent == folder:
            return None
        folder = folder.parent
    else:
        return None
    relative = Path(os.path.relpath(path, folder)).as_posix()
    for installed, source in _rules(str(folder)):
        if relative.startswith(installed):
            candidate = folder / source / relative[len(installed) :]
            if candidate.is_file():
                return str(candidate)
    return None


@lru_cache(maxsize=64)  # bounded: the service sees a new job folder per request
def _rules(package: str) -> tuple[tuple[str, str], ...]:
    """``(installed prefix, source folder)`` pairs of the package's install(DIRECTORY) rules
    into its share folder, relative to the package (``("ros2_control/", "description/
    ros2_control/")``)."""
    try:
        path = Path(package) / "CMakeLists.txt"
        if path.stat().st_size > MAX_CMAKE_BYTES:
            return ()
        text = path.read_text(encoding="utf-8", errors="replace")
    except OSError:
        return ()
    text = re.sub(r"#[^\n]*", "", text)
    found: list[tuple[str, str]] = []
    for match in INSTALL_RE.finditer(text):
        share = SHARE_RE.match(match.group(2).strip("\"'"))
        if share is None:
            continue
        base = (share.group(1) or "").strip("/")
        for item in match.group(1).split():
            item = item.strip("\"'")
            if not item or item.startswith("$") or item.isupper():
                continue  # a variable, or a keyword (USE_SOURCE_PERMISSIONS, ...)
            source = item.rstrip("/")
            name = "" if item.endswith("/") else Path(source).name
            installed = "/".join(p for p in (base, name) if p)
            found.append((installed + "/" if installed else "", source + "/"))
    return tuple(found)
