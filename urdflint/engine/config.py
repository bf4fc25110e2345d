"""Configuration: ``[tool.urdflint]`` in ``pyproject.toml`` or a ``urdflint.toml``.

Discovery walks up from the checked file's folder; the first ``.urdflint.toml``,
``urdflint.toml`` or ``pyproject.toml`` that has a ``[tool.urdflint]`` table wins.
Unknown keys, rule codes, severities and targets are errors naming the key.
"""

from __future__ import annotations

import fnmatch
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from urdflint.engine import registry, statics_settings
from urdflint.engine.stability_config import StabilitySettings, parse_stability
from urdflint.model import targets
from urdflint.model.finding import Severity

FILENAMES = (".urdflint.toml", "urdflint.toml", "pyproject.toml")
FAIL_ON = ("error", "warning", "info", "never")
KEYS = frozenset({
    "select", "extend-select", "ignore", "severity", "per-file-ignores", "fail-on", "targets",
    "rules", "package-paths", "expect", "xacro-args", "per-file-xacro-args", "confirm", "srdf",
    "profile", "cache-dir", "cache-max-size", "stability", "statics",
})  # fmt: skip
PROFILES = ("mobile", "industrial", "humanoid")  # the conventions rules (N family) to run
ENGINES = ("mujoco", "pybullet", "drake", "pinocchio", "sdformat")  # --confirm: the E rules
EXPECT_KEYS = frozenset({"mass", "mass-tolerance", "com", "com-tolerance", "q"})


class ConfigError(Exception):
    """An invalid configuration file or option; the CLI exits 2 with this message."""


@dataclass(frozen=True)
class Expect:
    """What the robot must weigh and where its centre of mass must be (P003, P004).

    ``mass_tolerance`` is a fraction of ``mass``; ``mass_abs_tolerance`` (from
    ``--expect-mass 12.3±0.2``) wins when set. The COM is in the root link's frame,
    at configuration ``q`` (joint name -> value; the neutral one otherwise).
    """

    mass: float | None = None
    mass_tolerance: float = 0.02
    mass_abs_tolerance: float | None = None
    com: tuple[float, float, float] | None = None
    com_tolerance: float = 0.01
    q: dict[str, float] = field(default_factory=dict)

    def mass_band(self) -> float:
        """The allowed absolute deviation from ``mass`` in kg."""
        if self.mass_abs_tolerance is not None:
            return self.mass_abs_tolerance
        return abs(self.mass or 0.0) * self.mass_tolerance


@dataclass(frozen=True)
class Settings:
    """The effective configuration for one file (file settings plus CLI overrides)."""

    select: tuple[str, ...] | None = None
    extend_select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()
    severity: dict[str, Severity | None] = field(default_factory=dict)  # None = off
    per_file_ignores: tuple[tuple[str, tuple[str, ...]], ...] = ()
    fail_on: str = "error"
    targets: tuple[str, ...] = ()  # none given: inferred per file (urdflint.engine.inference)
    rule_options: dict[str, dict[str, Any]] = field(default_factory=dict)
    package_paths: dict[str, Path] = field(default_factory=dict)  # resolved against the file
    expect: Expect = field(default_factory=Expect)
    xacro_args: dict[str, str] = field(default_factory=dict)
    per_file_xacro_args: tuple[tuple[str, dict[str, str]], ...] = ()
    source: Path | None = None  # the file these settings came from
    confirm: tuple[str, ...] = ()  # engines that load the model (E rules; --confirm)
    srdf: Path | None = None  # the MoveIt SRDF of the robot (M rules; else found beside it)
    profile: str | None = None  # "mobile", "industrial" or "humanoid": REP conventions
    cache_dir: Path | None = None  # where the analysis cache lives (not a lint setting)
    cache_max_size: int | None = None  # its size limit in bytes (not a lint setting)
    stability: StabilitySettings = field(default_factory=StabilitySettings)  # D003, info
    statics: statics_settings.StaticsSettings = statics_settings.DEFAULT  # D001, D002, info

    def xacro_args_for(self, path: str) -> dict[str, str]:
        """``xacro-args``, then each matching ``per-file-xacro-args`` table (later wins)."""
        found = dict(self.xacro_args)
        for pattern, table in self.per_file_xacro_args:
            if self._matches(path, pattern):
                found.update(table)
        return found

    def _matches(self, path: str, pattern: str) -> bool:
        base = self.source.parent if self.source else Path.cwd()
        try:
            rel = Path(path).resolve().relative_to(base.resolve()).as_posix()
        except ValueError:
            rel = Path(path).as_posix()
        return fnmatch.fnmatch(rel, pattern) or fnmatch.fnmatch(Path(rel).name, pattern)

    def enabled(self) -> set[str]:
        """Codes of the rules that run."""
        # only the selected families are imported
        codes = set(registry.load_rules()) if self.select is None else registry.expand(self.select)
        codes |= registry.expand(self.extend_select)
        codes -= registry.expand(self.ignore)
        codes -= {code for code, level in self.severity.items() if level is None}
        return codes

    def ignored_for(self, path: str) -> set[str]:
        """Codes switched off for ``path`` by ``per-file-ignores``."""
        if not self.per_file_ignores:
            return set()
        base = self.source.parent if self.source else Path.cwd()
        try:
            rel = Path(path).resolve().relative_to(base.resolve()).as_posix()
        except ValueError:
            rel = Path(path).as_posix()
        codes: set[str] = set()
        for pattern, selectors in self.per_file_ignores:
            if fnmatch.fnmatch(rel, pattern) or fnmatch.fnmatch(Path(rel).name, pattern):
                codes |= registry.expand(selectors)
        return codes

    def options(self, code: str) -> dict[str, Any]:
        rule = registry.RULES[code]
        return {**rule.options, **self.rule_options.get(code, {})}


def _strings(key: str, value: Any) -> tuple[str, ...]:
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise ConfigError(f"'{key}' must be a list of strings")
    return tuple(value)


def _selectors(key: str, value: Any) -> tuple[str, ...]:
    found = _strings(key, value)
    try:
        registry.expand(found)
    except ValueError as exc:
        raise ConfigError(f"'{key}': {exc}") from None
    return found


def from_mapping(data: dict[str, Any], source: Path | None = None) -> Settings:
    """Validate a ``[tool.urdflint]`` table (or the same keys from the HTTP API)."""
    if not isinstance(data, dict):
        raise ConfigError("the urdflint configuration must be a table")
    unknown = sorted(set(data) - KEYS)
    if unknown:
        raise ConfigError(
            f"unknown configuration key '{unknown[0]}' (known: {', '.join(sorted(KEYS))})"
        )
    settings = Settings(source=source)
    if "select" in data:
        settings = replace(settings, select=_selectors("select", data["select"]))
    if "extend-select" in data:
        settings = replace(
            settings, extend_select=_selectors("extend-select", data["extend-select"])
        )
    if "ignore" in data:
        settings = replace(settings, ignore=_selectors("ignore", data["ignore"]))
    if "fail-on" in data:
        if data["fail-on"] not in FAIL_ON:
            raise ConfigError(
                f"'fail-on' must be one of {', '.join(FAIL_ON)}, not {data['fail-on']!r}"
            )
        settings = replace(settings, fail_on=data["fail-on"])
    if "targets" in data:
        try:
            settings = replace(
                settings, targets=targets.validate(_strings("targets", data["targets"]))
            )
        except ValueError as exc:
            raise ConfigError(f"'targets': {exc}") from None
    if "severity" in data:
        settings = replace(settings, severity=_severity_table(data["severity"]))
    if "per-file-ignores" in data:
        table = data["per-file-ignores"]
        if not isinstance(table, dict):
            raise ConfigError("'per-file-ignores' must be a table of glob = [codes]")
        pairs = tuple(
            (glob, _selectors(f"per-file-ignores.{glob}", codes)) for glob, codes in table.items()
        )
        settings = replace(settings, per_file_ignores=pairs)
    if "rules" in data:
        settings = replace(settings, rule_options=_rule_options(data["rules"]))
    if "confirm" in data:
        settings = replace(
            settings, confirm=engines("confirm", _strings("confirm", data["confirm"]))
        )
    return _inputs(settings, data, source)


def engines(key: str, names: tuple[str, ...]) -> tuple[str, ...]:
    """Engine names for ``confirm`` (``all`` = every one), validated, in the given order."""
    found: list[str] = []
    for name in (n.strip().lower() for n in names):
        if name == "all":
            found.extend(ENGINES)
        elif name in ENGINES:
            found.append(name)
        elif name:
            raise ConfigError(
                f"'{key}': unknown engine {name!r} (known: {', '.join(ENGINES)}, all)"
            )
    return tuple(dict.fromkeys(found))


def _inputs(settings: Settings, data: dict[str, Any], source: Path | None) -> Settings:
    """The keys about the model's inputs: package paths, expectations, xacro arguments."""
    if "package-paths" in data:
        base = source.parent if source is not None else Path.cwd()
        settings = replace(settings, package_paths=_package_paths(data["package-paths"], base))
    if "expect" in data:
        settings = replace(settings, expect=_expect(data["expect"]))
    if "xacro-args" in data:
        table = data["xacro-args"]
        if not isinstance(table, dict) or not all(
            isinstance(v, (str, int, float, bool)) for v in table.values()
        ):
            raise ConfigError("'xacro-args' must be a table of name = value")
        settings = replace(settings, xacro_args=_xacro_table("xacro-args", table))
    if "per-file-xacro-args" in data:
        table = data["per-file-xacro-args"]
        if not isinstance(table, dict) or not all(isinstance(v, dict) for v in table.values()):
            raise ConfigError("'per-file-xacro-args' must be a table of glob = {name = value}")
        pairs = tuple(
            (str(glob), _xacro_table(f"per-file-xacro-args.{glob}", args))
            for glob, args in table.items()
        )
        settings = replace(settings, per_file_xacro_args=pairs)
    if "srdf" in data:
        if not isinstance(data["srdf"], str) or not data["srdf"].strip():
            raise ConfigError("'srdf' must be the path of an SRDF file")
        base = source.parent if source is not None else Path.cwd()
        settings = replace(settings, srdf=base / data["srdf"])
    if "profile" in data:
        settings = replace(settings, profile=profile("profile", data["profile"]))
    settings = replace(settings, statics=statics_settings.read(data, ConfigError))
    if "stability" in data:
        settings = replace(settings, stability=parse_stability(data["stability"], ConfigError))
    if "cache-dir" in data or "cache-max-size" in data:
        from urdflint.cache import configured

        try:
            folder, size = configured(data, source.parent if source is not None else Path.cwd())
        except ValueError as exc:
            raise ConfigError(str(exc)) from None
        settings = replace(settings, cache_dir=folder, cache_max_size=size)
    return settings


def profile(key: str, value: Any) -> str:
    """A conventions profile name (``mobile``, ``industrial`` or ``humanoid``)."""
    if value not in PROFILES:
        raise ConfigError(f"'{key}' must be one of {', '.join(PROFILES)}, not {value!r}")
    return str(value)


def _xacro_table(key: str, table: dict[str, Any]) -> dict[str, str]:
    if not all(isinstance(v, (str, int, float, bool)) for v in table.values()):
        raise ConfigError(f"'{key}' must be a table of name = value")
    return {str(k): _arg_text(v) for k, v in table.items()}


def _arg_text(value: object) -> str:
    return str(value).lower() if isinstance(value, bool) else str(value)


def _package_paths(table: Any, base: Path) -> dict[str, Path]:
    if not isinstance(table, dict) or not all(isinstance(v, str) for v in table.values()):
        raise ConfigError("'package-paths' must be a table of package = \"folder\"")
    return {str(name): (base / folder) for name, folder in table.items()}


def _number(key: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ConfigError(f"'{key}' must be a number")
    return float(value)


def _expect(table: Any) -> Expect:
    if not isinstance(table, dict):
        raise ConfigError("'expect' must be a table (mass, mass-tolerance, com, com-tolerance, q)")
    unknown = sorted(set(table) - EXPECT_KEYS)
    if unknown:
        raise ConfigError(
            f"unknown configuration key 'expect.{unknown[0]}' "
            f"(known: {', '.join(sorted(EXPECT_KEYS))})"
        )
    expect = Expect()
    if "mass" in table:
        expect = replace(expect, mass=_number("expect.mass", table["mass"]))
    if "mass-tolerance" in table:
        tolerance = _number("expect.mass-tolerance", table["mass-tolerance"])
        if not 0 <= tolerance < 1:
            raise ConfigError(
                "'expect.mass-tolerance' is a fraction of the mass, from 0 to 1 (0.02 = 2 %)"
            )
        expect = replace(expect, mass_tolerance=tolerance)
    if "com" in table:
        com = table["com"]
        if not isinstance(com, list) or len(com) != 3:
            raise ConfigError("'expect.com' must be [x, y, z] in metres")
        expect = replace(expect, com=tuple(_number("expect.com", v) for v in com))  # type: ignore[arg-type]
    if "com-tolerance" in table:
        expect = replace(
            expect, com_tolerance=_number("expect.com-tolerance", table["com-tolerance"])
        )
    if "q" in table:
        q = table["q"]
        if not isinstance(q, dict):
            raise ConfigError("'expect.q' must be a table of joint = value")
        expect = replace(expect, q={str(k): _number(f"expect.q.{k}", v) for k, v in q.items()})
    return expect


def _severity_table(table: Any) -> dict[str, Severity | None]:
    if not isinstance(table, dict):
        raise ConfigError("'severity' must be a table of CODE = \"error|warning|info|off\"")
    result: dict[str, Severity | None] = {}
    for key, level in table.items():
        found = registry.lookup(key)
        if found is None:
            raise ConfigError(f"'severity.{key}': unknown rule {key!r}")
        if level == "off":
            result[found.code] = None
            continue
        try:
            result[found.code] = Severity.parse(str(level))
        except ValueError as exc:
            raise ConfigError(f"'severity.{key}': {exc} or off") from None
    return result


def _rule_options(table: Any) -> dict[str, dict[str, Any]]:
    if not isinstance(table, dict):
        raise ConfigError("'rules' must be a table of [rules.CODE] option tables")
    result: dict[str, dict[str, Any]] = {}
    for key, options in table.items():
        found = registry.lookup(key)
        if found is None:
            raise ConfigError(f"'rules.{key}': unknown rule {key!r}")
        if not isinstance(options, dict):
            raise ConfigError(f"'rules.{key}' must be a table of options")
        for name, value in options.items():
            if name not in found.options:
                known = ", ".join(found.options) or "none"
                raise ConfigError(
                    f"unknown option 'rules.{key}.{name}' (options of {found.code}: {known})"
                )
            default = found.options[name]
            if isinstance(default, (int, float)) and not isinstance(default, bool):
                if not isinstance(value, (int, float)) or isinstance(value, bool):
                    raise ConfigError(f"'rules.{key}.{name}' must be a number")
            elif not isinstance(value, type(default)):
                raise ConfigError(f"'rules.{key}.{name}' must be a {type(default).__name__}")
        result[found.code] = dict(options)
    return result


def load(path: Path) -> Settings:
    """Read and validate one configuration file."""
    import tomllib  # only when there is a configuration file

    try:
        with path.open("rb") as handle:
            data = tomllib.load(handle)
    except OSError as exc:
        raise ConfigError(f"cannot read {path}: {exc.strerror or exc}") from None
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{path}: invalid TOML: {exc}") from None
    if path.name == "pyproject.toml":
        data = data.get("tool", {}).get("urdflint", {})
    try:
        return from_mapping(data, path.resolve())
    except ConfigError as exc:
        raise ConfigError(f"{path}: {exc}") from None


def discover(start: Path) -> Path | None:
    """The nearest configuration file at or above ``start`` (a folder)."""
    for folder in (start, *start.parents):
        for name in FILENAMES:
            candidate = folder / name
            if not candidate.is_file():
                continue
            if name != "pyproject.toml":
                return candidate
            import tomllib

            try:
                with candidate.open("rb") as handle:
                    if "urdflint" in tomllib.load(handle).get("tool", {}):
                        return candidate
            except (OSError, tomllib.TOMLDecodeError):
                continue
    return None
