"""What an engine printed: its warnings and errors, each mapped to the element it concerns.

Each engine prints in its own way: PyBullet ``b3Warning[file,line]:`` followed by the
message (and sometimes the link's name as a second message), Drake Python log records
(``WARNING:drake:FILE:LINE: warning: ...``), urdfdom (Pinocchio) ``Warning:`` / ``Error:``
lines followed by the C++ source location, MuJoCo ``WARNING:`` lines in ``MUJOCO_LOG.TXT``,
sdformat ``Error [parser_urdf.cc:3023] ...`` / ``Warning [...] ...`` lines (coloured; the
bracket is sdformat's own source location, dropped) and urdfdom's ``Error:`` lines (the
probe prints the errors ``sdf::Root::Load`` returned as ``Error [Root::Load] ...``).
A message is mapped to the element at the line it names, else to the first link or joint
whose name it quotes (or mentions), else to the robot.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from lxml import etree

from urdflint.model.document import Document

NOISE = re.compile(r"^(pybullet build time:|\s*at line \d+ in \S+$|argv\[\d+\]=)")
BULLET = re.compile(r"(b3(?:Warning|Error|Printf)\[[^\]]*\]:|\bWarning:|\bError:)\s*")
LEVEL = re.compile(r"^\s*(?:\[[^\]]*\]\s*)*(?:\[(warning|error)\]|(WARNING|ERROR|Warning|Error)"
                   r"(?::drake)?:)\s*(.*)$")  # fmt: skip
WHERE = re.compile(r"^(?P<file>\S+?):(?P<line>\d+):\s*(?:(?:warning|error):\s*)?")
ELEMENT = re.compile(r"Element '(?P<tag>\w+)', line (?P<line>\d+)")
SOURCE = re.compile(r"Failure at \S+ in ")
COLOUR = re.compile(r"\x1b\[[0-9;]*m")
SDFORMAT = re.compile(r"^\s*(Error|Warning|Msg|Dbg) \[[^\]\s]*\]\s*(.*)$")


@dataclass(frozen=True)
class Message:
    """One thing an engine said, and the element it concerns (``None``: the robot)."""

    text: str
    element: etree._Element | None = None


def clean(text: str, temporary: str, shown: str) -> list[str]:
    """The printed lines, the temporary file's name replaced by the document's, and other
    paths in the temporary folder (a missing mesh) by paths beside the document."""
    folder = temporary.rsplit("/", 1)[0] + "/" if "/" in temporary else None
    beside = shown.rsplit("/", 1)[0] + "/" if "/" in shown else ""
    text = text.replace(temporary, shown)
    if folder:
        text = text.replace(folder, beside)
    text = COLOUR.sub("", text)
    return [line.rstrip() for line in text.splitlines() if line.strip() and not NOISE.match(line)]


def classify(doc: Document, engine: str, lines: list[str]) -> tuple[list[Message], list[Message]]:
    """The distinct warnings and errors among the printed lines, in order."""
    if engine == "pybullet":
        found = _bullet(doc, "\n".join(lines))
    else:
        found = [kind for line in lines if (kind := _level(engine, line)) is not None]
    warnings: dict[str, Message] = {}
    errors: dict[str, Message] = {}
    for level, text in found:
        if not text:
            continue
        message = locate(doc, text)
        target = errors if level == "error" else warnings
        target.setdefault(message.text, message)
    return list(warnings.values()), list(errors.values())


def _level(engine: str, line: str) -> tuple[str, str] | None:
    """``(level, message)`` of a warning or error line (sdformat's or the common forms)."""
    match = SDFORMAT.match(line) if engine == "sdformat" else None
    if match:
        kind = match.group(1).lower()
        return (kind, match.group(2).strip()) if kind in ("error", "warning") else None
    match = LEVEL.match(line)
    if match:
        return (match.group(1) or match.group(2)).lower(), match.group(3).strip()
    return None


def _bullet(doc: Document, text: str) -> list[tuple[str, str]]:
    """PyBullet prints ``b3Warning[...]:`` or ``Warning:`` and a message without a newline,
    then often the link's or joint's name as another message."""
    names = set(doc.link_map) | set(doc.joint_map)
    parts = BULLET.split(text)
    found: list[tuple[str, str]] = []
    for marker, body in zip(parts[1::2], parts[2::2], strict=True):
        body = " ".join(body.split())
        if "Printf" in marker:
            continue
        kind = "error" if "Error" in marker else "warning"
        if found and body in names and found[-1][0] == kind:
            found[-1] = (kind, f"{found[-1][1].rstrip(': ')}: {body}")
            continue
        found.append((kind, body))
    return found


def locate(doc: Document, text: str) -> Message:
    """``text`` without the file prefix, and the element it names by line or by name."""
    where = WHERE.match(text)
    line = int(where.group("line")) if where else None
    text = SOURCE.sub("", text[where.end() :] if where else text).strip()
    tag = None
    element = ELEMENT.search(text)
    if element:
        tag, line = element.group("tag"), int(element.group("line"))
    found = _at_line(doc, line, tag) if line and line > 1 else None
    return Message(text, found if found is not None else named(doc, text))


def _at_line(doc: Document, line: int, tag: str | None) -> etree._Element | None:
    for element in doc.robot.iter():
        if not isinstance(element.tag, str) or element is doc.robot:
            continue
        if (tag is None or element.tag == tag) and doc.start_of(element)[0] <= line <= (
            element.sourceline or 0
        ):
            return element
    return None


QUOTED = re.compile(r"""['"\[]([^'"\[\]\s]+)['"\]]""")
WORD = re.compile(r"[\w.\-/]+")


def named(doc: Document, text: str) -> etree._Element | None:
    """The first link or joint the text quotes, else the first one it mentions."""
    for pattern in (QUOTED, WORD):
        for token in pattern.findall(text):
            found = doc.joint_map.get(token) or doc.link_map.get(token)
            if found is not None:
                return found.element
    return None


def refusal(doc: Document, errors: list[Message], raised: list[str]) -> Message:
    """Why the engine refused: what it printed as an error, else its exception's message."""
    if errors:
        return errors[0]
    whole = " ".join(raised)
    first = raised[0] if raised else "no reason given"
    first = re.sub(r"^\w+(Error|Exception|error): ", "", first)
    message = locate(doc, first)
    if message.element is None:
        hint = ELEMENT.search(whole)
        if hint:
            message = Message(message.text, locate(doc, hint.group(0)).element)
    return message
