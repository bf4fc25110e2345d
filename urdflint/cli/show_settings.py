"""``urdflint check --show-settings``: the settings each file would be checked with, and why.

Per file: the configuration file that applies (or none, or ``--isolated``), the targets and
how they were chosen (given with ``--target``, configured, inferred from evidence in the
model and its package, or assumed), the rules (select, ignore, the per-file ignores that
match, severities, options), fail-on, the xacro arguments, the package paths, the SRDF,
profile, engines and expectations, the statics (payload, gravity: D001, D002, ``info
--statics``) and stability settings (contact links and tolerance, samples: D003), the cache,
and each package name the file uses (``package://``, ``$(find)``) with the folder it resolves
to and why (:mod:`urdflint.cli.show_packages`). Each value says where it came from: ``command
line``, the configuration file, or ``default``. The file is read (xacro expanded) for the
targets and packages, but no rule runs. ``--format json`` writes the same as JSON.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from dataclasses import replace
from pathlib import Path
from typing import IO, Any

from urdflint.cli import show_packages
from urdflint.cli.common import UsageError
from urdflint.engine import config, linter, registry, statics_settings
from urdflint.engine.stability_config import StabilitySettings
from urdflint.model.document import Document
from urdflint.model.values import fmt
from urdflint.sources import package_xml

DEFAULT = "default"
MAX_EVIDENCE = 3  # reasons listed per target in the text (JSON lists every one)
COMMAND_LINE = "command line"


def write(
    args: argparse.Namespace, files: list[str], context: Any, finder: Any, out: IO[str]
) -> None:
    found = [describe(args, name, context, finder) for name in files]
    if args.format == "json":
        out.write(json.dumps({"version": 1, "files": found}, indent=2) + "\n")
    else:
        out.write("\n".join(render(one) for one in found))
    out.flush()


def describe(args: argparse.Namespace, name: str, context: Any, finder: Any) -> dict[str, Any]:
    """The settings of one file, as JSON data (see the module docstring)."""
    shown = args.stdin_filename if name == "-" else name
    try:
        settings = finder.for_folder(Path.cwd() if name == "-" else Path(name).parent)
    except config.ConfigError as exc:
        raise UsageError(str(exc)) from None
    doc, problem = _document(name, shown, settings, context)
    return {
        "path": shown,
        "configuration": _configuration(args, settings),
        "targets": _targets(doc, settings, finder),
        **_rules(shown, settings, finder),
        "fail-on": _value("fail_on", settings.fail_on, "error", settings, finder),
        "xacro-args": settings.xacro_args_for(shown) if linter.is_xacro(shown) else None,
        "package-paths": _package_paths(settings, context),
        "srdf": _value("srdf", _text(settings.srdf), None, settings, finder),
        "profile": _value("profile", settings.profile, None, settings, finder),
        "confirm": _value("confirm", list(settings.confirm), [], settings, finder),
        "expect": _expect(settings, finder),
        "statics": _statics(settings, finder),
        "stability": _stability(settings, finder),
        "cache": _cache(args, context),
        "packages": _packages(doc, context),
        "problem": problem,
    }


def _document(name: str, shown: str, settings: Any, context: Any) -> tuple[Any, str | None]:
    """The file read as a check reads it (xacro expanded), and why it could not be."""
    try:
        if name == "-":
            data = sys.stdin.buffer.read()
            doc = Document(shown, data, targets=frozenset(settings.targets), settings=settings,
                           context=context, base_dir=Path.cwd())  # fmt: skip
        else:
            doc = linter.load(Path(name), shown, settings, context)
    except OSError as exc:
        return None, f"cannot read: {exc.strerror or exc}"
    problem = doc.problem.message if doc.problem is not None else None
    return doc, problem


def _text(value: Any) -> str | None:
    return None if value is None else str(value)


def _from(
    key: str, value: Any, default: Any, settings: Any, finder: Any, given: bool = False
) -> str:
    """Where a value came from: the command line, the configuration file, or the default."""
    given = given or key in finder.overrides
    if given or (key == "expect" and (finder.expect_mass or finder.expect_com)):
        return COMMAND_LINE
    if value != default and settings.source is not None:
        return _shown(settings.source)
    return DEFAULT


def _value(key: str, value: Any, default: Any, settings: Any, finder: Any) -> dict[str, Any]:
    return {"value": value, "from": _from(key, value, default, settings, finder)}


def _configuration(args: argparse.Namespace, settings: Any) -> dict[str, Any]:
    if args.isolated:
        return {"file": None, "how": "--isolated"}
    if settings.source is None:
        return {"file": None, "how": "none found"}
    return {"file": _shown(settings.source), "how": "--config" if args.config else "found"}


def _targets(doc: Any, settings: Any, finder: Any) -> dict[str, Any]:
    if settings.targets:
        how = "given" if "targets" in finder.overrides else "configured"
        return {"names": list(settings.targets), "how": how, "evidence": [],
                "from": _from("targets", settings.targets, (), settings, finder)}  # fmt: skip
    if doc is None:
        return {"names": [], "how": "unknown", "evidence": [], "from": DEFAULT}
    found = linter.targets_of(doc, settings).to_dict()
    unique = {tuple(e.values()): e for e in found["evidence"]}  # a macro's plugin, N times
    return {**found, "evidence": list(unique.values()), "from": DEFAULT}


def _rules(shown: str, settings: Any, finder: Any) -> dict[str, Any]:
    """select, ignore (configured, then the command line's), per-file ignores that match,
    severities, rule options, and how many rules are on for the file."""
    given = tuple(finder.overrides.get("ignore", ()))
    configured = settings.ignore[: len(settings.ignore) - len(given)]
    matching = [
        {"pattern": pattern, "codes": list(codes)}
        for pattern, codes in settings.per_file_ignores
        if replace(settings, per_file_ignores=((pattern, codes),)).ignored_for(shown)
    ]
    enabled = settings.enabled() - settings.ignored_for(shown)
    severity = {code: str(level) if level is not None else "off"
                for code, level in sorted(settings.severity.items())}  # fmt: skip
    return {
        "select": _value("select", _list(settings.select), None, settings, finder),
        "extend-select": list(settings.extend_select),
        "ignore": {"configuration": list(configured), COMMAND_LINE: list(given)},
        "per-file-ignores": matching,
        "severity": severity,
        "rule-options": {code: dict(o) for code, o in sorted(settings.rule_options.items())},
        "rules": {"enabled": len(enabled), "of": len(registry.load_rules())},
    }


def _list(value: Any) -> list[str] | None:
    return None if value is None else list(value)


def _package_paths(settings: Any, context: Any) -> list[dict[str, str]]:
    found = [{"name": name, "folder": str(folder), "from": _shown(settings.source) if
              settings.source else DEFAULT} for name, folder in settings.package_paths.items()
             if name not in context.package_paths]  # fmt: skip
    found += [{"name": name, "folder": str(folder), "from": COMMAND_LINE}
              for name, folder in context.package_paths.items()]  # fmt: skip
    return sorted(found, key=lambda p: p["name"])


def _expect(settings: Any, finder: Any) -> dict[str, Any]:
    expect = settings.expect
    value = None
    if expect.mass is not None or expect.com is not None or expect.q:
        value = {
            "mass": expect.mass,
            "mass-band": expect.mass_band() if expect.mass is not None else None,  # ± kg
            "com": list(expect.com) if expect.com is not None else None,
            "com-tolerance": expect.com_tolerance if expect.com is not None else None,
            "q": dict(expect.q),
        }
    return {"value": value, "from": _from("expect", value, None, settings, finder)}


def _statics(settings: Any, finder: Any) -> dict[str, Any]:
    """The payload and the gravity (``--payload``/``--gravity`` win over the configuration)."""
    found, (given_payload, given_gravity) = settings.statics, finder.statics
    payload = {"kg": found.payload, "link": found.payload_link}  # link None: the tool
    gravity = list(found.gravity)
    return {
        "payload": {"value": payload, "from": _from("payload", payload, {"kg": 0, "link": None},
                                                    settings, finder, given_payload is not None)},
        "gravity": {"value": gravity, "from": _from("gravity", gravity, [*statics_settings.EARTH],
                                                    settings, finder, given_gravity is not None)},
    }  # fmt: skip


def _stability(settings: Any, finder: Any) -> dict[str, Any]:
    """``[tool.urdflint.stability]``: contact links (empty: found), tolerance (m), samples."""
    found, default = settings.stability, StabilitySettings()
    return {k.replace("_", "-"): _value(k, getattr(found, k), getattr(default, k), settings,
            finder) for k in ("contact_links", "contact_tolerance", "samples")}  # fmt: skip


def _cache(args: argparse.Namespace, context: Any) -> dict[str, Any]:
    cache = context.cache
    if cache is not None:
        return {"folder": str(cache.folder), "max-size": cache.store.max_bytes, "why": None}
    if args.no_cache:
        why = "--no-cache"
    elif os.environ.get("URDFLINT_NO_CACHE", "") not in ("", "0"):
        why = "URDFLINT_NO_CACHE is set"
    else:
        why = "its folder cannot be used"
    return {"folder": None, "max-size": None, "why": why}


def _packages(doc: Any, context: Any) -> list[dict[str, Any]]:
    """Each package name the file uses, in the order written, where it resolves and why."""
    if doc is None:
        return []
    found: list[dict[str, Any]] = []
    for name in dict.fromkeys(use.name for use in package_xml.package_uses(doc)):
        lookup = doc.resolver.lookup(name)
        folder, how, ties = show_packages.answer(lookup, context)
        found.append({
            "name": name,
            "folder": folder if lookup.folder is not None else None,
            "how": how if lookup.folder is not None else None,
            "ties": list(ties),
            "tried": list(lookup.tried),
        })  # fmt: skip
    return found


def _shown(path: Path) -> str:
    full = os.path.abspath(path)
    here = os.getcwd()
    return os.path.relpath(full, here) if full.startswith(here + os.sep) else full


# -- text ------------------------------------------------------------------------------------


def render(one: dict[str, Any]) -> str:
    """The text listing of one file's settings."""
    rows = _rows(one)
    width = max(len(label) for label, _ in rows) + 2
    lines = [one["path"]]
    for label, text in rows:
        first, *rest = text.split("\n")
        lines.append(f"  {label:<{width}}{first}")
        lines.extend(f"  {'':<{width}}{line}" for line in rest)
    return "\n".join(lines) + "\n"


def _rows(one: dict[str, Any]) -> list[tuple[str, str]]:
    ignores = (f'"{p["pattern"]}" = {", ".join(p["codes"])}' for p in one["per-file-ignores"])
    severity = (f"{code} = {level}" for code, level in one["severity"].items())
    options = (f"{code}: {values}" for code, values in one["rule-options"].items())
    paths = (f"{p['name']} = {p['folder']} ({p['from']})" for p in one["package-paths"])
    rows = [
        ("configuration", _configuration_text(one["configuration"])),
        ("targets", _targets_text(one["targets"])),
        ("select", _select_text(one)),
        ("ignore", _ignore_text(one["ignore"])),
        ("per-file-ignores", _pairs(ignores) or "none matches"),
        ("rules", f"{one['rules']['enabled']} of {one['rules']['of']} selected for this file"),
        ("severity", _pairs(severity) or "as each rule says"),
        ("rule options", _pairs(options) or "defaults"),
        ("fail-on", _valued(one["fail-on"])),
        ("xacro-args", _xacro_text(one["xacro-args"])),
        ("package-paths", _pairs(paths) or "none"),
        ("srdf", _valued(one["srdf"], "found beside the file or through its package")),
        ("profile", _valued(one["profile"], "none: the N rules do not run")),
        ("confirm", _valued(one["confirm"], "none: no engine loads the model")),
        ("expect", _expect_text(one["expect"])),
        ("statics", _statics_text(one["statics"])),
        ("stability", _stability_text(one["stability"])),
        ("cache", _cache_text(one["cache"])),
        ("packages", _packages_text(one["packages"])),
    ]
    if one["problem"]:
        rows.append(("read", one["problem"]))
    return rows


def _pairs(items: Any) -> str:
    return "\n".join(items)


def _valued(entry: dict[str, Any], empty: str = "none") -> str:
    value = entry["value"]
    if value in (None, [], {}):
        return f"{empty} ({entry['from']})"
    if isinstance(value, list):
        value = ", ".join(value)
    elif isinstance(value, dict):
        value = ", ".join(f"{k} {v}" for k, v in value.items() if v not in (None, {}, []))
    return f"{value} ({entry['from']})"


def _configuration_text(found: dict[str, Any]) -> str:
    if found["how"] == "--isolated":
        return "none (--isolated)"
    if found["file"] is None:
        return "none found at or above the file (defaults)"
    return found["file"] + (" (--config)" if found["how"] == "--config" else "")


def _targets_text(found: dict[str, Any]) -> str:
    names = ", ".join(found["names"]) or "?"
    how = found["how"]
    if how == "given":
        return f"{names}: given (--target)"
    if how == "configured":
        return f"{names}: configured ({found['from']})"
    if how == "unknown":
        return "unknown: the file could not be read"
    assumed = ", nothing in the model or its package names a simulator" if how == "assumed" else ""
    lines = [f"{names}: {how}{assumed}"]
    shown: dict[str, int] = {}
    for e in found["evidence"]:
        shown[e["target"]] = shown.get(e["target"], 0) + 1
        if shown[e["target"]] <= MAX_EVIDENCE:
            place = f"{e['path']}:{e['line']}" if e["path"] and e["line"] else e["path"]
            lines.append(f"  {e['target']}: {e['why']}" + (f" ({place})" if place else ""))
    for target, count in shown.items():
        if count > MAX_EVIDENCE:
            lines.append(f"  {target}: and {count - MAX_EVIDENCE} more (--format json lists them)")
    return "\n".join(lines)


def _select_text(one: dict[str, Any]) -> str:
    select = one["select"]
    text = _valued(select, "every rule")
    if one["extend-select"]:
        text += f"; extend-select {', '.join(one['extend-select'])}"
    return text


def _ignore_text(found: dict[str, Any]) -> str:
    parts = [f"{', '.join(codes)} ({where})" for where, codes in
             (("configuration", found["configuration"]), (COMMAND_LINE, found[COMMAND_LINE]))
             if codes]  # fmt: skip
    return "; ".join(parts) or "nothing"


def _expect_text(found: dict[str, Any]) -> str:
    value = found["value"]
    if value is None:
        return f"nothing: P003 and P004 do not run ({found['from']})"
    parts = []
    if value["mass"] is not None:
        parts.append(f"mass {value['mass']:g} ± {value['mass-band']:g} kg")
    if value["com"] is not None:
        com = ", ".join(f"{c:g}" for c in value["com"])
        parts.append(f"com {com} ± {value['com-tolerance']:g} m")
    if value["q"]:
        parts.append("q " + " ".join(f"{k}={v:g}" for k, v in value["q"].items()))
    return f"{'; '.join(parts)} ({found['from']})"


def _statics_text(found: dict[str, Any]) -> str:
    kg, link = found["payload"]["value"].values()
    held = replace(statics_settings.DEFAULT, payload=kg, payload_link=link).describe()
    vector = ", ".join(fmt(g) for g in found["gravity"]["value"])
    return (f"payload: {held if kg else 'none'} ({found['payload']['from']})\n"
            f"gravity: {vector} m/s², root link frame ({found['gravity']['from']})")  # fmt: skip


def _stability_text(found: dict[str, Any]) -> str:
    links, tolerance, samples = found.values()
    named = ", ".join(links["value"]) or "found by the heuristic"
    return (f"contact-links: {named} ({links['from']})\n"
            f"contact-tolerance: {fmt(tolerance['value'])} m ({tolerance['from']})\n"
            f"samples: {samples['value']} ({samples['from']})")  # fmt: skip


def _xacro_text(found: dict[str, str] | None) -> str:
    if found is None:
        return "none (not a xacro file)"
    return " ".join(f"{k}:={v}" for k, v in found.items()) or "none"


def _cache_text(found: dict[str, Any]) -> str:
    if found["folder"] is None:
        return f"not used ({found['why']})"
    return f"{found['folder']} (limit {found['max-size'] / 2**20:.0f} MiB)"


def _packages_text(found: list[dict[str, Any]]) -> str:
    lines = []
    for p in found:
        if p["folder"] is None:
            looked = "; ".join(p["tried"]) or "nothing"
            lines.append(f"{p['name']}: not found (looked at: {looked})")
            continue
        ties = f"; as near: {', '.join(p['ties'])} (C017)" if p["ties"] else ""
        lines.append(f"{p['name']}: {p['folder']} ({p['how']}{ties})")
    return "\n".join(lines) or "none used"
