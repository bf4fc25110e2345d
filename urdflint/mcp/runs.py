"""One lint as ``urdflint check`` does it, confined to the client's roots.

The tools' options become the namespace :class:`urdflint.engine.options.SettingsFinder`
reads (the CLI's ``--target``, ``--select``, ``--ignore``, ``--xacro-arg``, ``--q``), so the
settings, and with them the findings, are the CLI's. What differs is confinement: each file
is linted with its root as the context's ``root`` (the HTTP service's mechanism), a
workspace of the packages below that root only, no environment for xacro, and the nearest
configuration file looked for up to the root, never above it.

The steps of a ``check`` run (:func:`check`) follow ``urdflint/cli/check.py``, which this
layer may not import (tests/test_architecture.py): folders expanded and xacro libraries
replaced by their entry files (:mod:`urdflint.sources.discovery`), a ``*.urdf`` fragment
given one X011 note (as ``urdflint/cli/fragments.py``), each file linted as
``urdflint/cli/parallel.py``'s ``lint_one`` does it (``--matrix``: every target's row), then
the notes across files, the U004 note and the order of ``check._finish``.
"""

from __future__ import annotations

import argparse
import os
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from urdflint import __version__
from urdflint.engine import config, linter, options
from urdflint.engine.context import Context
from urdflint.engine.options import SettingsFinder
from urdflint.mcp.roots import Place, Refused, Roots
from urdflint.model.finding import Finding
from urdflint.sources import workspace


@dataclass
class Request:
    """What a model tool was asked: files (or one text under a name), settings, roots."""

    roots: Roots
    places: list[Place]
    finder: SettingsFinder
    package_paths: dict[str, Path] = field(default_factory=dict)
    overlay: dict[str, bytes] = field(default_factory=dict)  # a text given instead of a file
    contexts: dict[Path, Context] = field(default_factory=dict)  # one per root

    @property
    def is_text(self) -> bool:
        return bool(self.overlay)

    def context(self, root: Path) -> Context:
        if root not in self.contexts:
            self.contexts[root] = Context(
                package_paths=self.package_paths,
                root=root,
                environ={},  # $(env) and $(optenv) see nothing, as in the service
                workspace=RootPackages([root]),
                overlay=self.overlay,
            )
        return self.contexts[root]


@dataclass
class Run:
    """What linting the request's files produced (``urdflint/cli/check.py``'s ``Run``)."""

    findings: list[Finding] = field(default_factory=list)
    checked: list[str] = field(default_factory=list)
    models: dict[str, Any] = field(default_factory=dict)
    ran: dict[str, tuple[str, ...]] = field(default_factory=dict)
    skipped: dict[str, tuple[str, ...]] = field(default_factory=dict)
    targets: dict[str, Any] = field(default_factory=dict)
    matrix: list[dict[str, Any]] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)
    fail_on: str = "error"
    expects: bool = False


class RootPackages(workspace.Packages):
    """The packages below the root (the CLI's workspace also walks up to the git root)."""

    def _discover(self) -> list[tuple[str, str]]:
        found = workspace.packages_below(self.paths).every
        inside = [(name, folder) for name, folder in found if _under(folder, self.paths)]
        return sorted(((name, str(folder)) for name, folder in inside), key=lambda p: p[0])


def _under(folder: Path, roots: tuple[Path, ...]) -> bool:
    """Whether ``folder`` is inside one of ``roots`` once links are resolved."""
    real = Path(os.path.realpath(folder))
    return any(real.is_relative_to(root) for root in roots)


class Finder(SettingsFinder):
    """The CLI's settings for a folder, from the nearest configuration file inside its root."""

    def __init__(self, args: argparse.Namespace, roots: Roots) -> None:
        super().__init__(args)
        self.roots = roots

    def for_folder(self, folder: Path) -> config.Settings:
        folder = folder.resolve()
        if folder not in self.cache:
            found = nearest_config(folder, self.roots.containing(folder))
            try:
                self.cache[folder] = config.load(found) if found else config.Settings()
            except config.ConfigError as exc:
                raise Refused(str(exc)) from None
        return self._apply(self.cache[folder])


def nearest_config(folder: Path, root: Path | None) -> Path | None:
    """:func:`urdflint.engine.config.discover`, stopping at ``root``."""
    import tomllib

    for level in (folder, *folder.parents):
        if root is None or not level.is_relative_to(root):
            return None
        for name in config.FILENAMES:
            candidate = level / name
            if not candidate.is_file():
                continue
            if name != "pyproject.toml":
                return candidate
            try:
                with candidate.open("rb") as handle:
                    if "urdflint" in tomllib.load(handle).get("tool", {}):
                        return candidate
            except (OSError, tomllib.TOMLDecodeError):
                continue
    return None


# -- the request -----------------------------------------------------------------------------


def request(arguments: Mapping[str, Any], roots: Roots, command: str = "check") -> Request:
    """The files and settings ``arguments`` name (:mod:`.schemas`), checked against the roots."""
    try:
        finder = Finder(namespace(arguments, command), roots)
    except options.UsageError as exc:
        raise Refused(str(exc).replace("--", "", 1)) from None
    packages = {  # named as the CLI names them: relative to the working directory if below it
        str(name): Path(roots.place(str(folder)).shown)
        for name, folder in _mapping(arguments, "package_paths").items()
    }
    text, name = arguments.get("text"), arguments.get("name")
    if text is not None:
        if not isinstance(text, str) or not isinstance(name, str) or not name.strip():
            raise Refused("a text needs its file name (name), e.g. robot.urdf")
        place = roots.place(name, must_exist=False)
        overlay = {os.path.abspath(place.path): text.encode("utf-8")}
        return Request(roots, [place], finder, packages, overlay)
    given = arguments.get("paths", arguments.get("path"))
    paths = [given] if isinstance(given, str) else list(given or [])
    if not paths or not all(isinstance(p, str) for p in paths):
        raise Refused("give paths (files or folders), or a text and its name")
    return Request(roots, [roots.place(p) for p in paths], finder, packages)


def namespace(arguments: Mapping[str, Any], command: str) -> argparse.Namespace:
    """The tool's options as the CLI's ``check`` (or ``info``) options."""
    targets = _strings(arguments, "targets")
    try:
        chosen = [options.target_list(",".join(targets))] if targets else []
    except argparse.ArgumentTypeError as exc:
        raise Refused(f"targets: {exc}") from None
    q = {str(k): v for k, v in _mapping(arguments, "q").items()}
    if not all(isinstance(v, int | float) and not isinstance(v, bool) for v in q.values()):
        raise Refused("q: each joint position is a number")
    return argparse.Namespace(
        command=command,
        select=[_strings(arguments, "select")] if arguments.get("select") else [],
        ignore=[_strings(arguments, "ignore")] if arguments.get("ignore") else [],
        target=chosen,
        xacro_arg=[(str(k), _text(v)) for k, v in _mapping(arguments, "xacro_args").items()],
        q=list(q.items()),
        exit_zero=False,
        fail_on=None,
        confirm=[],
        isolated=False,
        config=None,
    )


def _strings(arguments: Mapping[str, Any], key: str) -> list[str]:
    value = arguments.get(key) or []
    value = [value] if isinstance(value, str) else value
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise Refused(f"{key}: expected a list of strings")
    return [part.strip() for v in value for part in v.split(",") if part.strip()]


def _mapping(arguments: Mapping[str, Any], key: str) -> dict[str, Any]:
    value = arguments.get(key) or {}
    if not isinstance(value, dict):
        raise Refused(f"{key}: expected an object")
    return value


def _text(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


# -- the run -----------------------------------------------------------------------------


def check(req: Request, matrix: bool = False) -> Run:
    """Lint the request's files as ``urdflint check [--matrix]`` does."""
    from urdflint.engine import instances
    from urdflint.outputs import report

    run = Run()
    for place, fragment in files(req, run.errors):
        settings = req.finder.for_folder(place.path.parent)
        if fragment is None:
            lint_one(place, settings, req.context(place.root), matrix, run)
        else:
            lint_fragment(place, fragment, settings, req.context(place.root), run)
    findings = instances.across_files(run.findings) if len(run.checked) > 1 else run.findings
    here = req.finder.for_folder(req.places[0].root)  # the CLI: the current folder's settings
    if run.skipped and run.checked:
        gate = run.expects and bool({"P003", "P004"} & set(run.skipped))
        if gate or "U004" in here.enabled():
            findings.append(report.skipped_note(run.checked[0], run.skipped, run.expects))
    findings.sort(key=Finding.sort_key)
    run.findings = findings
    return run


def files(req: Request, errors: list[str]) -> list[tuple[Place, str | None]]:
    """Each file to lint, and why it is a fragment (``None``: a robot): folders expanded,
    xacro libraries replaced by their entry files, anything outside the roots left out."""
    from urdflint.sources import discovery

    if req.is_text:
        return [(req.places[0], None)]
    found: list[tuple[Place, str | None]] = []
    for place in req.places:
        packages = req.context(place.root).workspace
        for name in discovery.as_entries(_expanded(req, place, errors), packages):
            try:
                chosen = req.roots.place(os.path.abspath(name))
            except Refused as exc:
                errors.append(str(exc))
                continue
            found.append((chosen, discovery.fragment(chosen.path)))
    unique = {os.path.abspath(p.path): (p, why) for p, why in found}
    return list(unique.values())


def _expanded(req: Request, place: Place, errors: list[str]) -> list[str]:
    """``discovery.collect`` for one path, a folder's files taken only inside the roots (a
    link below it may lead out): none outside is read, not even to find its includes."""
    from urdflint.sources import discovery

    if not place.path.is_dir():
        names, problems = discovery.collect([str(place.path)])
        errors.extend(problems)
        return names
    urdfs, xacros = discovery._below(place.path)

    def inside(paths: list[Path]) -> list[Path]:
        kept = [path for path in paths if req.roots.containing(path) is not None]
        errors.extend(f"{p}: outside the allowed roots" for p in paths if p not in kept)
        return kept

    packages = req.context(place.root).workspace
    return [str(p) for p in sorted(discovery.entries(inside(xacros), packages, inside(urdfs)))]


def lint_one(place: Place, settings: Any, context: Context, matrix: bool, run: Run) -> None:
    """One file, as ``lint_one`` of ``urdflint/cli/parallel.py`` (no analysis cache)."""
    from urdflint.engine import matrix as rows
    from urdflint.outputs import report

    def lint(chosen: Any) -> linter.Result:  # the path as the CLI has it (meshes are named so)
        return linter.lint_path(Path(place.shown), place.shown, chosen, context)

    try:
        result = lint(settings)
    except OSError as exc:
        run.errors.append(f"{place.shown}: cannot read: {exc.strerror or exc}")
        return
    doc = result.document
    built = doc is not None and doc.root is not None
    if matrix and built:
        chosen = result.targets.names if result.targets else settings.targets
        found = rows.every_target(
            result.findings, replace(settings, targets=chosen), lambda s: lint(s).findings
        )
        run.matrix.extend({"path": place.shown, **row} for row in found)
    run.checked.append(place.shown)
    run.ran[place.shown] = result.ran
    run.findings.extend(result.findings)
    run.skipped.update(result.skipped)
    run.fail_on = settings.fail_on
    expect = settings.expect
    run.expects = run.expects or expect.mass is not None or expect.com is not None
    run.models[place.shown] = report.model_summary(result)
    if result.targets and built:
        run.targets[place.shown] = result.targets.to_dict()


def lint_fragment(place: Place, why: str, settings: Any, context: Context, run: Run) -> None:
    """A ``*.urdf`` fragment nobody includes: its X011 note (``urdflint/cli/fragments.py``)."""
    from urdflint.model.document import Document
    from urdflint.model.parsing import XmlProblem

    message = (
        f"a fragment of a robot, not checked on its own: {why}, and no file found includes it"
        " (its findings appear where the file that includes it is checked)"
    )
    doc = Document(
        place.shown,
        place.path.read_bytes(),
        targets=frozenset(settings.targets),
        settings=settings,
        context=context,
        base_dir=Path(place.shown).parent,
        problem=XmlProblem("X011", message),
        library=True,
    )
    result = linter.lint_document(doc, settings)
    run.checked.append(place.shown)
    run.ran[place.shown] = result.ran
    run.findings.extend(result.findings)


def envelope(run: Run) -> dict[str, Any]:
    """``urdflint check --format json``'s document for the run."""
    from urdflint.outputs.formatters import json as formatter

    return formatter.document(run.findings, info(run))


def info(run: Run) -> Any:
    from urdflint.outputs.formatters.run import RunInfo

    return RunInfo(
        __version__,
        tuple(run.checked),
        run.models,
        run.fail_on,
        run.ran,
        show_info=run.fail_on == "info",  # the CLI's default: infos in one line
        matrix=tuple(run.matrix),
        targets=run.targets,
    )
