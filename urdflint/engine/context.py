"""What one lint run shares across its files: package paths, the confinement root, meshes."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from urdflint.sources.resolve import Resolver

if TYPE_CHECKING:
    from urdflint.engine.config import Settings


@dataclass
class Context:
    """Run-wide state. ``root`` confines every file access (the HTTP service sets it).

    ``package_paths`` come from the command line and win over the configuration's, which
    win over ``workspace``: the packages found below the checked paths and their git root
    (see :mod:`urdflint.sources.workspace`).
    The mesh cache is created on first use, so a run whose rules read no mesh never
    imports trimesh.
    """

    package_paths: dict[str, Path] = field(default_factory=dict)
    root: Path | None = None
    environ: Mapping[str, str] | None = None
    q: dict[str, float] = field(default_factory=dict)
    workspace: Mapping[str, Path] = field(default_factory=dict)  # may be found lazily
    overlay: Mapping[str, bytes] = field(default_factory=dict)  # absolute path -> unsaved text
    cache: Any = None  # the analysis cache (urdflint.cache.Cache), None: nothing is kept
    _meshes: Any = None

    def resolver(self, base_dir: Path | None, settings: Settings) -> Resolver:
        paths = {**settings.package_paths, **self.package_paths}
        return Resolver(
            base_dir, paths, root=self.root, environ=self.environ, workspace=self.workspace
        )

    @property
    def meshes(self) -> Any:
        """The run's :class:`urdflint.meshes.MeshCache` (imports trimesh lazily)."""
        if self._meshes is None:
            from urdflint.sources.meshes import MeshCache

            self._meshes = MeshCache(root=self.root, cache=self.cache)
        return self._meshes
