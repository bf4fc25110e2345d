"""urdflint's guards around xacro: refusals as clean findings, a confined glob and evaluator,
a cap on macro calls."""

from __future__ import annotations

from collections.abc import Callable
from functools import cache
from typing import Any

MAX_MACRO_CALLS = 20_000  # a macro "billion laughs" stops here

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


@cache
def refusal_class(xacro: Any) -> type:
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


class ConfinedGlob:
    """``glob`` for xacro's include patterns that never answers outside the root."""

    def __init__(self, inside: Callable[[str], bool]) -> None:
        self.inside = inside

    def glob(self, pattern: str, *args: Any, **kwargs: Any) -> list[str]:
        import glob

        return [p for p in glob.glob(pattern, *args, **kwargs) if self.inside(p)]


def counting(x: Any, original: Callable[..., Any], calls: list[int]) -> Callable[..., Any]:
    """``handle_macro_call`` that refuses more than MAX_MACRO_CALLS macro calls."""

    def handle_macro_call(node: Any, macros: Any, symbols: Any) -> Any:
        if node.tagName.startswith("xacro:"):
            calls[0] += 1
            if calls[0] > MAX_MACRO_CALLS:
                raise refusal_class(x)(
                    "X010",
                    f"more than {MAX_MACRO_CALLS} macro calls: runaway recursion or an"
                    " expansion bomb",
                )
        return original(node, macros, symbols)

    return handle_macro_call


def confined_eval(x: Any, original: Callable[..., Any]) -> Callable[..., Any]:
    """xacro's ``safe_eval`` refusing the names that lead out of its sandbox."""
    refused = refusal_class(x)

    def vet(code: Any) -> None:
        for name in code.co_names:
            if name.startswith("_") or name in CONFINED_DENY:
                raise refused("X010", f"the expression uses '{name}', which is not allowed here")
        for const in code.co_consts:
            if isinstance(const, str) and "__" in const:
                raise refused("X010", "the expression uses a string with '__', not allowed here")
            if hasattr(const, "co_names"):
                vet(const)

    def safe_eval(expr: str, globals: Any, locals: Any = None) -> Any:
        vet(compile(expr.strip(), "<expression>", "eval"))
        return original(expr, globals, locals)

    return safe_eval


def confined_extension(original: Callable[[str], Any]) -> Callable[[str], Any]:
    """``$(cwd)`` is ``.`` in confined mode: the server's folders are nobody's business."""

    def eval_extension(s: str) -> Any:
        return "." if s == "$(cwd)" else original(s)

    return eval_extension
