"""Options given on the command line and to the HTTP API, and the settings they make.

Values: ``NAME=VALUE`` pairs, joint
positions and mass/COM expectations (``12.3±0.2``, ``12.3+-2%``, ``0,0,0.4±0.005``).

Each parser raises ``argparse.ArgumentTypeError`` with a one-line reason, which argparse
turns into a usage error and the service into a 422.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import Any

from urdflint.engine import config, registry, statics_settings
from urdflint.model import targets
from urdflint.model.values import parse_number


def pair(sep: str) -> Callable[[str], tuple[str, str]]:
    def parse(text: str) -> tuple[str, str]:
        name, found, value = text.partition(sep)
        if not found or not name.strip():
            raise argparse.ArgumentTypeError(f"expected NAME{sep}VALUE, got {text!r}")
        return name.strip(), value.strip()

    return parse


def number(text: str, what: str) -> float:
    value = parse_number(text.strip())
    if value is None:
        raise argparse.ArgumentTypeError(f"{what} {text!r} is not a number")
    return value


def joint_value(text: str) -> tuple[str, float]:
    name, value = pair("=")(text)
    return name, number(value, f"joint {name!r} value")


def split_tolerance(text: str) -> tuple[str, str | None]:
    for sep in ("±", "+-", "+/-"):
        if sep in text:
            value, _, tolerance = text.partition(sep)
            return value, tolerance
    return text, None


def expect_mass(text: str) -> tuple[float, float | None, float | None]:
    """``12.3`` / ``12.3±0.2`` / ``12.3+-2%`` -> (mass, absolute tolerance, fraction)."""
    value, tolerance = split_tolerance(text)
    mass = number(value, "mass")
    if tolerance is None:
        return mass, None, None
    if tolerance.strip().endswith("%"):
        return mass, None, number(tolerance.strip()[:-1], "tolerance") / 100
    return mass, number(tolerance, "tolerance"), None


def expect_com(text: str) -> tuple[tuple[float, float, float], float | None]:
    value, tolerance = split_tolerance(text)
    parts = value.replace(",", " ").split()
    if len(parts) != 3:
        raise argparse.ArgumentTypeError(f"expected X,Y,Z[±TOL], got {text!r}")
    com = tuple(number(p, "coordinate") for p in parts)
    return com, (number(tolerance, "tolerance") if tolerance is not None else None)  # type: ignore[return-value]


def engine_list(text: str) -> tuple[str, ...]:
    """``--confirm mujoco,pybullet`` (or ``all``): the engines that load the model."""
    try:
        return config.engines("--confirm", tuple(text.split(",")))
    except config.ConfigError as exc:
        raise argparse.ArgumentTypeError(str(exc).replace("'--confirm': ", "")) from None


def target_list(text: str) -> tuple[str, ...]:
    """``--target mujoco,drake`` (or ``all``): the consumers the model is meant for."""
    names = tuple(name.strip() for name in text.split(",") if name.strip())
    try:
        targets.validate(names or (text,))
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    return names


class UsageError(Exception):
    """A wrong option value: the CLI prints it and exits 2, the service answers 422."""


def overrides(args: argparse.Namespace) -> dict[str, object]:
    flat = {key: [c for group in getattr(args, key) for c in group] for key in ("select", "ignore")}
    for key, selectors in flat.items():
        try:
            registry.expand(selectors)
        except ValueError as exc:
            raise UsageError(f"--{key}: {exc}") from None
    found: dict[str, object] = {}
    if args.select:
        found["select"] = tuple(flat["select"])
    if flat["ignore"]:
        found["ignore"] = tuple(flat["ignore"])
    if args.exit_zero:
        found["fail_on"] = "never"
    elif args.fail_on:
        found["fail_on"] = args.fail_on
    if args.target:
        found["targets"] = targets.validate([t for group in args.target for t in group])
    if args.xacro_arg:
        found["xacro_args"] = dict(args.xacro_arg)
    confirm = [e for group in getattr(args, "confirm", None) or () for e in group]
    if confirm:
        found["confirm"] = tuple(dict.fromkeys(confirm))
    if getattr(args, "srdf", None):
        found["srdf"] = Path(args.srdf)
    if getattr(args, "profile", None):
        found["profile"] = args.profile
    given: dict[str, dict[str, Any]] = {}
    if getattr(args, "density", None) is not None:  # --density: I001's unsafe fix
        given["I001"] = {"density": args.density}
    if getattr(args, "write_meshes", False):  # C001's unsafe fix for mesh visuals
        given["C001"] = {"write_meshes": True}
    if given:
        found["rule_options"] = given
    return found


class SettingsFinder:
    """Effective settings per file: discovered (or given) config plus CLI overrides."""

    def __init__(self, args: argparse.Namespace) -> None:
        self.overrides = overrides(args) if args.command in ("check", "fix") else {}
        if args.command == "info" and args.xacro_arg:
            self.overrides["xacro_args"] = dict(args.xacro_arg)
        self.expect_mass = getattr(args, "expect_mass", None)
        self.expect_com = getattr(args, "expect_com", None)
        self.q = dict(args.q)
        self.statics = (getattr(args, "payload", None), getattr(args, "gravity", None))
        self.isolated = args.isolated
        self.explicit = config.load(args.config) if args.config else None
        self.cache: dict[Path, config.Settings] = {}
        self.base = config.Settings()  # --isolated's, and a folder without configuration's
        self.applied: dict[int, tuple[config.Settings, config.Settings]] = {}  # id(base) ->

    def _apply_once(self, settings: config.Settings) -> config.Settings:
        """:meth:`_apply`, one object per configuration: the files of a folder share their
        settings (a run over thousands of files digests each settings once)."""
        known = self.applied.get(id(settings))
        if known is None or known[0] is not settings:
            known = self.applied[id(settings)] = (settings, self._apply(settings))
        return known[1]

    def for_folder(self, folder: Path) -> config.Settings:
        if self.explicit is not None:
            return self._apply_once(self.explicit)
        if self.isolated:
            return self._apply_once(self.base)
        folder = folder.resolve()
        if folder not in self.cache:
            found = config.discover(folder)
            self.cache[folder] = config.load(found) if found else self.base
        return self._apply_once(self.cache[folder])

    def _apply(self, settings: config.Settings) -> config.Settings:
        extra: dict[str, Any] = dict(self.overrides)
        if "ignore" in extra:
            extra["ignore"] = settings.ignore + tuple(extra["ignore"])
        if "rule_options" in extra:  # the command line's options win, the others stay
            given = extra["rule_options"]
            codes = {*settings.rule_options, *given}
            extra["rule_options"] = {
                c: {**settings.rule_options.get(c, {}), **given.get(c, {})} for c in codes
            }
        if "xacro_args" in extra:
            given = extra["xacro_args"]
            extra["xacro_args"] = {**settings.xacro_args, **given}
            # the command line wins over per-file tables too: applied last, for every file
            extra["per_file_xacro_args"] = (*settings.per_file_xacro_args, ("*", given))
        expect = settings.expect
        if self.expect_mass is not None:
            mass, absolute, fraction = self.expect_mass
            expect = replace(expect, mass=mass, mass_abs_tolerance=absolute)
            if fraction is not None:
                expect = replace(expect, mass_tolerance=fraction)
        if self.expect_com is not None:
            com, tolerance = self.expect_com
            expect = replace(expect, com=com)
            if tolerance is not None:
                expect = replace(expect, com_tolerance=tolerance)
        if self.q:
            expect = replace(expect, q={**expect.q, **self.q})
        statics = statics_settings.apply(settings.statics, *self.statics)
        return replace(settings, expect=expect, statics=statics, **extra)
