"""One run of xacro over one file, in-process, with urdflint's guards and the source map."""

from __future__ import annotations

import contextlib
import io
import logging
import os
import re
import threading
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from urdflint.cache import deps
from urdflint.model.document import MAX_BYTES, XmlProblem
from urdflint.sources import install_layout
from urdflint.sources.xacro.arguments import Site
from urdflint.sources.xacro.guards import (
    ConfinedGlob,
    confined_eval,
    confined_extension,
    counting,
    refusal_class,
)
from urdflint.sources.xacro.literal import Source
from urdflint.sources.xacro.problems import Problems, _base, _describe, _sentence
from urdflint.sources.xacro.sourcemap import Tracker

if TYPE_CHECKING:
    from urdflint.engine.config import Settings
    from urdflint.engine.context import Context

log = logging.getLogger("urdflint.sources.xacro")

# xacro keeps its state in module globals: one expansion at a time per process.
_LOCK = threading.Lock()
MAX_TOTAL_BYTES = MAX_BYTES  # everything xacro reads for one file, includes and YAML together
BLANK_BYTES_RE = re.compile(rb"<!--.*?-->|<!\[CDATA\[.*?\]\]>", re.S)
_MISSING = object()


class Expansion(Problems):
    """One run of xacro over one file, with urdflint's guards patched in."""

    def __init__(self, path: Path, shown: str, settings: Settings, context: Context) -> None:
        self.main = os.path.abspath(path)
        self.shown = shown
        self.settings = settings
        self.context = context
        self.root = context.root.resolve() if context.root is not None else None
        self.environ: Mapping[str, str] = (
            context.environ
            if context.environ is not None
            else ({} if self.root is not None else os.environ)
        )
        self.sources: list[Source] = []
        self.read_bytes = 0
        self.macro_calls = [0]
        self.tracker = Tracker()
        self.dom: Any = None  # the expanded DOM, marked for the source map
        self.last_yaml: str | None = None
        self.include_site: Site | None = None  # the include being processed, until parsed
        self.x: Any = None

    # -- paths -----------------------------------------------------------------------

    def inside(self, path: str) -> bool:
        if self.root is None:
            return True
        try:
            return Path(path).resolve().is_relative_to(self.root)
        except (OSError, RuntimeError):
            return False

    def shown_path(self, full: str) -> str:
        full = os.path.abspath(full)
        if full == self.main:
            return self.shown
        try:
            rel = os.path.relpath(full, os.path.dirname(self.main))
        except ValueError:  # another drive
            return full
        return os.path.normpath(os.path.join(os.path.dirname(self.shown), rel))

    def source(self, path: str | None) -> Source | None:
        if path is None:
            return None
        full = os.path.abspath(path)
        return next((s for s in self.sources if s.path == full), None)

    # -- the run -----------------------------------------------------------------------

    def run(self) -> bytes | XmlProblem:
        if not self.inside(self.main):
            return XmlProblem("X010", f"{self.shown} is outside the allowed folder")
        try:
            import xacro
        except ImportError:
            return XmlProblem(
                "X010",
                "cannot expand xacro files: the xacro package, a dependency of urdflint, "
                "is not installed (pip install xacro)",
            )
        self.x = xacro
        sink = io.StringIO()
        with _LOCK, contextlib.redirect_stdout(sink), contextlib.redirect_stderr(sink):
            with self._patched():
                try:
                    outcome: bytes | XmlProblem = self._expand()
                except Exception as exc:  # xacro raises anything; never let it escape
                    log.debug("xacro failed on %s", self.shown, exc_info=True)
                    try:
                        outcome = self._problem(exc)
                    except Exception:  # locating the error must not turn it into a crash
                        log.debug("cannot locate the xacro error", exc_info=True)
                        outcome = XmlProblem("X010", _sentence(_describe(exc)))
            self._reset()
        if sink.getvalue().strip():
            log.debug("xacro said on %s:\n%s", self.shown, sink.getvalue())
        return outcome

    def _expand(self) -> bytes | XmlProblem:
        x = self.x
        x.init_stacks(self.main)
        x.all_includes = []
        dom = x.parse(None, self.main)
        x.process_doc(dom, mappings=self.settings.xacro_args_for(self.main), verbosity=1)
        name = re.sub(r"-+", "-", self.shown)
        banner = dom.createComment(
            f" expanded by urdflint with xacro from {name}; findings marked"
            " 'line N of the expanded document' refer to this text "
        )
        dom.insertBefore(banner, dom.firstChild)
        self.dom = dom
        out: bytes = dom.toprettyxml(indent="  ", encoding="utf-8")
        if len(out) > MAX_BYTES:
            return XmlProblem(
                "X010",
                f"the expanded document is {len(out) / 2**20:.0f} MiB, over the 64 MiB limit",
            )
        return out

    def _reset(self) -> None:
        x = self.x
        x.init_stacks(None)
        x.all_includes = []
        x.substitution_args_context.clear()

    @contextlib.contextmanager
    def _patched(self) -> Iterator[None]:
        """Swap xacro's file access, ``$(find)``, environment and evaluator for ours."""
        import xml.dom.minidom as minidom

        x = self.x
        from xacro import substitution_args as sa

        saved: list[tuple[Any, str, Any]] = []
        saved_dict: dict[str, Any] = {k: sa._eval_dict.get(k) for k in ("find", "env", "optenv")}

        def put(obj: Any, name: str, value: Any) -> None:
            saved.append((obj, name, obj.__dict__.get(name, _MISSING)))
            setattr(obj, name, value)

        put(x, "parse", self._parse)
        put(x, "open", self._open)  # load_yaml's open()
        put(x, "root_dir", os.curdir)
        put(x, "verbosity", 1)
        put(
            x,
            "handle_macro_call",
            self.tracker.calling(counting(x, x.handle_macro_call, self.macro_calls)),
        )
        put(x, "process_include", self._including(x.process_include))
        put(minidom, "_clone_node", self.tracker.cloning(minidom._clone_node))  # type: ignore[attr-defined]
        put(sa, "_eval_find", self._find)
        put(sa, "_eval_env", self._env)
        put(sa, "_eval_optenv", self._optenv)
        sa._eval_dict.update(find=self._find, env=self._env, optenv=self._optenv)
        if self.root is not None:
            put(x, "glob", ConfinedGlob(self.inside))
            put(x, "safe_eval", confined_eval(x, x.safe_eval))
            put(x, "eval_extension", confined_extension(x.eval_extension))
        try:
            yield
        finally:
            for obj, name, value in reversed(saved):
                if value is _MISSING:
                    delattr(obj, name)
                else:
                    setattr(obj, name, value)
            sa._eval_dict.update(saved_dict)

    # -- what xacro calls --------------------------------------------------------------

    def _read(self, full: str) -> bytes:
        refused = refusal_class(self.x)
        shown = self.shown_path(full)
        if not self.inside(full):
            raise refused("X010", f"{shown} is outside the allowed folder", needle=_base(full))
        unsaved = self.context.overlay.get(full)  # an editor's buffer (urdflint lsp)
        if unsaved is not None:
            deps.note_content(full, unsaved)
            return unsaved
        try:
            size = os.stat(full).st_size
            if size > MAX_BYTES:
                raise refused("X010", f"{shown} is {size / 2**20:.0f} MiB, over the 64 MiB limit")
            with open(full, "rb") as handle:
                data = handle.read(MAX_BYTES + 1)
        except OSError as exc:
            reason = (exc.strerror or str(exc)).lower()
            message = f"cannot read {shown}: {reason}"
            raise refused("X010", message, exc=exc, needle=_base(full)) from exc
        self.read_bytes += len(data)
        if self.read_bytes > MAX_TOTAL_BYTES:
            raise refused("X010", "the files xacro read add up to over 64 MiB")
        return data

    def _parse(self, inp: Any, filename: str | None = None) -> Any:
        """xacro's ``parse`` for files: guarded reading, DOCTYPE refused, source kept."""
        from xml.parsers.expat import ExpatError

        x = self.x
        if inp is not None or filename is None:
            raise TypeError("urdflint's xacro parse only reads files")
        full = os.path.abspath(os.path.join(x.root_dir, filename))
        if not os.path.exists(full):  # installed there by CMake: read it in the source tree
            deps.note_absent(full)
            full = install_layout.source_file(full) or full
        is_main = full == self.main
        site = self.include_site
        if site is not None:
            site.resolved = os.path.abspath(os.path.join(x.root_dir, filename))
            site.read = full
        try:
            data = self._read(full)
        except x.XacroException:
            if x.filestack:
                x.filestack.pop()  # as xacro does: the missing file is not "in file"
            raise
        refused = refusal_class(x)
        shown = self.shown_path(full)
        stripped = BLANK_BYTES_RE.sub(b"", data)
        for needle in (b"<!DOCTYPE", b"<!ENTITY"):
            if needle in stripped:
                line = data[: data.find(needle)].count(b"\n") + 1 if needle in data else 1
                what = "document" if is_main else "included file"
                raise refused(
                    "X002",
                    f"{what} has a DOCTYPE declaration; URDF never needs one and it is not"
                    " expanded",
                    full,
                    line,
                )
        try:
            dom = self.tracker.parse(data, full, shown)
        except ExpatError as exc:
            reason = str(exc).split(": line ")[0]
            code = "X001" if is_main else "X010"
            raise refused(code, f"XML error: {reason}", full, exc.lineno, exc.offset + 1) from None
        text = data.decode("utf-8", "replace")
        if self.source(full) is None:
            chain = tuple(os.path.abspath(f) for f in (x.filestack or []) if f)
            self.sources.append(Source(full, shown, text, chain or (full,)))
        self.include_site = None  # what goes wrong from here is inside the included file
        return dom

    def _including(self, original: Any) -> Any:
        """xacro's ``process_include``, keeping the include in hand until its file is parsed
        (an error meanwhile is the include's own: its filename or its file)."""

        def process_include(elt: Any, macros: Any, symbols: Any, func: Any) -> Any:
            self.include_site = Site(elt, symbols)
            result = original(elt, macros, symbols, func)
            self.include_site = None  # (an optional include that was not found)
            return result

        return process_include

    def _open(self, file: Any, mode: str = "r", *args: Any, **kwargs: Any) -> Any:
        """``open`` for ``xacro.load_yaml``: confined and size-limited like includes."""
        full = os.path.abspath(os.fspath(file))
        if not os.path.exists(full):
            deps.note_absent(full)
            full = install_layout.source_file(full) or full
        self.last_yaml = full
        data = self._read(full)
        if "b" in mode:
            return io.BytesIO(data)
        return io.StringIO(data.decode(kwargs.get("encoding") or "utf-8", "replace"))

    def _find(self, name: str) -> str:
        from xacro.substitution_args import SubstitutionException

        resolver = self.context.resolver(Path(self.main).parent, self.settings)
        folder, tried = resolver.find_package(name)
        if folder is None:
            looked = "; ".join(tried) if tried else "nowhere"
            exc = SubstitutionException(f"package '{name}' was not found (looked at: {looked})")
            exc.needle = f"$(find {name})"  # type: ignore[attr-defined]
            raise exc
        return os.path.abspath(folder)

    def _env(self, name: str) -> str:
        from xacro.substitution_args import SubstitutionException

        deps.note_env(name, self.environ.get(name))
        try:
            return self.environ[name]
        except KeyError:
            exc = SubstitutionException(f"environment variable {name} is not set")
            exc.needle = f"$(env {name})"  # type: ignore[attr-defined]
            raise exc from None

    def _optenv(self, name: str, default: str = "") -> str:
        deps.note_env(name, self.environ.get(name))
        return self.environ.get(name, default)
