"""Hardened parsing of a URDF file into the tree the rules read.

The parser never expands entities, never loads a DTD, never touches the network
and keeps libxml2's size and depth limits; comments stay in the tree because they
carry suppressions. Beyond a strict parse, it reads what the TinyXML-based
consumers (urdfdom, PyBullet, MuJoCo, Drake, Pinocchio) read, without hiding it:

- a namespace prefix used without its ``xmlns:`` declaration (``<drake:joint>``) is
  declared with a placeholder URI on the root's start tag (same line, so every line
  number stays) and the file is parsed again; X012 reports the prefix;
- a default namespace on ``<robot>`` (``xmlns="..."``) is taken off the elements in
  it, so the rules see ``<link>``, not ``{uri}link``; X002 reports it as a warning;
- an XML declaration TinyXML and TinyXML2 read past (a version other than 1.x, a
  declaration after blank lines or after other content) and stray text before the root
  element are blanked out, every newline kept, and the file is parsed again: the tree is
  the one the TinyXML-based consumers read, nothing in it guessed. Each such repair is an
  X001 finding (``Parsed.repairs``) whose severity follows what those consumers do;
- a file that is not well-formed is X001, and when libxml2's recovery
  (``recover=True``, the parser otherwise unchanged) still yields a ``<robot>``, that
  tree is checked too (``Parsed.recovered``);
- a DOCTYPE or an entity reference is X002 and is never recovered.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace

from lxml import etree

from urdflint.model.finding import Severity
from urdflint.model.positions import TAG_END_RE, Lines

MAX_BYTES = 64 * 2**20
XACRO_NS = "http://www.ros.org/wiki/xacro"
UNDECLARED_NS = "urn:urdflint:undeclared-prefix:"  # + the prefix: a placeholder namespace

_UNDECLARED = etree.ErrorTypes.NS_ERR_UNDEFINED_NAMESPACE
_PREFIX_RE = re.compile(r"Namespace prefix ([A-Za-z_][\w.-]*) (?:for \S+ )?on \S+ is not defined")
_PROLOG_RE = re.compile(rb"(?:\s+|<\?.*?\?>|<!--.*?-->)*", re.S)
_ROOT_RE = re.compile(rb"<([A-Za-z_][^\s/>]*)")
_DECLARATION_RE = re.compile(rb"<\?xml(?=[\s?])[^<]*?\?>", re.I)
_PIS_RE = re.compile(rb"(?:\s+|<\?[^<]*?\?>)*")  # what TinyXML2 allows before a declaration
_STRAY_RE = re.compile(rb"[^<]+")
_NOT_NEWLINE_RE = re.compile(rb"[^\r\n]")
MAX_REPAIRS = 16  # declarations and stray texts blanked out in one file

# who reads what the repairs take out (observed with check_urdf 3.0.1, PyBullet, Pinocchio)
_TINYXML_BOTH = "TinyXML and TinyXML2 (urdfdom, PyBullet, Pinocchio, Gazebo)"
_TINYXML2 = "TinyXML2 (urdfdom 4 and later, PyBullet, Pinocchio, Gazebo, Drake, MuJoCo)"
_TINYXML1 = "TinyXML (urdfdom 3, check_urdf)"


@dataclass(frozen=True, slots=True)
class XmlProblem:
    """Why a document is not a usable ``<robot>``: X001 (syntax) or X002 (not a robot)."""

    code: str
    message: str
    line: int = 1
    column: int = 1
    path: str | None = None  # xacro: the (shown) file the problem is in, when not the main file
    severity: Severity | None = None  # a repair's: how the TinyXML-based consumers take it


@dataclass(frozen=True, slots=True)
class Parsed:
    """What :func:`parse` made of a file.

    ``root`` is set for a usable ``<robot>``, and also beside an X001 ``problem`` when
    ``recovered`` (the tree libxml2 rebuilt from a file that is not well-formed).
    ``repairs`` are the X001 findings for what was blanked out before the tree was read
    (kept only when that gave a ``<robot>``); the tree itself is then exact.
    """

    root: etree._Element | None = None
    problem: XmlProblem | None = None
    recovered: bool = False
    undeclared: tuple[str, ...] = ()  # namespace prefixes used without a declaration
    default_namespace: str | None = None  # the xmlns="..." of <robot>, taken off the tree
    repairs: tuple[XmlProblem, ...] = ()


def make_parser(*, recover: bool = False) -> etree.XMLParser:
    # One parser per parse: lxml parsers are not safe to share across threads.
    return etree.XMLParser(
        resolve_entities=False,
        no_network=True,
        load_dtd=False,
        dtd_validation=False,
        huge_tree=False,
        remove_comments=False,
        remove_pis=True,
        remove_blank_text=False,
        recover=recover,
    )


def local_tag(el: etree._Element) -> str:
    """``link`` for ``<link>``, ``xacro:macro`` for a namespaced xacro element."""
    tag = el.tag
    if not isinstance(tag, str):
        return ""
    if tag.startswith("{"):
        uri, _, local = tag[1:].partition("}")
        prefix = el.prefix or ("xacro" if "xacro" in uri else uri)
        return f"{prefix}:{local}"
    return tag


def undeclared_uri(prefix: str) -> str:
    """The placeholder namespace an undeclared ``prefix`` is bound to in the tree."""
    return UNDECLARED_NS + prefix


def parse(source: bytes) -> Parsed:
    """Parse ``source`` strictly, then as leniently as the TinyXML-based consumers do."""
    if len(source) > MAX_BYTES:
        return Parsed(
            problem=XmlProblem(
                "X001", f"file is {len(source) / 2**20:.0f} MiB, over the 64 MiB limit"
            )
        )
    text = source
    repairs: list[XmlProblem] = []
    while True:
        parser = make_parser()
        try:
            return _repaired(source, _checked(etree.fromstring(text, parser), text), repairs)
        except etree.XMLSyntaxError as exc:
            if b"<!DOCTYPE" in source or b"<!ENTITY" in source:
                # e.g. an entity bomb libxml2 stopped: refuse it as a DOCTYPE, not a typo
                return Parsed(problem=_doctype_problem(source))
            # the parser's own log: exc.error_log also holds earlier parses of this thread
            repair = _repair(text, source, parser.error_log) if len(repairs) < MAX_REPAIRS else None
            if repair is None:
                return _repaired(source, _not_well_formed(text, parser, exc), repairs)
            text = repair[0]
            repairs.append(repair[1])
        except ValueError as exc:  # e.g. an encoding declaration lxml refuses
            return Parsed(problem=XmlProblem("X001", str(exc)))


def _repaired(source: bytes, parsed: Parsed, repairs: list[XmlProblem]) -> Parsed:
    """``parsed`` with its repairs, or, when they gave no ``<robot>``, the original file's
    problem: a repair is reported only with the tree it let urdflint check."""
    if not repairs:
        return parsed
    if parsed.root is None:
        parser = make_parser()
        try:
            etree.fromstring(source, parser)
        except etree.XMLSyntaxError as exc:
            return _not_well_formed(source, parser, exc)
    return replace(parsed, repairs=tuple(repairs))


def _not_well_formed(text: bytes, parser: etree.XMLParser, exc: etree.XMLSyntaxError) -> Parsed:
    """X001 for ``text``, with the tree libxml2 recovers from it when that is sound."""
    prefixes = _undeclared(parser.error_log)
    problem = _first_error(parser.error_log)
    declared = _declare(text, prefixes) if prefixes else None
    if problem is None and declared is not None:
        again = make_parser()
        try:
            return _checked(etree.fromstring(declared, again), declared, prefixes)
        except etree.XMLSyntaxError:
            problem = _first_error(again.error_log)
    problem = problem or _exception_problem(exc)
    if not _after_root_tag(text, problem):
        # in or before the root's start tag: not even the robot's name can be trusted
        return Parsed(problem=problem)
    return _recover(declared or text, problem, prefixes)


# -- repairs: what TinyXML-based parsers read past, blanked out -------------------------------


def _repair(
    text: bytes, source: bytes, log: etree._ListErrorLog
) -> tuple[bytes, XmlProblem] | None:
    """``text`` with the cause of its first error blanked out, and the X001 finding for it;
    ``None`` when that error is not in an XML declaration or stray text before the root."""
    error = next((e for e in log if e.type != _UNDECLARED), None)
    if error is None or "ENCODING" in error.type_name:  # the bytes may not be UTF-8, as
        return None  # TinyXML2 reads them
    lines = Lines(text)
    if not 1 <= error.line <= len(lines.starts):
        return None
    start = lines.starts[error.line - 1]
    characters = text[start : lines.end_of_line(error.line)].decode("utf-8", "replace")
    at = start + len(characters[: max(error.column, 1) - 1].encode("utf-8"))
    if error.type == etree.ErrorTypes.ERR_DOCUMENT_EMPTY:
        offset, span = at, _STRAY_RE.match(text, at)
        if span is None or span.end() == len(text) or not span.group().strip():
            return None
        problem = _stray(Lines(source).position(offset), span.group())
    else:  # an error inside a declaration, or right after its <?xml
        offset = text.rfind(b"<?", 0, at + 2)
        span = _DECLARATION_RE.match(text, offset) if offset >= 0 else None
        if span is None or at > span.end():
            return None
        at_source = Lines(source).position(offset)  # blanked bytes are each a space in text
        problem = _declaration(source, offset, at_source, error.message or "")
    blank = _NOT_NEWLINE_RE.sub(b" ", span.group())  # every line break kept
    return text[:offset] + blank + text[span.end() :], problem


def _declaration(source: bytes, start: int, at: tuple[int, int], why: str) -> XmlProblem:
    """X001 for an XML declaration at ``start``: a warning where TinyXML2 reads past it."""
    before = source[3 if source.startswith(b"\xef\xbb\xbf") else 0 : start]
    if not before:
        said = f"the XML declaration is refused by lxml ({why.strip()}) but ignored by"
    elif _PIS_RE.fullmatch(before):
        said = (
            "the file has a second XML declaration"
            if _DECLARATION_RE.search(before)
            else "the XML declaration is not at the very start of the file"
        ) + ", which lxml and xacro refuse but"
    else:
        root = _root_start(source)
        tag = _ROOT_RE.match(source, root) if root is not None and root < start else None
        rest = before[_PIS_RE.match(before).end() :]  # type: ignore[union-attr]
        where = (
            f"inside <{tag.group(1).decode('utf-8', 'replace')}>"
            if tag is not None
            else "after a comment"
            if rest.startswith(b"<!--")
            else "after other content"
        )
        message = (
            f"the XML declaration comes {where}, which {_TINYXML2} refuses "
            "(XML_ERROR_PARSING_DECLARATION), as do lxml and xacro; the rest of the file was "
            f"checked as {_TINYXML1} reads it"
        )
        return XmlProblem("X001", message, *at, severity=Severity.ERROR)
    message = f"{said} {_TINYXML_BOTH}; the rest of the file was checked as they read it"
    return XmlProblem("X001", message, *at, severity=Severity.WARNING)


def _stray(at: tuple[int, int], stray: bytes) -> XmlProblem:
    shown = stray.decode("utf-8", "replace").strip()
    shown = shown if len(shown) <= 30 else shown[:29] + "…"
    message = (
        f"text {shown!r} before the root element, which {_TINYXML1} refuses "
        f'("Error document empty"), as do lxml and xacro, but {_TINYXML2} ignores; the rest of '
        "the file was checked as TinyXML2 reads it"
    )
    return XmlProblem("X001", message, *at, severity=Severity.ERROR)


def _checked(root: etree._Element, source: bytes, prefixes: tuple[str, ...] = ()) -> Parsed:
    """A strictly parsed tree: refused when it has a DOCTYPE or entities or is no ``<robot>``."""
    refused = _refusal(root, source)
    if refused is not None:
        return Parsed(problem=refused)
    default = _strip_default_namespace(root)
    if root.tag != "robot":
        line = root.sourceline or 1
        message = f"root element is <{local_tag(root)}>, not <robot>"
        return Parsed(problem=XmlProblem("X002", message, line))
    return Parsed(root, undeclared=prefixes, default_namespace=default)


def _refusal(root: etree._Element, source: bytes) -> XmlProblem | None:
    tree = root.getroottree()
    if tree.docinfo.internalDTD is not None or tree.docinfo.doctype:
        return _doctype_problem(source)
    entity = next(root.iter(etree.Entity), None)
    if entity is not None:
        line = entity.sourceline or 1
        return XmlProblem("X002", f"document uses the entity reference {entity.text}", line)
    return None


def _recover(text: bytes, problem: XmlProblem, prefixes: tuple[str, ...]) -> Parsed:
    """X001, with the tree libxml2 recovers when it is a plain ``<robot>``."""
    found = _recovered(text)
    if found is not None:
        more = tuple(p for p in found[1] if p not in prefixes)
        patched = _declare(text, more) if more else None
        if patched is not None:  # prefixes met only after the fatal error: declare them too
            text, prefixes = patched, prefixes + more
            found = _recovered(text)
    root = found[0] if found is not None else None
    if root is None or _refusal(root, text) is not None:
        return Parsed(problem=problem)
    default = _strip_default_namespace(root)
    if root.tag != "robot":
        return Parsed(problem=problem)
    return Parsed(root, problem, True, prefixes, default)


def _after_root_tag(text: bytes, problem: XmlProblem) -> bool:
    """Whether the X001 error lies after the end of the root element's start tag."""
    start = _root_start(text)
    end = TAG_END_RE.match(text, start + 1) if start is not None else None
    if end is None:
        return False
    line = text.count(b"\n", 0, end.end()) + 1
    column = end.end() - (text.rfind(b"\n", 0, end.end()) + 1)
    return (problem.line, problem.column) > (line, column)


def _root_start(source: bytes) -> int | None:
    """Offset of the root element's ``<`` (after the XML declaration, comments, PIs)."""
    start = 3 if source.startswith(b"\xef\xbb\xbf") else 0
    prolog = _PROLOG_RE.match(source, start)
    root = _ROOT_RE.match(source, prolog.end() if prolog else start)
    return root.start() if root else None


def _recovered(text: bytes) -> tuple[etree._Element | None, tuple[str, ...]] | None:
    """libxml2's recovered tree of ``text`` and the undeclared prefixes it met."""
    parser = make_parser(recover=True)
    try:
        root = etree.fromstring(text, parser)
    except (etree.XMLSyntaxError, ValueError):
        return None
    return root, _undeclared(parser.error_log)


def _first_error(log: etree._ListErrorLog) -> XmlProblem | None:
    """X001 for the first error that is not an undeclared prefix (``None`` if there is none)."""
    error = next((e for e in log if e.type != _UNDECLARED), None)
    if error is None:
        return None
    message = (error.message or "").strip() or "not well-formed XML"
    return XmlProblem("X001", message, max(error.line, 1), max(error.column, 1))


def _exception_problem(exc: etree.XMLSyntaxError) -> XmlProblem:
    line, column = exc.position if exc.position else (1, 1)
    message = (exc.msg or str(exc)).strip()
    message = message.split(", line ")[0] if ", line " in message else message
    return XmlProblem("X001", message, max(line, 1), max(column, 1))


def _undeclared(log: etree._ListErrorLog) -> tuple[str, ...]:
    """The prefixes libxml2 found used without a declaration, in order of first use."""
    found: dict[str, None] = {}
    for error in log:
        if error.type == _UNDECLARED:
            match = _PREFIX_RE.match(error.message or "")
            if match and match.group(1) not in ("xml", "xmlns"):
                found[match.group(1)] = None
    return tuple(found)


def _declare(source: bytes, prefixes: tuple[str, ...]) -> bytes | None:
    """``source`` with ``xmlns:prefix="placeholder"`` added right after the root's tag name.

    The declarations go on the root tag's own line, so every line number stays; columns
    are computed from the original text. ``None`` when the root tag cannot be found.
    """
    start = _root_start(source)
    root = _ROOT_RE.match(source, start) if start is not None else None
    if root is None:
        return None
    declarations = b"".join(
        b' xmlns:%s="%s"' % (p.encode(), undeclared_uri(p).encode()) for p in prefixes
    )
    return source[: root.end()] + declarations + source[root.end() :]


def _strip_default_namespace(root: etree._Element) -> str | None:
    """Take ``<robot xmlns="uri">``'s namespace off the un-prefixed elements in it.

    TinyXML-based parsers compare tag names as written, so ``<link>`` inside such a
    robot is a link for them; the rules see it the same way. Returns the URI.
    """
    if root.prefix is not None or not isinstance(root.tag, str) or not root.tag.startswith("{"):
        return None
    qname = etree.QName(root)
    if qname.localname != "robot":
        return None
    uri = qname.namespace or ""
    marker = "{" + uri + "}"
    for el in root.iter(etree.Element):
        if el.prefix is None and el.tag.startswith(marker):
            el.tag = el.tag[len(marker) :]
    etree.cleanup_namespaces(root)
    return uri


def _doctype_problem(source: bytes) -> XmlProblem:
    index = source.find(b"<!DOCTYPE")
    line = source.count(b"\n", 0, index) + 1 if index >= 0 else 1
    return XmlProblem(
        "X002",
        "document has a DOCTYPE declaration; URDF never needs one and it is not expanded",
        line,
    )
