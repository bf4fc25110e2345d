"""What an X010 says about xacro arguments: the argument that is empty or missing behind a
failed include, ``$(find)``, ``$(arg)`` or ``${}``, where its default is declared, the chain
of macros, properties and argument defaults it went through, and how to pass it; or, for a
file or package that is not found, the argument that decides the ``<xacro:if>`` or
``<xacro:unless>`` around the failing element, and the value that skips it."""

from __future__ import annotations

import glob
import logging
import os
import re
from collections.abc import Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from urdflint.sources.xacro.sourcemap import MARK
from urdflint.sources.xacro.tracing import CONDITIONS, Tracer, Use, skip_value, where

if TYPE_CHECKING:
    from urdflint.engine.config import Settings
    from urdflint.sources.xacro.literal import Lit, Source
    from urdflint.sources.xacro.sourcemap import Tracker

log = logging.getLogger("urdflint.sources.xacro")

MARKER = "urdflint{}candidate"  # stands for an argument's value in a trial include path
MAX_CANDIDATES = 4
PASS_HOW = (
    "pass it with --xacro-arg {name}:=VALUE or set it under [tool.urdflint.xacro-args] (for"
    " this file only: [tool.urdflint.per-file-xacro-args])"
)
_MISSING = object()


@dataclass
class Site:
    """The ``<xacro:include>`` xacro is processing, until the file it names is parsed: its
    element, the symbols its filename is evaluated with and the file it resolved to."""

    elt: Any
    symbols: Any
    resolved: str | None = None  # the path xacro asked for
    read: str | None = None  # the path urdflint read (in the source tree, for an install's)


class Arguments:
    """The argument side of :class:`~urdflint.sources.xacro.problems.Problems`."""

    x: Any
    main: str
    shown: str
    sources: list[Source]
    settings: Settings
    tracker: Tracker
    include_site: Site | None

    def source(self, path: str | None) -> Source | None:
        raise NotImplementedError

    def shown_path(self, full: str) -> str:
        raise NotImplementedError

    def inside(self, path: str) -> bool:
        raise NotImplementedError

    # -- where -------------------------------------------------------------------------------

    def _tracer(self) -> Tracer:
        values = self.x.substitution_args_context.get("arg") or {}
        return Tracer(self.sources, values, self.settings.xacro_args_for(self.main), self._params)

    def _params(self, text: str) -> dict[str, tuple[bool, str | None]]:
        found: dict[str, tuple[bool, str | None]] = {}
        rest = text
        while rest.strip() and len(found) < 1000:
            param, spec, rest = self.x.parse_macro_arg(rest)
            forward, default = spec if spec else (None, None)
            found[param] = (forward is not None, default)
        return found

    def _site_lit(self) -> tuple[Lit | None, list[Lit]]:
        """The include being processed, as written, and the macro calls it is expanded in."""
        site = self.include_site
        mark = getattr(site.elt, MARK, None) if site is not None else None
        if mark is None:
            return None, []
        calls: list[Lit] = []
        for _, index, offset in mark[2]:
            call = self._mark_lit(index, offset)
            if call is None:
                break
            calls.append(call)
        return self._mark_lit(mark[0], mark[1]), calls

    def _site_at(self) -> tuple[str, int, int] | None:
        """Where the include being processed is written, when the failure is its own."""
        try:
            lit = self._site_lit()[0]
        except Exception:  # then the needle locates the failure, as without an include
            log.debug("cannot locate the failed include", exc_info=True)
            return None
        return (lit.source.path, lit.line, lit.column) if lit is not None else None

    def _mark_lit(self, index: int, offset: int) -> Lit | None:
        if not 0 <= index < len(self.tracker.files):
            return None
        file = self.tracker.files[index]
        line, column = file.position(offset)
        source = self.source(file.path)
        lits = source.lits if source is not None else []
        return next((lit for lit in lits if (lit.line, lit.column) == (line, column)), None)

    def _lit_at(self, path: str | None, line: int | None, column: int | None) -> Lit | None:
        """The last start tag that begins at or before ``line:column`` of ``path``."""
        source = self.source(path)
        if source is None or line is None:
            return None
        here = (line, column or 1)
        return next((lit for lit in reversed(source.lits) if (lit.line, lit.column) <= here), None)

    # -- messages ----------------------------------------------------------------------------

    def _missing_message(self, name: str, at: tuple[str | None, int | None, int | None]) -> str:
        """``$(arg name)`` has no value: where it is declared, if it is, and how to pass it."""
        decl = self._tracer().declaration(name)
        use = self._lit_at(*at)
        needed = ""
        if use is not None and use.tag == "xacro:arg" and use.attrs.get("name") != name:
            reader = use.attrs.get("name")
            needed = f" (the default of argument '{reader}' at {where(use)} reads it)"
        if decl is None:
            why = "it has no default and was not given; "
        else:
            after = (
                use is not None
                and decl.source is use.source
                and (decl.line, decl.column) > (use.line, use.column)
            )
            default = decl.attrs.get("default", "")
            why = f"it was not given, and its <xacro:arg> (default '{default}' in {where(decl)})"
            if after:
                why += " comes after this use; declare it first, or "
            else:  # in an include or a condition that xacro did not reach before this use
                why += " is not read before this use; "
        entry = os.path.basename(self.shown)
        return (
            f"xacro argument '{name}' has no value when expanding {entry}{needed}: {why}"
            + PASS_HOW.format(name=name)
        )

    def _explained(
        self,
        message: str,
        not_found: bool,
        needle: str | None,
        at: tuple[str | None, int | None, int | None],
    ) -> str:
        """``message`` with the arguments behind the failure, when some are empty, or the
        argument whose condition lets a missing file or package be read."""
        try:
            return self._explain(message, not_found, needle, at)
        except Exception:  # a hint must not cost the finding its place
            log.debug("cannot explain the xacro error by its arguments", exc_info=True)
            return message

    def _explain(
        self,
        message: str,
        not_found: bool,
        needle: str | None,
        at: tuple[str | None, int | None, int | None],
    ) -> str:
        lit, calls = self._site_lit()
        site = self.include_site
        if lit is not None and site is not None:
            text = site.elt.getAttribute("filename")
        else:
            lit, calls = self._lit_at(*at), []
            text = needle if needle and ("${" in needle or "$(arg" in needle) else ""
        empty = _unique(u for u in self._tracer().uses(text, lit, calls) if u.empty)
        values: dict[str, list[str]] = {}
        if empty and site is not None and site.resolved is not None:
            empty, values = self._evidence(site, empty)
        elif not_found:  # a package or variable that is not there: not an empty argument's doing
            empty = []
        if empty:
            head = message
            if site is not None and site.resolved is not None:
                shown = self.shown_path(site.read or site.resolved)
                head = f"include of '{text}' resolved to '{shown}' ({_reason(message)})"
            return f"{head}: {self._blame(empty, values)}"
        if not_found and lit is not None:
            return message + self._condition_hint(lit, calls)
        return message

    def _blame(self, empty: list[Use], values: dict[str, list[str]]) -> str:
        entry = os.path.basename(self.shown)
        parts, advice = [], []
        for use in empty:
            state = "has no value" if use.value is None else "is empty"
            parts.append(f"argument '{use.name}' {state} when expanding {entry} ({_told(use)})")
            shown = " or ".join(f"{use.name}:={v}" for v in values.get(use.name, []))
            advice.append(f"--xacro-arg {shown or use.name + ':=VALUE'}")
        return f"{'; '.join(parts)}; pass {' and '.join(advice)}"

    def _condition_hint(self, lit: Lit, calls: list[Lit]) -> str:
        """``; this <tag> is inside <xacro:if ...>, which depends on argument ...``."""
        tracer = self._tracer()
        for condition, rest in self._conditions(lit, calls, tracer):
            uses = _unique(tracer.uses(condition.attrs.get("value", ""), condition, rest))
            if not uses:
                continue
            described = ", and ".join(f"argument '{u.name}' ({_told(u)})" for u in uses)
            skip = next(((u, v) for u in uses if (v := skip_value(condition, u)) is not None), None)
            if skip is not None:
                advice = f"pass --xacro-arg {skip[0].name}:={skip[1]} to skip it"
            else:
                wanted = "true" if condition.tag == "xacro:unless" else "false"
                advice = (
                    f"to skip it, pass --xacro-arg {uses[0].name}:=VALUE that makes the"
                    f" condition {wanted}"
                )
            value = condition.attrs.get("value", "")
            entry = os.path.basename(self.shown)
            return (
                f'; this <{lit.tag}> is inside <{condition.tag} value="{value}"> at'
                f" {where(condition)}, which depends on {described} when expanding {entry};"
                f" {advice}"
            )
        return ""

    def _conditions(
        self, lit: Lit, calls: list[Lit], tracer: Tracer
    ) -> Iterator[tuple[Lit, list[Lit]]]:
        """The ``<xacro:if>``/``<xacro:unless>`` around ``lit``, innermost first, through the
        macro calls and includes that lead to it."""
        node: Lit | None = lit
        rest = list(calls)
        for _ in range(1000):
            if node is None:
                return
            parent = node.parent
            if parent is None:
                node, rest = self._includer_lit(node.source), []
                continue
            if parent.tag in CONDITIONS:
                yield parent, rest
            if parent.tag == "xacro:macro":
                node, rest = tracer.call(parent, rest)
                continue
            node = parent

    def _includer_lit(self, source: Source) -> Lit | None:
        """The ``<xacro:include>`` of the file that includes ``source``, if it is found."""
        if len(source.chain) < 2:
            return None
        includer = self.source(source.chain[-2])
        name = os.path.basename(source.path)
        lits = includer.lits if includer is not None else []
        return next(
            (
                lit
                for lit in lits
                if lit.tag == "xacro:include" and lit.attrs.get("filename", "").endswith(name)
            ),
            None,
        )

    # -- values that would work --------------------------------------------------------------

    def _evidence(self, site: Site, empty: list[Use]) -> tuple[list[Use], dict[str, list[str]]]:
        """Of the empty arguments in a failed include's filename, those that make it wrong
        (one is a whole folder or file name, or some value of it names a file that exists),
        and those values, by argument (when it goes into the filename unchanged)."""
        refs = list(dict.fromkeys(u.ref for u in empty))
        markers = {ref: MARKER.format(i) for i, ref in enumerate(refs)}
        pattern = self._trial_path(site, markers)
        if pattern is None:  # no evidence either way
            return empty, {}
        names = pattern.split(os.sep)
        combos = self._combinations(pattern, list(markers.values()))
        kept: list[Use] = []
        values: dict[str, list[str]] = {}
        for use in empty:
            index = refs.index(use.ref)
            found = list(dict.fromkeys(v for c in combos if (v := c[index]) is not None))
            if markers[use.ref] in names or found:
                kept.append(use)
            if found and use.direct:
                values[use.name] = found[:MAX_CANDIDATES]
        return kept, values

    def _combinations(self, pattern: str, markers: list[str]) -> list[tuple[str | None, ...]]:
        """The files that exist for ``pattern`` with any value in place of each marker: the
        values of the markers, in order, for each."""
        wildcard, regex = glob.escape(pattern), re.escape(pattern)
        for i, marker in enumerate(markers):  # (markers are letters and digits: never escaped)
            wildcard = wildcard.replace(marker, "*")
            first = regex.find(marker)
            if first >= 0:
                rest = regex[first + len(marker) :].replace(marker, f"(?P=v{i})")
                regex = f"{regex[:first]}(?P<v{i}>[^/]+){rest}"
        found = []
        for path in sorted(glob.glob(wildcard))[:200]:
            match = re.fullmatch(regex, path)
            if match is not None and self.inside(path):
                groups = match.groupdict()
                found.append(tuple(groups.get(f"v{i}") for i in range(len(markers))))
        return found

    def _trial_path(self, site: Site, markers: dict[tuple[str, str], str]) -> str | None:
        """The path the failed include names with a marker for each reference, when it is the
        path it named with the markers left out."""
        x = self.x
        args = x.substitution_args_context.get("arg")
        if args is None:
            return None
        saved = {name: args.get(name, _MISSING) for kind, name in markers if kind == "arg"}
        table = x.Table(site.symbols)
        for (kind, name), marker in markers.items():
            if kind == "arg":
                args[name] = marker
            else:
                dict.__setitem__(table, name, marker)
        try:
            spec = str(x.eval_text(site.elt.getAttribute("filename"), table))
            path = os.path.abspath(x.abs_filename_spec(spec))
        except Exception:  # a trial only: no evidence
            return None
        finally:
            for name, value in saved.items():
                if value is _MISSING:
                    args.pop(name, None)
                else:
                    args[name] = value
        blank = path
        for marker in markers.values():
            blank = blank.replace(marker, "")
        return path if os.path.abspath(blank) == site.resolved else None


def _told(use: Use) -> str:
    """Where the argument's value comes from, and the way from the text to it."""
    if use.given:
        origin = f"given as '{use.value}'"
    elif use.decl is not None:
        origin = f"default '{use.decl.attrs.get('default', '')}' in {where(use.decl)}"
    else:
        origin = "not declared and not given"
    return f"{origin}; reached through {', then '.join(use.steps)}" if use.steps else origin


def _reason(message: str) -> str:
    """``no such file or directory`` from ``cannot read PATH: no such file or directory``."""
    return message.rpartition(": ")[2] if message.startswith("cannot read ") else message


def _unique(uses: Iterator[Use] | list[Use]) -> list[Use]:
    found: dict[str, Use] = {}
    for use in uses:
        found.setdefault(use.name, use)
    return list(found.values())
