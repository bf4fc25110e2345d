"""Uploaded files: a safe name for the URDF, and the meshes zip unpacked without surprises.

The zip is unpacked into the request's own folder (created and removed by the app) and
refused as a whole (:class:`Rejected`, answered with 422) when any member is unsafe:

- a name that is absolute, has a drive letter, a backslash, a NUL, or a ``..`` part
  (zip-slip), or that appears twice;
- a symbolic link, an encrypted member, or a nested archive (by name or by content);
- more than ``max_members`` entries, more than ``max_unzipped`` bytes in total, or a
  member over 1 MiB compressed more than ``max_ratio`` times (zip bombs). The sizes in
  the zip's headers are never trusted: bytes are counted as they are inflated.

Files are created with ``O_EXCL | O_NOFOLLOW``, so nothing is written through a link.
The zip's folders then serve as ROS packages: each top-level folder ``NAME`` answers
``package://NAME/...``, and each ``package.xml`` found names its own folder.
"""

from __future__ import annotations

import os
import re
import stat
import zipfile
from dataclasses import dataclass
from pathlib import Path, PurePosixPath

from urdflint.sources.resolve import package_name

CHUNK = 1 << 16
RATIO_FLOOR = 1 << 20  # members smaller than this are not ratio-checked
URDF_SUFFIXES = (".urdf", ".xacro", ".xml")
NAME_RE = re.compile(r"[^A-Za-z0-9._+-]")
ARCHIVE_SUFFIXES = (
    ".zip", ".jar", ".tar", ".tgz", ".gz", ".bz2", ".xz", ".zst", ".7z", ".rar", ".lz4", ".lzma",
)  # fmt: skip
ARCHIVE_MAGIC = (
    b"PK\x03\x04",  # zip
    b"PK\x05\x06",  # empty zip
    b"\x1f\x8b",  # gzip
    b"BZh",  # bzip2
    b"\xfd7zXZ\x00",  # xz
    b"7z\xbc\xaf\x27\x1c",  # 7-zip
    b"Rar!\x1a\x07",  # rar
    b"\x28\xb5\x2f\xfd",  # zstd
)


class Rejected(Exception):
    """An upload refused as a whole; the message is the reason given to the client."""


@dataclass(frozen=True)
class ZipLimits:
    max_members: int = 5000
    max_unzipped: int = 512 * 2**20
    max_ratio: float = 100.0


def urdf_name(raw: str | None, default: str = "robot.urdf") -> str:
    """A safe file name for the upload, keeping its suffix (``.urdf``/``.xacro``/``.xml``)."""
    base = re.split(r"[\\/]", raw or "")[-1].strip()
    if not base:
        return default
    if not base.lower().endswith(URDF_SUFFIXES):
        raise ValueError(f"the URDF file must end in .urdf, .xacro or .xml, not {base!r}")
    safe = NAME_RE.sub("_", base).lstrip(".") or default
    if len(safe) > 120:
        stem, dot, suffix = safe.rpartition(".")
        safe = stem[: 119 - len(suffix)] + dot + suffix
    return safe


def member_path(raw: str) -> PurePosixPath:
    """The member's path, or :class:`Rejected` for anything that could leave the folder."""
    if not raw or "\x00" in raw or "\\" in raw:
        raise Rejected(f"the zip has a member with an illegal name ({raw!r})")
    path = PurePosixPath(raw)
    if path.is_absolute() or raw.startswith("/"):
        raise Rejected(f"the zip has a member with an absolute path ({raw!r})")
    if ".." in path.parts:
        raise Rejected(f"the zip has a member leading out of its folder ({raw!r})")
    if ":" in path.parts[0]:
        raise Rejected(f"the zip has a member with a drive letter ({raw!r})")
    if any(len(part.encode()) > 255 for part in path.parts) or len(raw) > 1024:
        raise Rejected(f"the zip has a member with an over-long name ({raw[:60]!r}...)")
    return path


def _is_link(info: zipfile.ZipInfo) -> bool:
    return stat.S_ISLNK(info.external_attr >> 16)


def extract(archive: Path, root: Path, limits: ZipLimits) -> dict[str, Path]:
    """Unpack ``archive`` into ``root`` (an empty folder); the package paths it provides."""
    try:
        with zipfile.ZipFile(archive) as zf:
            infos = zf.infolist()
            if len(infos) > limits.max_members:
                raise Rejected(
                    f"the zip has {len(infos)} members, over the limit of {limits.max_members}"
                )
            planned = _plan(infos)
            total = 0
            for info, path in planned:
                target = root.joinpath(*path.parts)
                if info.is_dir():
                    target.mkdir(parents=True, exist_ok=True)
                    continue
                target.parent.mkdir(parents=True, exist_ok=True)
                total = _write(zf, info, target, total, limits)
    except Rejected:
        raise
    except zipfile.BadZipFile as exc:
        raise Rejected(f"the meshes upload is not a readable zip file ({exc})") from None
    except (zipfile.LargeZipFile, NotImplementedError, RuntimeError, EOFError) as exc:
        raise Rejected(f"the zip cannot be unpacked ({exc})") from None
    except OSError as exc:
        raise Rejected(f"the zip cannot be unpacked ({exc.strerror or exc})") from None
    return packages(root)


def _plan(infos: list[zipfile.ZipInfo]) -> list[tuple[zipfile.ZipInfo, PurePosixPath]]:
    """Every member checked before anything is written."""
    seen: set[PurePosixPath] = set()
    planned = []
    for info in infos:
        path = member_path(info.filename)
        if path in seen and not info.is_dir():
            raise Rejected(f"the zip has the member {info.filename!r} twice")
        seen.add(path)
        if _is_link(info):
            raise Rejected(f"the zip has a symbolic link ({info.filename!r})")
        if info.flag_bits & 0x1:
            raise Rejected(f"the zip has an encrypted member ({info.filename!r})")
        if not info.is_dir() and path.name.lower().endswith(ARCHIVE_SUFFIXES):
            raise Rejected(f"the zip contains another archive ({info.filename!r})")
        planned.append((info, path))
    files = {p for i, p in planned if not i.is_dir()}
    for path in files:
        if any(parent in files for parent in path.parents):
            raise Rejected(f"the zip uses a file as a folder ({path.as_posix()!r})")
    return planned


def _write(
    zf: zipfile.ZipFile, info: zipfile.ZipInfo, target: Path, total: int, limits: ZipLimits
) -> int:
    compressed = max(info.compress_size, 1)
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | getattr(os, "O_CLOEXEC", 0)
    try:
        fd = os.open(target, flags, 0o600)
    except FileExistsError:
        raise Rejected(f"the zip has the member {info.filename!r} twice") from None
    written = 0
    with os.fdopen(fd, "wb") as out, zf.open(info) as src:
        while True:
            chunk = src.read(CHUNK)
            if not chunk:
                break
            if written == 0 and chunk.startswith(ARCHIVE_MAGIC):
                raise Rejected(f"the zip contains another archive ({info.filename!r})")
            written += len(chunk)
            total += len(chunk)
            if total > limits.max_unzipped:
                raise Rejected(
                    f"the zip expands to more than {limits.max_unzipped // 2**20} MiB "
                    "(the limit for unpacked meshes)"
                )
            if written > RATIO_FLOOR and written > limits.max_ratio * compressed:
                raise Rejected(
                    f"the zip member {info.filename!r} is compressed more than "
                    f"{limits.max_ratio:g} times: refused as a possible zip bomb"
                )
            out.write(chunk)
    return total


def packages(root: Path) -> dict[str, Path]:
    """Package name -> folder: top-level folders, then every ``package.xml`` (which wins)."""
    found = {p.name: p for p in sorted(root.iterdir()) if p.is_dir() and not p.is_symlink()}
    for manifest in sorted(root.rglob("package.xml")):
        if manifest.is_symlink() or not manifest.is_file():
            continue
        name = package_name(manifest.parent)
        if name and "/" not in name and name not in (".", ".."):
            found[name] = manifest.parent
    return found
