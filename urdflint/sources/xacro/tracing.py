"""Which xacro arguments a piece of source text reads, and through what.

The trace is literal: ``$(arg NAME)`` is the argument, ``${name}`` is the parameter of the
macro the text is written in (followed to the call that gave it, or to its default) or a
``<xacro:property>`` (followed to its ``value``), and an argument that was not given is
followed into its ``<xacro:arg default="...">``. Only the values come from the expansion:
what each argument held when it failed.
"""

from __future__ import annotations

import ast
import os
import re
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass

from urdflint.sources.xacro.literal import Lit, Source

ARG_RE = re.compile(r"\$\(arg\s+([^\s)]+)\s*\)")
EXPR_RE = re.compile(r"\$\{([^}]*)\}")
MAX_DEPTH = 12
CONDITIONS = ("xacro:if", "xacro:unless")

# a macro's params, parsed like xacro: name -> (forwarded with ^, default or None)
ParamsParser = Callable[[str], dict[str, tuple[bool, str | None]]]


@dataclass(frozen=True)
class Use:
    """An argument that a text reads: ``ref`` is how the text names it (``("arg", "x")`` for
    ``$(arg x)``, ``("expr", "x")`` for ``${x}``), ``steps`` the macros, properties and
    argument defaults in between, ``direct`` whether each of them passes the value unchanged."""

    name: str
    ref: tuple[str, str]
    steps: tuple[str, ...]
    direct: bool
    value: str | None  # None: no value when the expansion failed
    decl: Lit | None  # its <xacro:arg>
    given: bool  # with --xacro-arg or the configuration

    @property
    def empty(self) -> bool:
        return self.value is None or not str(self.value).strip()


def where(lit: Lit) -> str:
    return f"{os.path.basename(lit.source.shown)}:{lit.line}"


def calls_macro(tag: str, macro: str) -> bool:
    """``<tag>`` calls the macro named ``macro`` (possibly through a namespace)."""
    return tag == f"xacro:{macro}" or (tag.startswith("xacro:") and tag.endswith(f".{macro}"))


class Tracer:
    """Follows the names of a text to the arguments they come from (see the module)."""

    def __init__(
        self,
        sources: list[Source],
        values: Mapping[str, object],
        given: Mapping[str, object],
        params: ParamsParser,
    ) -> None:
        self.sources = sources
        self.values = values
        self.given = given
        self.params = params

    def lits(self) -> Iterator[Lit]:
        for source in self.sources:
            yield from source.lits

    def declaration(self, name: str) -> Lit | None:
        """The first ``<xacro:arg name="NAME">`` xacro read."""
        args = (lit for lit in self.lits() if lit.tag == "xacro:arg")
        return next((lit for lit in args if lit.attrs.get("name") == name), None)

    def call(self, macro: Lit, calls: list[Lit]) -> tuple[Lit | None, list[Lit]]:
        """The call of ``macro`` that is running (the first of ``calls``), or its only call."""
        name = macro.attrs.get("name", "")
        if calls and calls_macro(calls[0].tag, name):
            return calls[0], calls[1:]
        sites = [lit for lit in self.lits() if calls_macro(lit.tag, name)]
        return (sites[0], []) if len(sites) == 1 else (None, [])

    def uses(
        self,
        text: str,
        lit: Lit | None,
        calls: list[Lit],
        steps: tuple[str, ...] = (),
        direct: bool = True,
        ref: tuple[str, str] | None = None,
        depth: int = 0,
    ) -> list[Use]:
        """Every argument ``text`` (written at ``lit``, in the macro calls ``calls``) reads.

        ``ref`` and ``direct`` are for the recursion: the reference in the first text that
        led here, and whether every text since was that reference alone."""
        if depth > MAX_DEPTH:
            return []
        found: list[Use] = []
        whole = text.strip()
        for match in ARG_RE.finditer(text):
            name = match.group(1)
            same = direct and (ref is None or whole == match.group(0))
            found += self._arg(name, steps, same, ref or ("arg", name), depth)
        for match in EXPR_RE.finditer(text):
            expr = match.group(1).strip()
            for name in _names(expr):
                same = direct and (ref is None or (whole == match.group(0) and expr == name))
                found += self._name(name, lit, calls, steps, same, ref or ("expr", name), depth)
        return found

    def _arg(
        self, name: str, steps: tuple[str, ...], direct: bool, ref: tuple[str, str], depth: int
    ) -> list[Use]:
        value = self.values.get(name)
        decl = self.declaration(name)
        given = name in self.given
        if not given and value is not None and decl is not None:
            default = decl.attrs.get("default", "")
            step = f"argument '{name}' whose default is '{default}' at {where(decl)}"
            inner = self.uses(default, decl, [], (*steps, step), direct, ref, depth + 1)
            if inner:
                return inner
        shown = None if value is None else str(value)
        return [Use(name, ref, steps, direct, shown, decl, given)]

    def _name(
        self,
        name: str,
        lit: Lit | None,
        calls: list[Lit],
        steps: tuple[str, ...],
        direct: bool,
        ref: tuple[str, str],
        depth: int,
    ) -> list[Use]:
        macro = _enclosing_macro(lit)
        params = self.params(macro.attrs.get("params", "")) if macro is not None else {}
        if macro is not None and name in params:
            title = macro.attrs.get("name", "")
            call, rest = self.call(macro, calls)
            if call is not None and name in call.attrs:
                raw = call.attrs[name]
                step = f"macro '{title}' called with {name}=\"{raw}\" at {where(call)}"
                return self.uses(raw, call, rest, (*steps, step), direct, ref, depth + 1)
            forward, default = params[name]
            if forward and call is not None:
                step = f"macro '{title}' called at {where(call)}, which forwards {name}"
                return self._name(name, call, rest, (*steps, step), direct, ref, depth + 1)
            if default is None:
                return []
            step = f"macro '{title}' whose parameter {name} defaults to '{default}'"
            return self.uses(default, call or macro, rest, (*steps, step), direct, ref, depth + 1)
        prop = self._property(name, lit)
        if prop is None:
            return []
        value = prop.attrs.get("value", prop.attrs.get("default"))
        if value is None:  # a block property
            return []
        step = f"property '{name}' = '{value}' at {where(prop)}"
        return self.uses(value, prop, calls, (*steps, step), direct, ref, depth + 1)

    def _property(self, name: str, lit: Lit | None) -> Lit | None:
        """The ``<xacro:property>`` of that name: the last one above ``lit`` in its file, else
        the first one anywhere."""
        named = [
            p for p in self.lits() if p.tag == "xacro:property" and p.attrs.get("name") == name
        ]
        if lit is not None:
            above = [p for p in named if p.source is lit.source and p.line <= lit.line]
            if above:
                return above[-1]
        return named[0] if named else None


def skip_value(condition: Lit, use: Use) -> str | None:
    """The value of ``use``'s argument that makes ``<xacro:if>``/``<xacro:unless>``
    ``condition`` drop its content, for the simple conditions (``${x}``, ``${not x}``,
    ``${x == 'v'}``, ``${x != 'v'}``, ``$(arg x)``), else None."""
    if not use.direct:
        return None
    wanted = condition.tag == "xacro:unless"  # what the condition must be to drop the content
    text = condition.attrs.get("value", "").strip()
    kind, name = use.ref
    if text == (f"$(arg {name})" if kind == "arg" else f"${{{name}}}"):
        return "true" if wanted else "false"
    match = re.fullmatch(r"\$\{(.*)\}", text, re.S)
    try:
        tree = ast.parse(match.group(1).strip(), mode="eval").body if match else None
    except SyntaxError:
        return None
    if isinstance(tree, ast.UnaryOp) and isinstance(tree.op, ast.Not):
        return ("false" if wanted else "true") if _refers(tree.operand, use) else None
    if not isinstance(tree, ast.Compare) or len(tree.ops) != 1:
        return None
    left, right = tree.left, tree.comparators[0]
    if _refers(right, use):
        left, right = right, left
    if not _refers(left, use) or not isinstance(right, ast.Constant):
        return None
    equal = isinstance(tree.ops[0], ast.Eq)
    if (equal and wanted) or (isinstance(tree.ops[0], ast.NotEq) and not wanted):
        return str(right.value)
    return None


def _refers(node: ast.expr, use: Use) -> bool:
    kind, name = use.ref
    if kind == "expr":
        return isinstance(node, ast.Name) and node.id == name
    return isinstance(node, ast.Constant) and node.value == f"$(arg {name})"


def _names(expr: str) -> list[str]:
    """The names an expression reads, in order, once each."""
    try:
        tree = ast.parse(expr, mode="eval")
    except SyntaxError:
        return []
    names = sorted(
        (n for n in ast.walk(tree) if isinstance(n, ast.Name)),
        key=lambda n: (n.lineno, n.col_offset),
    )
    return list(dict.fromkeys(n.id for n in names))


def _enclosing_macro(lit: Lit | None) -> Lit | None:
    node = lit.parent if lit is not None else None
    while node is not None and node.tag != "xacro:macro":
        node = node.parent
    return node
