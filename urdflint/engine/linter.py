"""Runs the rules over a document and stamps their hits into findings."""

from __future__ import annotations

import contextlib
import contextvars
import gc
import logging
import os
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field, replace
from pathlib import Path

from lxml import etree

from urdflint.cache import deps
from urdflint.engine import fixes, instances, registry, suppress
from urdflint.engine.causes import BLOCKING  # the static errors that explain a P001
from urdflint.engine.config import Settings
from urdflint.engine.context import Context
from urdflint.engine.inference import Targets
from urdflint.engine.registry import Hit, Rule
from urdflint.model import memo, optional, targets
from urdflint.model.document import Document
from urdflint.model.effects import for_targets
from urdflint.model.finding import Call, Finding, Severity

log = logging.getLogger(__name__)

LIBRARY_FAMILIES = frozenset({"X", "U"})  # what a xacro library file (no <link>) gets
# A file that is not well-formed is checked on the tree libxml2 recovers: its findings say so.
# Pinocchio reads the file itself, not that tree, so the physics family does not run. A file
# whose XML declaration or stray leading text was only blanked out (doc.repairs) is not
# recovered: its tree is the one TinyXML reads, so every rule runs and nothing is marked.
RECOVERED = " (from the part of the file that could be read after the X001 error)"
RECOVERED_SKIPS = frozenset({"P", "D"})  # Pinocchio: the physics and statics families
EXTRAS = optional.EXTRAS


@dataclass
class Result:
    """What linting one file produced."""

    path: str
    findings: list[Finding]
    document: Document | None = None
    skipped: dict[str, tuple[str, ...]] = field(default_factory=dict)  # code -> missing modules
    ran: tuple[str, ...] = ()  # codes of the rules that ran to completion on the document
    targets: Targets | None = None  # the targets the findings are for, and how chosen

    @property
    def crashed(self) -> bool:
        return any(f.code == "U001" for f in self.findings)


XACRO_SUFFIXES = (".xacro",)

# Set by a caller that may abandon a run (the language server, when a newer edit arrives):
# asked between rules, and a run whose answer is True stops with :class:`Superseded`.
_STOP: contextvars.ContextVar[Callable[[], bool] | None] = contextvars.ContextVar(
    "urdflint_stop", default=None
)


class Superseded(Exception):
    """A run stopped at a rule boundary because its caller no longer wants the answer."""


@contextlib.contextmanager
def stoppable(stop: Callable[[], bool]) -> Iterator[None]:
    """Runs inside this block end early (:class:`Superseded`) once ``stop()`` is true."""
    token = _STOP.set(stop)
    try:
        yield
    finally:
        _STOP.reset(token)


def is_xacro(path: str) -> bool:
    return path.lower().endswith(XACRO_SUFFIXES)


def lint_bytes(
    source: bytes,
    path: str,
    settings: Settings | None = None,
    context: Context | None = None,
    base_dir: Path | None = None,
) -> Result:
    """Lint one URDF given as bytes; ``path`` is for display, ``base_dir`` for relative meshes."""
    settings = settings or Settings()
    doc = Document(
        path,
        source,
        targets=frozenset(settings.targets),
        settings=settings,
        context=context,
        base_dir=base_dir,
    )
    return lint_document(doc, settings)


def load(path: Path, shown: str, settings: Settings, context: Context | None = None) -> Document:
    """A file on disk as a document: a URDF, or a xacro file expanded first (no ROS needed)."""
    context = context or Context()
    if is_xacro(shown):
        from urdflint.sources import xacro as xacro_input

        return xacro_input.document(path, shown, settings, context)
    unsaved = context.overlay.get(os.path.abspath(path))  # an editor's buffer (urdflint lsp)
    if unsaved is not None:
        deps.note_content(path, unsaved)
    return Document(
        shown,
        unsaved if unsaved is not None else path.read_bytes(),
        targets=frozenset(settings.targets),
        settings=settings,
        context=context,
        base_dir=path.parent,
    )


def lint_path(path: Path, shown: str, settings: Settings, context: Context | None = None) -> Result:
    """Lint a file on disk (see :func:`load`)."""
    return lint_document(load(path, shown, settings, context), settings)


def lint_document(doc: Document, settings: Settings) -> Result:
    # The rules allocate objects by the hundred thousand on a big model and leave next to no
    # reference cycles: the cyclic collector, which would walk every live object again and
    # again as they pile up (a 10-25% share of an 8,000-link check), waits until they ran.
    chosen = targets_of(doc, settings)
    if not chosen.given:
        settings = replace(settings, targets=chosen.names)
    doc.targets = frozenset(chosen.names)
    pause = gc.isenabled()
    if pause:
        gc.disable()
    try:
        result = _lint_document(doc, settings)
        result.targets = chosen
        return result
    finally:
        memo.forget()  # the per-element results the rules shared: nothing outlives the run
        if pause:
            gc.enable()


def targets_of(doc: Document, settings: Settings) -> Targets:
    """The targets ``settings`` give (``--target``, the configuration), else those the model
    and its package show (:mod:`urdflint.engine.inference`)."""
    if settings.targets:
        return Targets(tuple(settings.targets), given=True)
    from urdflint.engine import inference

    return inference.infer(doc)


def _lint_document(doc: Document, settings: Settings) -> Result:
    enabled = settings.enabled() - settings.ignored_for(doc.path)
    rules = registry.RULES  # enabled() imported the families it names
    raw: list[tuple[Rule, Hit]] = []
    skipped: dict[str, tuple[str, ...]] = {}
    ran: list[str] = []
    stop = _STOP.get()
    for code in sorted(enabled):
        if stop is not None and stop():
            raise Superseded(doc.path)
        rule = rules[code]
        if not _applies(rule, doc, settings):
            continue
        missing = tuple(m for m in rule.needs if not optional.available(m))
        if missing:
            skipped[code] = missing
            continue
        hits = _run(rule, doc, settings)
        raw.extend(hits)
        if not (code != "U001" and hits and hits[0][0].code == "U001"):
            ran.append(code)  # a crashed rule is reported by its U001 error instead

    directives: list[suppress.Directive] = []
    if doc.root is not None:
        directives, malformed = suppress.parse(doc.robot)
        if "U003" in enabled:
            ran.append("U003")
            raw.extend((rules["U003"], Hit(m.comment, m.message)) for m in malformed)

    findings: list[Finding] = []
    hushed: list[Finding] = []  # suppressed by a comment: still a cause P001 need not restate
    for rule, hit in raw:
        covering = (
            [d for d in directives if d.covers(rule.code, hit.element, doc.root)]
            if doc.root is not None
            else []
        )
        if covering:
            for directive in covering:
                directive.used.add(rule.code)
            if rule.code in BLOCKING:
                hushed.append(stamp(doc, rule, hit, settings))
            continue
        findings.append(stamp(doc, rule, hit, settings))
    if "U002" in enabled:
        ran.append("U002")
        findings.extend(_unused(doc, directives, enabled, settings))
    findings = _one_cause(doc, findings, hushed)
    findings.sort(key=Finding.sort_key)
    if doc.origin is not None:
        findings = instances.merge(findings)
    return Result(doc.path, findings, doc, skipped, tuple(sorted(ran)))


def _applies(rule: Rule, doc: Document, settings: Settings) -> bool:
    """Whether ``rule`` runs on ``doc`` at all."""
    if rule.requires_robot and doc.root is None:
        return False
    if doc.recovered and rule.family in RECOVERED_SKIPS:
        return False
    if doc.library and rule.family not in LIBRARY_FAMILIES:
        return False
    if rule.targets and rule.targets.isdisjoint(settings.targets):
        return False  # a target rule for consumers this run does not aim at
    if rule.code in ("U002", "U003"):
        return False  # produced from the suppressions themselves, after the rules
    # nothing asked of it: it does not run, and reports (JUnit) do not list it
    return not _dormant(rule.code, settings)


def _dormant(code: str, settings: Settings) -> bool:
    """A rule with nothing to do under these settings: the E rules without ``--confirm``,
    the N rules without a ``--profile``, P003/P004 without an expected mass/COM (or q)."""
    if code.startswith("E"):
        return not settings.confirm
    if code.startswith("N"):
        return settings.profile is None
    if code == "P003":
        return settings.expect.mass is None
    if code == "P004":  # it also checks the configuration --q names
        return settings.expect.com is None and not settings.expect.q
    return False


def _one_cause(doc: Document, findings: list[Finding], hushed: list[Finding]) -> list[Finding]:
    """One defect, one finding: a P001 whose refusal or misreading is the consequence of a
    static finding that is reported, or suppressed by a comment (``hushed``: the user knows
    the cause), goes (its ``blocker``); a reported cause carries the
    Pinocchio effect instead (when Pinocchio is a target and its own table says nothing for
    Pinocchio: a rule's table is what the engines were observed to do)."""
    if "physics" not in doc.__dict__ or not any(f.code == "P001" for f in findings):
        return findings
    physics = doc.physics
    cause = physics.blocker
    if cause is None:
        return findings
    element = doc.element_path(cause.element) if cause.element is not None else None
    matches = [
        f for f in [*findings, *hushed]
        if (f.code, f.line) == (cause.code, cause.line) and element in (None, f.element)
    ]  # fmt: skip
    if not matches:
        return findings  # the cause is ignored or suppressed: P001 is the only word on it
    from urdflint.model import effects as fx

    detail = (physics.reason or "").split(f" (see {cause.code} ")[0]  # it is this finding
    detail = detail.split(f" ({cause.code} on ")[0].split(f"; {cause.code} on ")[0]
    detail += ")" * (detail.count("(") - detail.count(")"))
    effect = fx.refused(detail)
    if physics.misread:  # a zero axis builds another joint; an unread <inertial>, a zero one
        effect = fx.changed(detail) if cause.code == "J007" else fx.substituted(detail)
    kept = []
    for f in findings:
        if f.code == "P001":
            continue
        if f is matches[0] and "pinocchio" in doc.targets and "pinocchio" not in dict(f.effects):
            others = tuple((t, e) for t, e in f.effects if t != "pinocchio")
            chosen = targets.ordered(doc.targets)
            merged = dict(others) | {"pinocchio": effect}
            f = replace(f, effects=tuple((t, merged[t]) for t in chosen if t in merged))
        kept.append(f)
    return kept


def _run(rule: Rule, doc: Document, settings: Settings) -> list[tuple[Rule, Hit]]:
    """The rule's hits, or one U001 internal-error hit if the rule raised."""
    try:
        if rule.options:
            hits = list(rule.check(doc, settings.options(rule.code)))
        else:
            hits = list(rule.check(doc))
    except Exception as exc:  # a broken rule must not stop the run
        log.debug("rule %s crashed on %s", rule.code, doc.path, exc_info=True)
        message = f"rule {rule.code} {rule.name} crashed: {type(exc).__name__}: {exc}"
        return [(registry.RULES["U001"], Hit(None, message, line=1))]
    return [(rule, hit) for hit in hits]


def _unused(
    doc: Document, directives: list[suppress.Directive], enabled: set[str], settings: Settings
) -> Iterable[Finding]:
    rule = registry.RULES["U002"]
    for directive in directives:
        unused = sorted(
            code for code in directive.codes if code in enabled and code not in directive.used
        )
        if unused and not directive.used:
            what = (
                "file"
                if directive.target is None
                else f"<{etree.QName(directive.target).localname}>"
            )
            hit = Hit(
                directive.comment,
                f"suppression of {', '.join(unused)} on this {what} matched no finding",
                line=None if doc.origin is not None else directive.line,
            )
            yield stamp(doc, rule, hit, settings)


def stamp(doc: Document, rule: Rule, hit: Hit, settings: Settings) -> Finding:
    """Turn a rule's hit into a finding: path, line, column, element, code, severity."""
    element = hit.element
    line, column = _position(doc, hit)
    chosen = targets.ordered(doc.targets)
    if hit.effects is not None:
        effects = tuple((t, hit.effects[t]) for t in chosen if t in hit.effects)
    else:
        effects = for_targets(rule.effects, hit.variant, chosen)
    configured = settings.severity.get(rule.code)
    severity = configured or hit.severity or rule.severity
    if rule.by_target and effects and not (configured or hit.severity):
        severity = max(effect.level for _, effect in effects)
    shown, message = hit.path or doc.path, hit.message
    if doc.recovered and rule.code != "X001":
        message += RECOVERED
    trace: tuple[Call, ...] = ()
    anchor = element if element is not None else doc.root  # robot-level: the <robot> tag
    if doc.origin is not None and anchor is not None and not hit.line:
        origin = doc.origin(anchor, hit.attribute if anchor is element else None)
        if origin is not None:
            shown, line, column, trace = origin.path, origin.line, origin.column, origin.trace
            if not origin.exact:
                message += f" (line {line} of the expanded document; see --emit-expanded)"
    path = (
        doc.element_path(element)
        if not isinstance(element, etree._Comment)
        else _comment_path(doc, element)
    )
    return Finding(
        path=shown,
        line=max(int(line), 1),
        column=max(int(column), 1),
        code=rule.code,
        name=rule.name,
        severity=Severity(severity),
        message=message,
        element=path,
        fix=hit.fix or rule.fix,
        trace=trace,
        effects=effects,
        engine=hit.engine,
        autofix=fixes.resolve(doc, hit.repair) if hit.repair is not None else None,
    )


def _position(doc: Document, hit: Hit) -> tuple[int, int]:
    """Where the hit is in the document's own text: the given line, the attribute the rule
    points at, or the start of the element's tag (libxml2 gives the line it ends on)."""
    element = hit.element
    if hit.line:
        return hit.line, hit.column or 1
    if element is None or isinstance(element, etree._Comment) or not element.sourceline:
        if element is None and doc.root is not None:
            return doc.start_of(doc.root)
        return (element.sourceline or 1) if element is not None else 1, 1
    if hit.attribute:
        found = doc.attribute_at(element, hit.attribute)
        if found is not None:
            return found
    return doc.start_of(element)


def _comment_path(doc: Document, comment: etree._Element) -> str:
    parent = comment.getparent()
    return doc.element_path(parent) if parent is not None else "/robot"
