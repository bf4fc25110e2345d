"""Xacro input: expand ``*.xacro`` in-process with the PyPI ``xacro`` package, no ROS needed.

``document()`` returns the expanded :class:`~urdflint.document.Document`. What it adds
to plain xacro:

- ``$(find pkg)`` resolves through urdflint's package paths (``--package-path``, the
  configuration's ``package-paths``, ``ROS_PACKAGE_PATH``, ``AMENT_PREFIX_PATH``, a
  ``package.xml`` upward search), the same as ``package://`` meshes;
- xacro's global state is reset for every file and its console output is captured,
  so several files in one run do not leak into each other and stdout stays a report;
- every file xacro opens is refused when it declares a DOCTYPE or entities (X002),
  is over 64 MiB, or (with ``context.root`` set, the HTTP service) lies outside the
  root; in that confined mode the environment is hidden from ``$(env)``/``$(optenv)``
  and the expression evaluator refuses the known ways out of its sandbox;
- an expansion error (undefined property, missing include, bad XML in an include,
  runaway recursion...) becomes one X010 finding instead of a traceback; a file that
  only fails because it is a fragment of another file (it uses names its includer
  defines) is a library (X011), and so is a file with no ``<link>`` after expansion;
- ``Document.origin`` maps each element of the expanded document back to the line
  of the source file where it is written literally (see :class:`LineMap`).
"""

from __future__ import annotations

import bisect
import contextlib
import html
import io
import logging
import os
import re
import threading
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from functools import cache, cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any

from lxml import etree

from urdflint.model.document import MAX_BYTES, Document, Origin, XmlProblem, children

if TYPE_CHECKING:
    from urdflint.engine.config import Settings
    from urdflint.engine.context import Context

log = logging.getLogger(__name__)

# xacro keeps its state in module globals: one expansion at a time per process.
_LOCK = threading.Lock()
MAX_MACRO_CALLS = 20_000  # a macro "billion laughs" stops here
MAX_TOTAL_BYTES = MAX_BYTES  # everything xacro reads for one file, includes and YAML together
FRAGMENT_SCAN_FILES = 2000
FRAGMENT_SUFFIXES = (".xacro", ".urdf", ".gazebo", ".trans", ".xml")

# The extra names refused in confined mode: each is a step of a known way out of
# xacro's expression sandbox (type/vars/mro reach every class, str.format reads
# attributes named in a string, generator and frame attributes reach module globals).
CONFINED_DENY = frozenset(
    {
        "vars", "type", "mro", "format", "format_map", "getattr", "setattr", "delattr",
        "globals", "locals", "dir", "eval", "exec", "compile", "open", "breakpoint", "input",
        "gi_frame", "gi_code", "gi_yieldfrom", "cr_frame", "cr_code", "ag_frame", "ag_code",
        "f_back", "f_globals", "f_locals", "f_builtins", "f_code", "tb_frame", "tb_next",
        "func_globals",
    }
)  # fmt: skip

BLANK_RE = re.compile(r"<!--.*?-->|<!\[CDATA\[.*?\]\]>|<\?.*?\?>", re.S)
BLANK_BYTES_RE = re.compile(rb"<!--.*?-->|<!\[CDATA\[.*?\]\]>", re.S)
TAG_RE = re.compile(
    r"<(?P<end>/)?(?P<tag>[A-Za-z_][\w.:-]*)"
    r"(?P<attrs>(?:\s+[^\s=/>]+\s*=\s*(?:\"[^\"]*\"|'[^']*'))*)\s*(?P<empty>/)?>"
)
ATTR_RE = re.compile(r"([^\s=/>]+)\s*=\s*(?:\"([^\"]*)\"|'([^']*)')")
EXPR_RE = re.compile(r"when evaluating expression '(.*)'\s*$", re.S)
CLASS_RE = re.compile(r"<class '[\w.]+'>:\s*")
YAML_MARK_RE = re.compile(r"\s*in \"<[^>]*>\", line \d+, column \d+")
TRANSPARENT = frozenset({"xacro:if", "xacro:unless"})  # literal children pass through


# -- the literal source ---------------------------------------------------------------


@dataclass(eq=False)
class Lit:
    """One start tag written in a source file, with its literal children."""

    tag: str
    attrs: dict[str, str]
    line: int
    column: int
    empty: bool
    source: Source
    parent: Lit | None = None
    children: list[Lit] = field(default_factory=list)

    def top_level(self) -> bool:
        """Written directly under ``<robot>``, possibly inside xacro macros or conditions."""
        node = self.parent
        if node is None or self.tag.startswith("xacro:"):
            return False
        while node is not None:
            if node.tag != "robot" and not node.tag.startswith("xacro:"):
                return False
            node = node.parent
        return True

    def effective_children(self) -> Iterator[Lit]:
        """Children as they appear after expansion, when written literally."""
        for child in self.children:
            if child.tag in TRANSPARENT:
                yield from child.effective_children()
            elif not child.tag.startswith("xacro:"):
                yield child


@dataclass(eq=False)
class Source:
    """One XML file xacro read: the main file or an include."""

    path: str  # absolute and normalised
    shown: str  # as findings name it
    text: str
    chain: tuple[str, ...]  # the include chain, main file first, this file last

    @cached_property
    def blanked(self) -> str:
        """The text with comments, CDATA and processing instructions blanked out."""
        return BLANK_RE.sub(lambda m: re.sub(r"[^\n]", " ", m.group()), self.text)

    @cached_property
    def _starts(self) -> list[int]:
        return [0, *(m.end() for m in re.finditer(r"\n", self.text))]

    def position(self, offset: int) -> tuple[int, int]:
        """1-based line and column of a character offset."""
        line = bisect.bisect_right(self._starts, offset)
        return line, offset - self._starts[line - 1] + 1

    @cached_property
    def lits(self) -> list[Lit]:
        """Every literal start tag, in document order, linked into a tree."""
        found: list[Lit] = []
        stack: list[Lit] = []
        for match in TAG_RE.finditer(self.blanked):
            tag = match.group("tag")
            if match.group("end"):
                while stack:
                    if stack.pop().tag == tag:
                        break
                continue
            line, column = self.position(match.start())
            attrs = {
                m.group(1): _attr_value(m.group(2) if m.group(2) is not None else m.group(3))
                for m in ATTR_RE.finditer(match.group("attrs"))
            }
            parent = stack[-1] if stack else None
            lit = Lit(tag, attrs, line, column, bool(match.group("empty")), self, parent)
            if parent is not None:
                parent.children.append(lit)
            found.append(lit)
            if not lit.empty:
                stack.append(lit)
        return found

    def find(self, needle: str) -> tuple[int, int] | None:
        index = self.blanked.find(needle)
        return self.position(index) if index >= 0 else None


def _attr_value(raw: str) -> str:
    return html.unescape(re.sub(r"[\t\n\r]", " ", raw))


def _qname(el: etree._Element) -> str:
    tag = el.tag
    if not isinstance(tag, str):
        return ""
    if tag.startswith("{"):
        local = tag.split("}", 1)[1]
        return f"{el.prefix}:{local}" if el.prefix else local
    return tag


def _key(tag: str) -> str:
    return "reference" if tag == "gazebo" else "name"


def _compatible(lit: Lit, el: etree._Element) -> bool:
    """The literal tag could have produced ``el``: same plain attributes, same literal values."""
    if lit.empty and len(children(el)):
        return False
    written = {k: v for k, v in lit.attrs.items() if ":" not in k}
    expanded = {k: v for k, v in el.attrib.items() if not k.startswith("{")}
    if set(written) != set(expanded):
        return False
    return all(expanded[k] == v for k, v in written.items() if "$" not in v)


# -- line mapping ---------------------------------------------------------------------


class LineMap:
    """Maps an element of the expanded document to where it is written.

    The element's anchor is its ancestor-or-self directly under ``<robot>`` (a link,
    joint, material, gazebo block, transmission). The anchor is looked up among the
    literal start tags of every file xacro read, by tag and ``name`` (``reference`` for
    ``<gazebo>``): exactly one compatible literal must exist, written outside any
    non-xacro element. From there the path down to the element is followed through
    the literal children (``xacro:if``/``xacro:unless`` are transparent), and each step
    must find as many literal siblings of that tag as the expansion has. Anything
    produced by a macro or named with ``${...}`` is not traceable: it gets the line of
    the expanded document, marked not exact.
    """

    def __init__(self, sources: list[Source], shown: str, expanded: bytes) -> None:
        self.sources = sources
        self.shown = shown
        self.expanded = expanded

    @cached_property
    def _index(self) -> dict[tuple[str, str | None], list[Lit]]:
        index: dict[tuple[str, str | None], list[Lit]] = {}
        for source in self.sources:
            for lit in source.lits:
                if lit.top_level():
                    value = lit.attrs.get(_key(lit.tag))
                    if value is None or "$" not in value:
                        index.setdefault((lit.tag, value), []).append(lit)
        return index

    @cached_property
    def _root(self) -> Lit | None:
        main = self.sources[0] if self.sources else None
        if main is None:
            return None
        return next((lit for lit in main.lits if lit.parent is None), None)

    @cached_property
    def _expanded_lines(self) -> list[bytes]:
        return self.expanded.splitlines()

    def __call__(self, el: etree._Element) -> Origin | None:
        lit = self.literal(el)
        if lit is not None:
            return Origin(lit.source.shown, lit.line, lit.column, exact=True)
        if isinstance(el, etree._Comment):
            found = self._comment(el)
            if found is not None:
                return found
        line = el.sourceline
        if not line:
            return None
        return Origin(self.shown, line, self._expanded_column(el, line), exact=False)

    def literal(self, el: etree._Element) -> Lit | None:
        """The literal start tag ``el`` was expanded from, when it can be traced."""
        if not isinstance(el.tag, str):
            return None
        anchor = el
        steps: list[etree._Element] = []
        while anchor.getparent() is not None and anchor.getparent().getparent() is not None:
            steps.append(anchor)
            anchor = anchor.getparent()
        if anchor.getparent() is None:
            return self._root if self._root is not None and self._root.tag == _qname(el) else None
        tag = _qname(anchor)
        candidates = [
            lit
            for lit in self._index.get((tag, anchor.get(_key(tag))), [])
            if _compatible(lit, anchor)
        ]
        if len(candidates) != 1:
            return None
        current = candidates[0]
        for node in reversed(steps):
            parent = node.getparent()
            same = [c for c in parent if c.tag == node.tag]
            written = [c for c in current.effective_children() if c.tag == _qname(node)]
            if len(written) != len(same):
                return None
            current = written[same.index(node)]
            if not _compatible(current, node):
                return None
        return current

    def _comment(self, el: etree._Element) -> Origin | None:
        needle = f"<!--{el.text}-->"
        hits = [(source, index) for source in self.sources for index in _all(source.text, needle)]
        if len(hits) != 1:
            return None
        source, index = hits[0]
        line, column = source.position(index)
        return Origin(source.shown, line, column, exact=True)

    def _expanded_column(self, el: etree._Element, line: int) -> int:
        if not 1 <= line <= len(self._expanded_lines):
            return 1
        text = self._expanded_lines[line - 1]
        index = text.find(b"<" + _qname(el).encode()) if isinstance(el.tag, str) else -1
        return len(text[:index].decode("utf-8", "replace")) + 1 if index >= 0 else 1


def _all(text: str, needle: str) -> Iterator[int]:
    start = text.find(needle)
    while start >= 0:
        yield start
        start = text.find(needle, start + 1)


# -- expansion --------------------------------------------------------------------------


def document(path: Path, shown: str, settings: Settings, context: Context) -> Document:
    """``path`` expanded by xacro, as a document whose findings name ``shown``."""
    expansion = Expansion(path, shown, settings, context)
    outcome = expansion.run()
    common: dict[str, Any] = {
        "targets": frozenset(settings.targets),
        "settings": settings,
        "context": context,
        "base_dir": path.parent,
    }
    if isinstance(outcome, XmlProblem):
        return Document(shown, b"", problem=outcome, library=outcome.code == "X011", **common)
    doc = Document(shown, outcome, origin=LineMap(expansion.sources, shown, outcome), **common)
    if doc.ok and not children(doc.robot, "link"):
        doc.library = True
    return doc


@cache
def _refusal_class(xacro: Any) -> type:
    class Refused(xacro.XacroException):
        """A file urdflint will not let xacro read, or cannot read: a clean message."""

        def __init__(
            self,
            code: str,
            message: str,
            path: str | None = None,
            line: int | None = None,
            column: int | None = None,
            exc: BaseException | None = None,
            needle: str | None = None,
        ) -> None:
            super().__init__(message, exc=exc)
            self.code, self.message, self.path = code, message, path
            self.line, self.column, self.needle = line, column, needle

        def __str__(self) -> str:
            return self.message

    return Refused


class _Glob:
    """``glob`` for xacro's include patterns that never answers outside the root."""

    def __init__(self, inside: Callable[[str], bool]) -> None:
        self.inside = inside

    def glob(self, pattern: str, *args: Any, **kwargs: Any) -> list[str]:
        import glob

        return [p for p in glob.glob(pattern, *args, **kwargs) if self.inside(p)]


_MISSING = object()


class Expansion:
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
        self.macro_calls = 0
        self.last_yaml: str | None = None
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
                "cannot expand xacro files: the xacro package is not installed "
                "(pip install 'urdflint[xacro]')",
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
        x.process_doc(dom, mappings=dict(self.settings.xacro_args), verbosity=1)
        name = re.sub(r"-+", "-", self.shown)
        banner = dom.createComment(
            f" expanded by urdflint with xacro from {name}; findings marked"
            " 'line N of the expanded document' refer to this text "
        )
        dom.insertBefore(banner, dom.firstChild)
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
        put(x, "handle_macro_call", self._counting(x.handle_macro_call))
        put(sa, "_eval_find", self._find)
        put(sa, "_eval_env", self._env)
        put(sa, "_eval_optenv", self._optenv)
        sa._eval_dict.update(find=self._find, env=self._env, optenv=self._optenv)
        if self.root is not None:
            put(x, "glob", _Glob(self.inside))
            put(x, "safe_eval", self._confined_eval(x.safe_eval))
            put(x, "eval_extension", self._confined_extension(x.eval_extension))
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
        refused = _refusal_class(self.x)
        shown = self.shown_path(full)
        if not self.inside(full):
            raise refused("X010", f"{shown} is outside the allowed folder", needle=_base(full))
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
        import xml.dom.minidom
        from xml.parsers.expat import ExpatError

        x = self.x
        if inp is not None or filename is None:
            raise TypeError("urdflint's xacro parse only reads files")
        full = os.path.abspath(os.path.join(x.root_dir, filename))
        is_main = full == self.main
        try:
            data = self._read(full)
        except x.XacroException:
            if x.filestack:
                x.filestack.pop()  # as xacro does: the missing file is not "in file"
            raise
        refused = _refusal_class(x)
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
            dom = xml.dom.minidom.parseString(data)
        except ExpatError as exc:
            reason = str(exc).split(": line ")[0]
            code = "X001" if is_main else "X010"
            raise refused(code, f"XML error: {reason}", full, exc.lineno, exc.offset + 1) from None
        text = data.decode("utf-8", "replace")
        if self.source(full) is None:
            chain = tuple(os.path.abspath(f) for f in (x.filestack or []) if f)
            self.sources.append(Source(full, shown, text, chain or (full,)))
        return dom

    def _open(self, file: Any, mode: str = "r", *args: Any, **kwargs: Any) -> Any:
        """``open`` for ``xacro.load_yaml``: confined and size-limited like includes."""
        full = os.path.abspath(os.fspath(file))
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

        try:
            return self.environ[name]
        except KeyError:
            exc = SubstitutionException(f"environment variable {name} is not set")
            exc.needle = f"$(env {name})"  # type: ignore[attr-defined]
            raise exc from None

    def _optenv(self, name: str, default: str = "") -> str:
        return self.environ.get(name, default)

    def _counting(self, original: Callable[..., Any]) -> Callable[..., Any]:
        def handle_macro_call(node: Any, macros: Any, symbols: Any) -> Any:
            if node.tagName.startswith("xacro:"):
                self.macro_calls += 1
                if self.macro_calls > MAX_MACRO_CALLS:
                    raise _refusal_class(self.x)(
                        "X010",
                        f"more than {MAX_MACRO_CALLS} macro calls: runaway recursion or an"
                        " expansion bomb",
                    )
            return original(node, macros, symbols)

        return handle_macro_call

    def _confined_eval(self, original: Callable[..., Any]) -> Callable[..., Any]:
        refused = _refusal_class(self.x)

        def vet(code: Any) -> None:
            for name in code.co_names:
                if name.startswith("_") or name in CONFINED_DENY:
                    raise refused(
                        "X010", f"the expression uses '{name}', which is not allowed here"
                    )
            for const in code.co_consts:
                if isinstance(const, str) and "__" in const:
                    raise refused(
                        "X010", "the expression uses a string with '__', not allowed here"
                    )
                if hasattr(const, "co_names"):
                    vet(const)

        def safe_eval(expr: str, globals: Any, locals: Any = None) -> Any:
            vet(compile(expr.strip(), "<expression>", "eval"))
            return original(expr, globals, locals)

        return safe_eval

    def _confined_extension(self, original: Callable[[str], Any]) -> Callable[[str], Any]:
        def eval_extension(s: str) -> Any:
            return "." if s == "$(cwd)" else original(s)

        return eval_extension

    # -- errors --------------------------------------------------------------------------

    def _problem(self, exc: BaseException) -> XmlProblem:
        x = self.x
        refused_cls = _refusal_class(x)
        chain = list(_chain(exc))
        refused: Any = next((e for e in chain if isinstance(e, refused_cls)), None)
        filestack = [os.path.abspath(f) for f in (x.filestack or []) if f]
        macrostack = list(x.macrostack or [])
        here = filestack[-1] if filestack else self.main
        macro = None
        if macrostack:
            macro = macrostack[-1].body.getAttribute("name") or None
            history = macrostack[-1].history
            if history and history[-1] and history[-1][-1]:
                here = os.path.abspath(history[-1][-1])
        if refused is not None and refused.path is not None:
            code, message = refused.code, refused.message
            path, line, column = refused.path, refused.line, refused.column
        else:
            code = refused.code if refused is not None else "X010"
            message = refused.message if refused is not None else _describe(exc)
            if macro and refused is None and f"'{macro}'" not in message:
                message += f" in macro '{macro}'"
            needle = (refused.needle if refused is not None else None) or _needle(chain)
            if needle is None and macro:
                needle = f"<xacro:{macro}"
            path, line, column = self._locate(needle, here)
            message += self._yaml_where(chain)
        if code == "X010" and self._is_fragment(chain):
            includer = self._includer()
            if includer is not None:
                at = (line or 1, column or 1) if path == self.main else (1, 1)
                return XmlProblem(
                    "X011",
                    f"not expanded on its own ({_sentence(message)}): it is a fragment of"
                    f" {includer}, which includes it and is where it is checked",
                    *at,
                )
        message = _sentence(message)
        if path is None or path == self.main:
            return XmlProblem(code, message, line or 1, column or 1)
        where = self.shown_path(path) + (f" line {line}" if line else "")
        if where not in message:
            message += f" (in {where})"
        line, column = self._include_line(path, filestack)
        return XmlProblem(code, message, line, column)

    def _yaml_where(self, chain: list[BaseException]) -> str:
        """`` (in FILE line N)`` for a YAML error in a file read by ``xacro.load_yaml``."""
        mark = next((getattr(e, "problem_mark", None) for e in chain if _is_yaml_error(e)), None)
        if self.last_yaml is None or not any(_is_yaml_error(e) for e in chain):
            return ""
        line = f" line {mark.line + 1}" if mark is not None else ""
        return f" (in {self.shown_path(self.last_yaml)}{line})"

    def _locate(self, needle: str | None, preferred: str) -> tuple[str, int | None, int | None]:
        """The first literal occurrence of ``needle``, in ``preferred`` first."""
        if needle:
            first = self.source(preferred)
            ordered = ([first] if first else []) + [s for s in self.sources if s is not first]
            for source in ordered:
                found = source.find(needle)
                if found is not None:
                    line, column = found
                    for lit in source.lits:  # a file name: point at its <xacro:include>
                        if lit.line == line and lit.tag == "xacro:include" and lit.column < column:
                            column = lit.column
                    return source.path, line, column
        return preferred, None, None

    def _include_line(self, path: str, filestack: list[str]) -> tuple[int, int]:
        """Where the main file includes the file that (eventually) includes ``path``."""
        source = self.source(path)
        main = self.source(self.main)
        chain = source.chain if source is not None else tuple(filestack)
        if main is None or len(chain) < 2 or chain[0] != self.main:
            return 1, 1
        top = _base(chain[1])
        for lit in main.lits:
            if lit.tag == "xacro:include" and lit.attrs.get("filename", "").endswith(top):
                return lit.line, lit.column
        return 1, 1

    # -- fragments -------------------------------------------------------------------------

    def _is_fragment(self, chain: list[BaseException]) -> bool:
        """The failure is a name that an including file would define."""
        from xacro.substitution_args import ArgException

        for exc in chain:
            if isinstance(exc, NameError | ArgException):
                return True
            text = str(exc.args[0]) if exc.args else ""
            if text.startswith(("unknown macro name", "Undefined block", "Undefined property")):
                return True
        return False

    def _includer(self) -> str | None:
        """Another file of the package that includes this one, if any (bounded search)."""
        main = Path(self.main)
        base = main.parent
        for ancestor in list(main.parents)[:4]:
            if (ancestor / "package.xml").is_file():
                base = ancestor
                break
        if not self.inside(str(base)):
            base = main.parent
        pattern = re.compile(
            rb"<xacro:include\b[^>]*?\bfilename\s*=\s*[\"'](?:[^\"']*/)?"
            + re.escape(main.name.encode())
            + rb"[\"']"
        )
        scanned = 0
        for dirpath, dirnames, filenames in os.walk(base):
            dirnames[:] = sorted(d for d in dirnames if not d.startswith("."))
            for name in sorted(filenames):
                if not name.endswith(FRAGMENT_SUFFIXES) or name == "package.xml":
                    continue
                candidate = os.path.join(dirpath, name)
                if os.path.abspath(candidate) == self.main or not self.inside(candidate):
                    continue
                scanned += 1
                if scanned > FRAGMENT_SCAN_FILES:
                    return None
                try:
                    if os.path.getsize(candidate) > 2**20:
                        continue
                    with open(candidate, "rb") as handle:
                        if pattern.search(handle.read()):
                            return self.shown_path(candidate)
                except OSError:
                    continue
        return None


def _base(path: str) -> str:
    return os.path.basename(os.path.normpath(path))


def _chain(exc: BaseException | None) -> Iterator[BaseException]:
    """The exception and what it wraps (xacro's ``.exc``, then ``__cause__``), outermost first."""
    seen: set[int] = set()
    while exc is not None and id(exc) not in seen:
        seen.add(id(exc))
        yield exc
        inner = getattr(exc, "exc", None)
        exc = inner if isinstance(inner, BaseException) else exc.__cause__


def _describe(exc: BaseException) -> str:
    """xacro's message, on one line, without class names, repeats and nested contexts."""
    chain = list(_chain(exc))
    if any(isinstance(e, RecursionError) for e in chain):
        return "the expansion recursed too deeply (a macro or property that refers to itself?)"
    parts: list[str] = []
    suffix = ""
    for e in chain:
        if hasattr(e, "suffix"):  # a XacroException: its own text is args[0]
            head = e.args[0] if e.args and isinstance(e.args[0], str) else ""
            suffix = str(e.suffix).strip() if e.suffix else suffix  # the innermost wins
        else:
            head = str(e) or type(e).__name__
        head = YAML_MARK_RE.sub("", CLASS_RE.sub("", head)).strip()
        if head and not (parts and parts[-1].endswith(head)):
            parts.append(head)
    text = " ".join([*parts, suffix])
    return re.sub(r"\s+", " ", text).strip() or type(exc).__name__


def _is_yaml_error(exc: BaseException) -> bool:
    return any(c.__module__.startswith("yaml") for c in type(exc).__mro__)


def _needle(chain: list[BaseException]) -> str | None:
    """A piece of source text that locates the failure."""
    from xacro.substitution_args import ArgException

    for exc in reversed(chain):  # the innermost first
        if isinstance(getattr(exc, "needle", None), str):
            return str(exc.needle)  # type: ignore[attr-defined]
        suffix = getattr(exc, "suffix", None)
        match = EXPR_RE.search(str(suffix)) if suffix else None
        if match:
            return "${" + match.group(1) + "}"
        if isinstance(exc, ArgException) and exc.args:
            return f"$(arg {exc.args[0]})"
        text = str(exc.args[0]) if exc.args else ""
        if text.startswith("unknown macro name: "):
            return "<" + text.removeprefix("unknown macro name: ").strip()
        macros = getattr(exc, "macros", None)
        if macros:
            name = macros[-1].body.getAttribute("name")
            if name:
                return f"<xacro:{name}"
    return None


def _sentence(message: str) -> str:
    """A lower-case start, no trailing period (house style), acronyms kept."""
    message = message.strip().rstrip(".")
    if len(message) > 1 and message[0].isupper() and not message[1].isupper():
        message = message[0].lower() + message[1:]
    return message
