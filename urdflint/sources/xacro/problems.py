"""Why an expansion failed, as one finding at the file and line where the cause is written."""

from __future__ import annotations

import os
import re
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from urdflint.model.document import XmlProblem
from urdflint.sources.xacro.arguments import Arguments
from urdflint.sources.xacro.guards import refusal_class

FRAGMENT_SCAN_FILES = 2000
FRAGMENT_SUFFIXES = (".xacro", ".urdf", ".gazebo", ".trans", ".xml")
EXPR_RE = re.compile(r"when evaluating expression '(.*)'\s*$", re.S)
CLASS_RE = re.compile(r"<class '[\w.]+'>:\s*")
YAML_MARK_RE = re.compile(r"\s*in \"<[^>]*>\", line \d+, column \d+")


class Problems(Arguments):
    """The error side of :class:`~urdflint.sources.xacro.expansion.Expansion`."""

    last_yaml: str | None

    def _problem(self, exc: BaseException) -> XmlProblem:
        x = self.x
        refused_cls = refusal_class(x)
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
        needle = None
        if refused is not None and refused.path is not None:
            code, message = refused.code, refused.message
            path, line, column = refused.path, refused.line, refused.column
            explain = False
        else:
            code = refused.code if refused is not None else "X010"
            message = refused.message if refused is not None else _describe(exc)
            needle = (refused.needle if refused is not None else None) or _needle(chain)
            if needle is None and macro:
                needle = f"<xacro:{macro}"
            # an include that failed is where it is written; otherwise, where the needle is
            path, line, column = self._site_at() or self._locate(needle, here)
            missing = _missing_arg(chain)
            if missing is not None and not self._includer():
                message = self._missing_message(missing, (path, line, column))
            if macro and refused is None and f"'{macro}'" not in message:
                message += f" in macro '{macro}'"
            message += self._yaml_where(chain)
            explain = code == "X010" and missing is None
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
        if explain:  # the arguments behind it
            found = _not_found(chain, refused)
            message = self._explained(message, found, needle, (path, line, column))
        return self._placed(code, _sentence(message), path, line, column, filestack)

    def _placed(
        self,
        code: str,
        message: str,
        path: str | None,
        line: int | None,
        column: int | None,
        filestack: list[str],
    ) -> XmlProblem:
        """The finding at ``path:line:column``, or at the include that leads there."""
        if path is None or path == self.main:
            return XmlProblem(code, message, line or 1, column or 1)
        if line:  # located in an included file: the finding goes there
            return XmlProblem(code, message, line, column or 1, self.shown_path(path))
        where = self.shown_path(path)
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


def _missing_arg(chain: list[BaseException]) -> str | None:
    """The name of an argument used with ``$(arg name)`` that has no value."""
    from xacro.substitution_args import ArgException

    for exc in chain:
        if isinstance(exc, ArgException) and exc.args:
            return str(exc.args[0])
    return None


def _not_found(chain: list[BaseException], refused: Any) -> bool:
    """The failure is a file, package or environment variable that is not there."""
    from xacro.substitution_args import SubstitutionException

    if refused is not None:
        return isinstance(refused.exc, OSError)
    # (urdflint's $(find) and $(env) give the exceptions they raise a needle)
    return any(isinstance(e, SubstitutionException) and hasattr(e, "needle") for e in chain)
