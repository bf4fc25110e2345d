"""Incremental re-expansion: a value typed into a plain element, without running xacro again.

The language server lints an entry again every time a file it reads is edited; a full xacro
expansion of a big robot takes longer than the time a diagnostic may take. The common edit is
a value typed into an attribute of a plain element (``<mass value="1.5"/>`` becomes
``value="-1.5"``). :func:`apply` turns the previous expanded document of the entry into the
document a full expansion of the edited files would give, or says it cannot (``None``: the
caller expands in full). It patches only when each step below is certain:

1. **The edit is one attribute value of one start tag.** The previous document's source map
   holds the exact bytes xacro read of every file (``SourceFile.data``); the edited file must be
   one of them and its old text must be those bytes (otherwise the map describes another
   text). The changed bytes are the middle left by the common prefix and suffix of the old and
   new text. The new file is parsed by expat (the parser xacro uses): it must be well-formed,
   and the last start tag that expat reports at or before the change must contain the change
   inside the quotes of one of its attribute values. Because expat reports that tag, it is a
   real start tag (not text inside a comment or CDATA); inside a start tag the attribute
   spans are found exactly. The old tag is the same bytes with the old value, and since both
   texts agree outside that value, the old and new files have the same elements, with the
   same attributes, at the same places, except for that value; only byte offsets after the
   change move (by the length difference).
2. **xacro copies the value verbatim.** xacro 2 reads an attribute of a plain element in one
   place only: ``eval_all`` sets it to ``str(eval_text(value))``, and ``eval_text`` of a text
   without ``$`` is that text, unchanged (its lexer gives one plain-text token; ``$`` starts
   every expression, extension and ``$$`` escape). So the element's start tag must not be a
   xacro element (``xacro:``, the only prefix xacro acts on, nor in the xacro namespace):
   those read their attributes as property values, macro parameters and defaults,
   conditions, names, include paths. The attribute must not be namespaced (``xacro:*``
   attributes are dropped, ``xmlns:*`` declare prefixes) nor ``xmlns``. The old and new
   values, as expat decodes them, must hold no ``$`` (so neither is an expression, and an
   evaluated block such as a block parameter evaluated twice still copies it) and no tab or
   line break (the raw text none either: expat folds them into spaces and minidom writes
   them back unescaped, which would move lines of the expanded document). A
   ``xacro:attribute`` inside the element could set the same attribute over the literal
   one: the element must have none among its descendants. Where the element sits does not
   matter: inside a macro body, a block parameter, a property block or a kept condition it
   is cloned or moved and evaluated the same way; inside a macro never called, a block never
   inserted, a condition not kept, a ``xacro:arg`` or an include, it is never written out.
3. **The expanded document changes exactly at the copies.** Every node xacro parses carries a
   mark (file, byte offset of its start tag, macro call chain) and every clone keeps it
   (``insert_block``, macro bodies), so the elements of the expanded document written by the
   edited start tag are exactly those marked with its file and offset. Each must have the
   attribute with the old value, and the expanded text at that attribute (found from the
   element's line: the start tag ``<tag`` and ``name="`` in it) must be the old value as
   minidom writes it. Each is replaced by the new value, escaped the same way (minidom's own
   writer). Nothing else in the expanded text depends on the value, so the new text is what
   ``toprettyxml`` would write.
4. **The rest of the document follows from the new text.** The new :class:`Document` is
   parsed from the new text with the same path, targets, settings, base folder and a
   context whose overlay holds the edited bytes (what the language server gives a full
   expansion). Its source map is the previous one carried over: the same marks in document
   order (the new tree has the same elements and comments in the same order), with the
   offsets in the edited file at or after the change moved by the length difference (the
   start tags and macro calls written after the edit, and so the lines and columns of the
   attributes after the edit on the same line), and the edited file's bytes replaced.
   ``library`` is decided as :func:`urdflint.sources.xacro.document` decides it. The
   literal sources xacro read (:mod:`.literal`) only locate expansion errors, and a document
   that failed to expand is never patched.

Anything that does not line up (a previous document that did not expand, a source map that
could not be built, an element past line 65535 of the expanded text, where libxml2's line
numbers are not reliable, a file declaring another encoding than UTF-8) gives ``None``.
"""

from __future__ import annotations

import dataclasses
import logging
import os
import re
import xml.parsers.expat
from typing import TYPE_CHECKING, Any
from xml.dom import minidom

from lxml import etree

from urdflint.model.document import MAX_BYTES, Document, children
from urdflint.model.parsing import XACRO_NS
from urdflint.model.positions import TAG_END_RE, attribute_offset
from urdflint.sources.xacro.sourcemap import SourceMap

if TYPE_CHECKING:
    from urdflint.engine.context import Context

__all__ = ["apply"]

log = logging.getLogger("urdflint.sources.xacro")

# an attribute inside a start tag: its name, and its value between quotes (group 2 or 3)
VALUE_RE = re.compile(rb"""\s([^\s=/>]+)\s*=\s*(?:"([^"]*)"|'([^']*)')""")
ENCODING_RE = re.compile(rb"""^\s*<\?xml[^>]*?encoding\s*=\s*["']([^"']+)["']""")
EQUALS_RE = re.compile(rb'\s*=\s*"')
MAX_LINE = 65535  # libxml2 reports at most this line without XML_PARSE_BIG_LINES


class Refused(Exception):
    """The edit cannot be patched (the reason, for the debug log)."""


def apply(
    previous: Document, path: str, old: bytes, new: bytes, context: Context | None = None
) -> Document | None:
    """The document a full expansion would give after ``path`` changed from ``old`` to ``new``,
    patched from ``previous`` (a document of :func:`urdflint.sources.xacro.document` that read
    ``path``); ``None`` when the edit is not one this module can prove (expand in full).

    ``context`` is the new document's; by default ``previous``'s, with ``new`` in its overlay.
    """
    try:
        return _apply(previous, os.path.abspath(path), old, new, context)
    except Refused as why:
        log.debug("xacro patch of %s: %s", path, why)
    except Exception:  # anything unexpected: the full expansion is always right
        log.debug("xacro patch of %s failed", path, exc_info=True)
    return None


def _apply(
    previous: Document, full: str, old: bytes, new: bytes, context: Context | None
) -> Document:
    sources = previous.origin
    root = previous.root
    if not isinstance(sources, SourceMap) or root is None or not previous.ok:
        raise Refused("the previous document is not an expanded robot")
    index = next((i for i, f in enumerate(sources.files) if f.path == full), None)
    if index is None:
        raise Refused("the file was not read by this expansion")
    if sources.files[index].data != old:
        raise Refused("the previous expansion read another text of the file")
    edit = _edit(old, new)
    if sources.sequence(root) is None:
        raise Refused("the previous source map could not be built")
    copies = sources.written_at(root, index, edit.tag)
    expanded = _spliced(previous.source, _spans(previous, copies, edit), _written(edit.new_value))

    # 4. the new document, with the source map carried over
    origin = sources.carried(index, new, edit.at, len(new) - len(old), expanded, root)
    if origin is None:
        raise Refused("the previous source map could not be built")
    if context is None:
        context = dataclasses.replace(
            previous.context, overlay={**previous.context.overlay, full: new}
        )
    doc = Document(
        previous.path,
        expanded,
        targets=previous.targets,
        settings=previous.settings,
        context=context,
        base_dir=previous.base_dir,
        origin=origin,
    )
    if not doc.ok:
        raise Refused("the patched text is not a robot")  # never: only a value changed
    if not children(doc.robot, "link"):
        doc.library = True  # as document() decides it
    return doc


def _spans(previous: Document, copies: list[etree._Element], edit: Edit) -> list[tuple[int, int]]:
    """3. Where the expanded text writes the edited value of each copy (between its quotes)."""
    name = edit.name.decode("utf-8")
    before = edit.old_value
    written = _written(before)
    text = previous.source
    spans: list[tuple[int, int]] = []
    for el in copies:
        if not isinstance(el.tag, str) or etree.QName(el).namespace == XACRO_NS:
            raise Refused("a copy is not a plain element")
        if el.get(name) != before:
            raise Refused(f"a copy of the element has {name}={el.get(name)!r}")
        if not el.sourceline or el.sourceline >= MAX_LINE:
            raise Refused("a copy's line in the expanded document is not known")
        start = previous._tag_offset(el)
        found = attribute_offset(text, start, name) if start is not None else None
        if found is None:
            raise Refused("a copy's attribute is not found in the expanded text")
        equals = EQUALS_RE.match(text, found + len(edit.name))
        if equals is None:
            raise Refused("a copy's attribute is not written as minidom writes it")
        begin = equals.end()
        end = text.find(b'"', begin)
        if text[begin:end] != written:
            raise Refused("a copy's value is not written as minidom writes it")
        spans.append((begin, end))
    return sorted(spans)


def _spliced(text: bytes, spans: list[tuple[int, int]], value: bytes) -> bytes:
    """``text`` with ``value`` at each span (sorted)."""
    pieces: list[bytes] = []
    last = 0
    for begin, end in spans:
        if begin < last:
            raise Refused("two copies overlap")
        pieces += (text[last:begin], value)
        last = end
    pieces.append(text[last:])
    expanded = b"".join(pieces)
    if len(expanded) > MAX_BYTES:
        raise Refused("the expanded document would be over the size limit")  # as expansion
    return expanded


@dataclasses.dataclass(frozen=True)
class Edit:
    """One attribute value changed in one start tag (offsets in the file)."""

    tag: int  # the start tag's ``<``
    at: int  # the first changed byte: marks at or after it move
    name: bytes  # the attribute
    old_value: str  # as expat decodes it (what xacro reads)
    new_value: str


def _edit(old: bytes, new: bytes) -> Edit:
    """1. The attribute value the edit changes, or :class:`Refused`."""
    if old == new:
        raise Refused("nothing changed")
    declared = ENCODING_RE.match(new)
    if declared is not None and declared.group(1).lower().replace(b"-", b"") != b"utf8":
        raise Refused("the file is not UTF-8")
    prefix = _common_prefix(old, new)
    suffix = _common_suffix(old, new, min(len(old), len(new)) - prefix)
    change_end = len(new) - suffix  # the changed bytes of new are [prefix, change_end)
    tag, name, attrs, nested = _enclosing(new, prefix)
    end = TAG_END_RE.match(new, tag + 1)
    if end is None:
        raise Refused("the start tag has no end")
    for attr in VALUE_RE.finditer(new, tag + 1, end.end()):
        group = 2 if attr.group(2) is not None else 3
        begin, stop = attr.span(group)
        if begin <= prefix and change_end <= stop:
            break
    else:
        raise Refused("the edit is not inside one attribute value")
    attribute = attr.group(1)
    delta = len(new) - len(old)
    raw_old, raw_new = old[begin : stop - delta], new[begin:stop]
    for raw in (raw_old, raw_new):
        if b"$" in raw or b"\n" in raw or b"\r" in raw:
            raise Refused("a value is an expression or spans lines")
    if name.startswith("xacro:") or b":" in attribute or attribute == b"xmlns":
        raise Refused(f"<{name} {attribute.decode('utf-8', 'replace')}> is read by xacro")
    if nested:
        raise Refused("a xacro:attribute inside the element may set its attributes")
    old_attrs = _attributes(old[tag : end.end() - delta])
    key = attribute.decode("utf-8")
    if list(old_attrs) != list(attrs) or any(old_attrs[k] != attrs[k] for k in attrs if k != key):
        raise Refused("the old and new start tags differ elsewhere")  # never: same bytes
    before, after = old_attrs[key], attrs[key]
    for value in (before, after):
        if "$" in value or "\t" in value or "\n" in value or "\r" in value:
            raise Refused("a value is an expression or holds line breaks")
    return Edit(tag, prefix, attribute, before, after)


def _enclosing(data: bytes, offset: int) -> tuple[int, str, dict[str, str], bool]:
    """The last start tag expat reports at or before ``offset`` in the well-formed ``data``:
    its offset, name, attributes, and whether a ``xacro:attribute`` is inside the element."""
    parser = xml.parsers.expat.ParserCreate("utf-8")
    parser.ordered_attributes = True
    found: list[Any] = [None, "", [], False]  # offset, name, attributes, xacro:attribute inside
    depth = [0, -1]  # the current depth, the found element's (-1: closed or none)

    def start(name: str, attributes: list[str]) -> None:
        at = parser.CurrentByteIndex
        if at <= offset:
            found[:] = [at, name, attributes, False]
            depth[1] = depth[0]
        elif depth[1] >= 0 and name == "xacro:attribute":
            found[3] = True
        depth[0] += 1

    def end(name: str) -> None:
        depth[0] -= 1
        if depth[0] == depth[1]:
            depth[1] = -1

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    try:
        parser.Parse(data, True)
    except xml.parsers.expat.ExpatError as exc:
        raise Refused(f"the new text is not well-formed: {exc}") from None
    if found[0] is None:
        raise Refused("the edit is before the first start tag")
    pairs = found[2]
    return found[0], found[1], dict(zip(pairs[::2], pairs[1::2], strict=True)), found[3]


def _attributes(tag: bytes) -> dict[str, str]:
    """The attributes of one start tag, as expat decodes them."""
    if not tag.endswith(b"/>"):
        tag = tag[:-1] + b"/>"
    parser = xml.parsers.expat.ParserCreate("utf-8")
    parser.ordered_attributes = True
    found: list[str] = []
    parser.StartElementHandler = lambda name, attributes: found.extend(attributes)
    try:
        parser.Parse(tag, True)
    except xml.parsers.expat.ExpatError as exc:
        raise Refused(f"the old start tag does not parse: {exc}") from None
    return dict(zip(found[::2], found[1::2], strict=True))


def _written(value: str) -> bytes:
    """``value`` as minidom's ``toprettyxml`` writes an attribute value (UTF-8)."""
    element = minidom.Document().createElement("a")
    element.setAttribute("v", value)
    text = element.toxml()
    if not (text.startswith('<a v="') and text.endswith('"/>')):
        raise Refused("minidom writes attributes in an unexpected way")
    return text[6:-3].encode("utf-8")


def _common_prefix(a: bytes, b: bytes) -> int:
    """Length of the common prefix (slices compared by halves: memcmp, not a Python loop)."""
    low, high = 0, min(len(a), len(b))
    while low < high:
        mid = (low + high + 1) // 2
        if a[low:mid] == b[low:mid]:
            low = mid
        else:
            high = mid - 1
    return low


def _common_suffix(a: bytes, b: bytes, limit: int) -> int:
    """Length of the common suffix, at most ``limit``."""
    low, high = 0, limit
    while low < high:
        mid = (low + high + 1) // 2
        if a[len(a) - mid : len(a) - low] == b[len(b) - mid : len(b) - low]:
            low = mid
        else:
            high = mid - 1
    return low
