"""The folders the client lets the server use (its MCP roots), and the paths inside them.

A client lists its roots (``roots/list``, ``file://`` URIs); without any, the folders given to
``urdflint mcp --root``, else the server's working directory, are the roots. Every path a
tool is given (files, folders, package paths, the name of a text) must lie inside a root once
symbolic links are resolved, and each file is linted with its root as
:attr:`urdflint.engine.context.Context.root`, the HTTP service's confinement: xacro
includes, ``$(find pkg)``, meshes and SRDFs outside it are refused as findings, as the
service refuses them. Fixes write only inside the roots (:mod:`.fixing`).

Relative paths are relative to the first root. Findings name a file as ``urdflint check``
run from the server's working directory names it: relative to that folder when the file is
below it, else by its absolute path.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import unquote, urlparse


class Refused(Exception):
    """What a tool was asked cannot be done (a path outside the roots, an unknown option):
    one line, the tool's error."""


@dataclass(frozen=True)
class Place:
    """A file (or folder) a tool works on: its absolute path, the name the findings give it,
    and the root it lies in."""

    path: Path
    shown: str
    root: Path


@dataclass(frozen=True)
class Roots:
    """The allowed folders (symbolic links resolved); ``given``: the client listed them."""

    folders: tuple[Path, ...]
    given: bool = False

    @classmethod
    def here(cls) -> Roots:
        """The server's working directory: the root when the client has none."""
        return cls((Path(os.path.realpath(os.getcwd())),))

    @classmethod
    def of(cls, folders: Iterable[Path]) -> Roots:
        """Folders given on the command line (``urdflint mcp --root DIR``)."""
        found = [Path(os.path.realpath(folder)) for folder in folders]
        return cls(tuple(dict.fromkeys(found))) if found else cls.here()

    @classmethod
    def from_uris(cls, uris: Iterable[str]) -> Roots:
        """The client's roots; none: the working directory. Roots that are not local folders
        (another scheme or host) confine to nothing: a client whose every root is such one
        is refused rather than given the working directory."""
        listed = list(uris)
        if not listed:
            return cls.here()  # (the server gives its --root instead)
        folders = [folder for uri in listed if (folder := _local(uri)) is not None]
        if not folders:
            raise Refused(f"the client's roots are not local folders: {', '.join(listed)}")
        return cls(tuple(dict.fromkeys(folders)), given=True)

    def describe(self) -> str:
        return ", ".join(str(folder) for folder in self.folders)

    def containing(self, path: Path | str) -> Path | None:
        """The root ``path`` lies in once links are resolved, or ``None``."""
        real = Path(os.path.realpath(path))
        return next((f for f in self.folders if real == f or real.is_relative_to(f)), None)

    def place(self, given: str, *, must_exist: bool = True) -> Place:
        """Where ``given`` is; :class:`Refused` when it is outside the roots or, with
        ``must_exist``, not there."""
        text = given.strip()
        if text.startswith("file:"):
            local = _local(text)
            if local is None:
                raise Refused(f"{given}: not a file on this machine")
            text = str(local)
        if not text:
            raise Refused("a path is empty")
        path = Path(text)
        if not path.is_absolute():
            path = self.folders[0] / path
        path = Path(os.path.normpath(path))
        root = self.containing(path)
        if root is None:
            raise Refused(f"{given}: outside the allowed roots ({self.describe()})")
        if must_exist and not path.exists():
            raise Refused(f"{given}: no such file or directory")
        return Place(path, shown(path), root)


def shown(path: Path) -> str:
    """The name ``urdflint check`` run from the working directory gives ``path``."""
    here = Path.cwd()
    return os.path.relpath(path, here) if path.is_relative_to(here) else str(path)


def _local(uri: str) -> Path | None:
    """The folder of a ``file://`` URI on this machine (symbolic links resolved)."""
    parsed = urlparse(str(uri))
    if parsed.scheme != "file" or parsed.netloc not in ("", "localhost"):
        return None
    text = unquote(parsed.path)
    if os.name == "nt" and text[:1] == "/" and text[2:3] == ":":
        text = text[1:]  # file:///C:/work -> C:/work
    return Path(os.path.realpath(text)) if text else None
