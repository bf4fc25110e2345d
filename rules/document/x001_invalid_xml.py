"""The file is not well-formed XML.

## What it does
Reports the XML syntax error lxml found, with its line and column. It also
reports files over 64 MiB, which urdflint refuses to parse.

What the TinyXML-based consumers read past is blanked out (every line and
column kept) and the file is parsed again, so the other rules check the same
tree they read, with nothing guessed, skipped or marked; `urdflint fix` works
on it too. Each such repair is its own X001 finding, at the severity that
follows from what those consumers do:

- a warning for an XML declaration that TinyXML and TinyXML2 both read past:
  one libxml2 refuses (`<?xml version="0.0"?>`, as in PyBullet's `bike.urdf`,
  a missing `version`, `<?XML`), or one after blank lines or after another
  declaration (as in PyBullet's `biped2d_pybullet.urdf` and `diff_ring.urdf`).
  This is X001, not X009: X009 is about `<robot version>`, which urdfdom reads,
  while no URDF consumer reads the declaration's version. An encoding that
  libxml2 does not know stays an error and is not repaired: the bytes may not be
  UTF-8, which is all TinyXML2 reads;
- an error for a declaration after a comment or inside `<robot>`, which
  TinyXML2 refuses and TinyXML (urdfdom 3, `check_urdf`) reads, and for stray
  text before the root element, which TinyXML refuses and TinyXML2 reads.

Other errors are not repaired. The other rules still run on the tree that
libxml2's recovery mode rebuilds from the file, when that tree is a `<robot>`;
their messages end with "(from the part of the file that could be read after
the X001 error)", since what follows the error may be read differently from
what was meant. The physics rules (P) do not run on such a tree. A file with a
DOCTYPE or entities (X002) is never recovered.

## Why is this bad?
The file is not XML, and what each consumer makes of it depends on its parser.
Strict XML parsers refuse it: xacro (expat: "not well-formed (invalid token)",
"junk after document element"), urdf_parser_py and the other lxml-based Python
tools; yourdfpy silently retries in recover mode and may load half of the robot.
The C++ consumers use TinyXML (urdfdom 3.0.1, `check_urdf`) or tinyxml2
(PyBullet, MuJoCo, Drake, sdformat, Pinocchio's urdfdom 6.0), which refuse
unclosed or mismatched tags, repeated attributes and truncated files ("Error
reading end tag", "Failed to parse XML file: XML_ERROR_MISMATCHED_ELEMENT";
tinyxml2 also refuses an unquoted attribute value, which `check_urdf` accepts),
but load some broken files without a word: observed with a stray `&` or `<` in
an attribute value, a `--` inside a comment, an undefined entity such as
`&nbsp;` and a second root element after `</robot>`. Such a file works in the
simulator and breaks the first time xacro or a Python tool reads it.

## How to fix
Fix the syntax at the reported position: an unclosed tag, a stray `<` or `&`
(write `&lt;`/`&amp;`), mismatched quotes or a second root element. Write the
XML declaration as `<?xml version="1.0"?>` on the very first line, or leave it
out: URDF needs none.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity


@rule("X001", "invalid-xml", Severity.ERROR, requires_robot=False)
def check(doc: Document) -> Iterator[Hit]:
    for repair in doc.repairs:
        line, column = repair.line, repair.column
        yield Hit(None, repair.message, severity=repair.severity, line=line, column=column)
    problem = doc.problem
    if problem is not None and problem.code == "X001":
        line, column = problem.line, problem.column
        yield Hit(None, problem.message, line=line, column=column, path=problem.path)
