"""Pinocchio's and urdfdom's refusals, translated into a sentence that names the element.

urdfdom writes its reasons through console_bridge on file descriptors 1 and 2, not in
the exception: :func:`captured_output` collects them while the model is built.
"""

from __future__ import annotations

import os
import re
import sys
import tempfile
import threading
from collections.abc import Iterator
from contextlib import contextmanager, suppress
from typing import TYPE_CHECKING, Any

from urdflint.model.values import fmt, number

if TYPE_CHECKING:
    from lxml import etree

    from urdflint.model.document import Document

LOCATION_RE = re.compile(r"\s*at line \d+ in \S+")
GENERIC = (
    "joint xml is not initialized correctly",
    "the xml stream does not contain a valid urdf model",
)
LIMIT_RE = re.compile(r"min_(\w+?) (?:are|is) greater than max_\1|min_(\w+) > max_\2")
NAMED_RE = re.compile(r"\b(joint|link|material)\s+(?:\[\s*([^\]]*?)\s*\]|'([^']*)')", re.I)


def messages(captured: str) -> list[str]:
    """urdfdom's error lines without C++ source locations, each once, in order."""
    found: list[str] = []
    for raw in captured.splitlines():
        line = LOCATION_RE.sub("", raw).strip()
        if not line:
            continue
        for prefix in ("Error:", "Warning:", "Info:", "Debug:"):
            if line.startswith(prefix):
                line = line[len(prefix) :].strip()
                break
        if line and line not in found:
            found.append(line)
    return found


def translate(doc: Document, error: str, captured: str = "") -> tuple[str, etree._Element | None]:
    """A sentence naming the element for a Pinocchio/urdfdom refusal, and that element."""
    error = LOCATION_RE.sub("", error).strip()
    limit = LIMIT_RE.search(error)
    if limit:
        what = limit.group(1) or limit.group(2)
        found = _negative_limit(doc, what)
        if found is not None:
            return found
    lines = [m for m in messages(captured) if m.lower().rstrip(".") not in GENERIC]
    specific = lines[0] if lines else error
    element = next(
        (el for el in (_named(doc, m) for m in [specific, *lines]) if el is not None), None
    )
    return f"Pinocchio refuses the model: {_sentence(specific)}", element


def _sentence(text: str) -> str:
    text = LOCATION_RE.sub("", text).strip().rstrip(".")
    return text[:1].lower() + text[1:] if text[:2] != text[:2].upper() else text


def _named(doc: Document, message: str) -> etree._Element | None:
    """The first joint, link or material the message names that exists in the document."""
    tables: dict[str, dict[str, Any]] = {
        "joint": doc.joint_map,
        "link": doc.link_map,
        "material": doc.material_map,
    }
    for kind, table in tables.items():
        for match in NAMED_RE.finditer(message):
            if match.group(1).lower() != kind:
                continue
            name = match.group(2) if match.group(2) is not None else match.group(3)
            item = table.get(name)
            if item is not None:
                return item if kind == "material" else item.element
    return None


LIMIT_SOURCES = {
    "effort": ("limit", "effort"),
    "velocity": ("limit", "velocity"),
    "dry_friction": ("dynamics", "friction"),
    "friction": ("dynamics", "friction"),
    "damping": ("dynamics", "damping"),
}


def _negative_limit(doc: Document, what: str) -> tuple[str, etree._Element] | None:
    """Pinocchio checks ``-x <= x`` for effort, velocity and friction without naming the joint."""
    source = LIMIT_SOURCES.get(what)
    if source is None:
        return None
    tag, attr = source
    for joint in doc.joints:
        el = joint.find(tag)
        value = number(el, attr)
        if el is not None and value is not None and value < 0:
            sentence = (
                f"Pinocchio refuses the model: joint '{joint.name}' has {attr} {fmt(value)} in its "
                f"<{tag}>, and Pinocchio uses the range -{attr}..{attr}, so min_{what} > max_{what}"
            )
            return sentence, el
    return None


_LOCK = threading.Lock()


@contextmanager
def captured_output() -> Iterator[list[str]]:
    """Capture what C++ code writes to file descriptors 1 and 2 (urdfdom's console_bridge)."""
    out: list[str] = []
    with _LOCK:
        for stream in (sys.stdout, sys.stderr):
            with suppress(AttributeError, ValueError, OSError):
                stream.flush()
        saved: list[tuple[int, int]] = []
        with tempfile.TemporaryFile() as sink:
            try:
                for fd in (1, 2):
                    try:
                        saved.append((fd, os.dup(fd)))
                        os.dup2(sink.fileno(), fd)
                    except OSError:
                        continue
                yield out
            finally:
                for fd, copy in saved:
                    os.dup2(copy, fd)
                    os.close(copy)
                sink.seek(0)
                out.append(sink.read().decode("utf-8", "replace"))
