"""``urdflint mcp``: a real MCP client (the SDK's stdio client) against ``python -m urdflint mcp``.

The tools answer what the CLI answers (one verdict), paths and the files a lint reads stay
inside the client's roots, fixes write only when asked and only there, and bad input is a
finding, never a traceback. Tests that need the SDK skip without it (the ``mcp`` extra).
Importing the SDK takes a server about 3 s: the tests share sessions (module fixtures).
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import shutil
import subprocess
import sys
from collections.abc import AsyncIterator, Awaitable, Callable
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import FIXTURES, ROOT
from tests.test_lazy_loading import imported_after
from urdflint.cli import main

BROKEN = FIXTURES / "models" / "broken_arm.urdf"
SMALL = FIXTURES / "models" / "example_arm.urdf"
MALFORMED = FIXTURES / "rules" / "X001" / "bad.urdf"
BROKEN_SHOWN, SMALL_SHOWN = str(BROKEN.relative_to(ROOT)), str(SMALL.relative_to(ROOT))
MALFORMED_SHOWN = str(MALFORMED.relative_to(ROOT))
TOOLS = ["check", "fix", "explain", "info", "matrix"]
Scenario = Callable[[Any], Awaitable[dict[str, Any]]]


def sdk() -> None:
    """Skip unless the SDK's 2.x API is installed (``pip install -e '.[mcp]'``)."""
    pytest.importorskip("mcp.client.stdio")
    from importlib.metadata import version

    if int(version("mcp").split(".")[0]) < 2:
        pytest.skip("urdflint mcp needs the mcp 2.x SDK")


def cli(*args: str) -> str:
    """What ``urdflint ARGS`` run from the repository prints."""
    out = io.StringIO()
    with contextlib.chdir(ROOT), contextlib.redirect_stdout(out):
        assert main(list(args)) in (0, 1)
    return out.getvalue()


@contextlib.asynccontextmanager
async def connect(
    cwd: Path, roots: list[Path] | None = None, options: tuple[str, ...] = ()
) -> AsyncIterator[Any]:
    """A session with ``python -m urdflint mcp [OPTIONS]`` started in ``cwd``; the client
    lists ``roots`` (``None``: the client has no roots capability)."""
    from mcp import ClientSession, StdioServerParameters, types
    from mcp.client.stdio import stdio_client

    async def listed(context: Any) -> Any:
        assert roots is not None
        return types.ListRootsResult(roots=[types.Root(uri=r.as_uri()) for r in roots])

    server = StdioServerParameters(
        command=sys.executable,
        args=["-m", "urdflint", "mcp", *options],
        cwd=str(cwd),
        env={"URDFLINT_CACHE_DIR": os.environ.get("URDFLINT_CACHE_DIR", "")},
    )
    with open(os.devnull, "w") as errlog:
        async with (
            stdio_client(server, errlog=errlog) as (read, write),
            ClientSession(read, write, list_roots_callback=listed if roots else None) as session,
        ):
            await session.initialize()
            yield session


def talk(
    cwd: Path, scenario: Scenario, roots: list[Path] | None = None, options: tuple[str, ...] = ()
) -> dict[str, Any]:
    """Run ``scenario(session)`` against a fresh server; what it returns."""
    import anyio

    async def main() -> dict[str, Any]:
        async with connect(cwd, roots, options) as session:
            return await scenario(session)

    return anyio.run(main)


def refused(result: Any) -> str:
    """The one line of a tool error."""
    assert result.is_error
    text = result.content[0].text
    assert "\n" not in text and "Traceback" not in text
    return str(text)


def codes(result: Any) -> list[str]:
    assert not result.is_error, result.content[0].text
    return [f["code"] for f in result.structured_content["findings"]]


def timeless(info: dict[str, Any]) -> dict[str, Any]:
    """``info --statics`` JSON without the time the statics took."""
    return {**info, "statics": {k: v for k, v in info["statics"].items() if k != "seconds"}}


# -- from the repository, no roots: one verdict ------------------------------------------------


@pytest.fixture(scope="module")
def repository(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    sdk()
    elsewhere = tmp_path_factory.mktemp("elsewhere") / "arm.urdf"
    shutil.copy(SMALL, elsewhere)

    async def scenario(session: Any) -> dict[str, Any]:
        call = session.call_tool
        return {
            **await _bad_input(session),
            "elsewhere": await call("check", {"paths": [str(elsewhere)]}),
            "tools": await session.list_tools(),
            "check": await call("check", {"paths": [BROKEN_SHOWN]}),
            "short": await call("explain", {"rule": "J009"}),
            "long": await call("explain", {"rule": "inverted-limits", "long": True}),
            "unknown": await call("explain", {"rule": "Q999"}),
            "info": await call("info", {"path": SMALL_SHOWN}),
            "statics": await call("info", {"path": SMALL_SHOWN, "statics": True}),
            "matrix": await call("matrix", {"paths": [BROKEN_SHOWN]}),
            "resources": await session.list_resources(),
            "templates": await session.list_resource_templates(),
            "rules": await session.read_resource("urdflint://rules"),
            "page": await session.read_resource("urdflint://rules/J009"),
            "lint": await call("lint", {}),
        }

    return talk(ROOT, scenario)  # no roots: the working directory, the repository


def test_a_client_lists_the_tools_and_check_is_urdflint_check_format_json(
    repository: dict[str, Any],
) -> None:
    assert [tool.name for tool in repository["tools"].tools] == TOOLS
    expected = json.loads(cli("check", "--format", "json", BROKEN_SHOWN))
    result = repository["check"]
    assert not result.is_error
    assert result.structured_content["findings"] == expected["findings"]
    assert result.structured_content == expected  # the whole envelope: summary, targets...
    text = result.content[0].text
    assert "urdflint: 12 errors, 3 warnings, 2 infos in 1 file" in text
    assert "2 fixable with the fix tool (2 more with unsafe=true)" in text
    assert "unknown tool 'lint'" in refused(repository["lint"])


def test_explain_info_matrix_and_the_resources_are_what_the_cli_prints(
    repository: dict[str, Any],
) -> None:
    got = repository
    assert got["short"].content[0].text == cli("explain", "J009")
    assert got["long"].content[0].text == cli("explain", "J009", "--long")
    assert "unknown rule 'Q999'" in refused(got["unknown"])
    info = json.loads(cli("info", "--format", "json", SMALL_SHOWN))
    assert got["info"].structured_content == info
    assert got["info"].content[0].text == cli("info", SMALL_SHOWN).rstrip("\n")
    statics = json.loads(cli("info", "--statics", "--format", "json", SMALL_SHOWN))
    assert timeless(got["statics"].structured_content) == timeless(statics)
    expected = json.loads(cli("check", "--matrix", "--format", "json", BROKEN_SHOWN))
    assert got["matrix"].structured_content["matrix"] == expected["matrix"]
    assert "Drake              crashes" in got["matrix"].content[0].text
    assert [str(r.uri) for r in got["resources"].resources] == ["urdflint://rules"]
    templates = [t.uri_template for t in got["templates"].resource_templates]
    assert templates == ["urdflint://rules/{code}"]
    assert json.loads(got["rules"].contents[0].text) == json.loads(cli("rules", "--format", "json"))
    assert got["page"].contents[0].text == cli("explain", "J009", "--long")


# -- a root the client gives: fixes and confinement ----------------------------------------------


def _world(folder: Path) -> tuple[Path, Path]:
    """A root holding models that reach outside it, and the folder outside."""
    root, outside = folder / "root", folder / "outside"
    (root / "sub").mkdir(parents=True)
    outside.mkdir()
    shutil.copy(BROKEN, root / "arm.urdf")
    shutil.copy(BROKEN, outside / "arm.urdf")
    shutil.copy(SMALL, folder / "here.urdf")  # the server's working directory: not a root
    (outside / "secret.xacro").write_text('<robot><link name="secret_link"/></robot>\n')
    (outside / "m.stl").write_text("solid m\nendsolid m\n")
    (root / "link.urdf").symlink_to(outside / "arm.urdf")
    xacro = '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">{}<link name="a"/></robot>'
    include = '<xacro:include filename="{}/secret.xacro"/>'
    (root / "include.urdf.xacro").write_text(xacro.format(include.format("../outside")))
    (root / "find.urdf.xacro").write_text(xacro.format(include.format("$(find out)")))
    mesh = '<mesh filename="../outside/m.stl"/>'
    (root / "mesh.urdf").write_text(SMALL.read_text().replace('<box size="0.2 0.2 0.1"/>', mesh))
    return root, outside


async def _fixing(session: Any, root: Path, outside: Path) -> dict[str, Any]:
    from urdflint.model.edits import Edit, apply

    call, done = session.call_tool, {}
    done["before"] = await call("check", {"paths": ["arm.urdf"]})  # the first root's
    done["preview"] = await call("fix", {"paths": ["arm.urdf"]})
    done["untouched"] = (root / "arm.urdf").read_bytes()
    fixes = done["preview"].structured_content["fixes"]
    edits = [Edit(e["path"], *e["offsets"], e["content"]) for f in fixes for e in f["edits"]]
    done["applied"], done["later"] = apply(BROKEN.read_bytes(), edits)
    text = done["applied"].decode()
    done["as_text"] = await call("check", {"text": text, "name": "arm.urdf"})
    done["write"] = await call("fix", {"paths": ["arm.urdf"], "write": True})
    done["written"] = (root / "arm.urdf").read_bytes()
    done["after"] = await call("check", {"paths": ["arm.urdf"]})
    done["outside"] = await call("fix", {"paths": [str(outside / "arm.urdf")], "write": True})
    done["text_write"] = await call("fix", {"text": text, "name": "x.urdf", "write": True})
    return done


async def _confined(session: Any, root: Path, outside: Path) -> dict[str, Any]:
    call = session.call_tool
    return {
        "absolute": await call("check", {"paths": [str(outside / "arm.urdf")]}),
        "dotdot": await call("check", {"paths": ["../outside/arm.urdf"]}),
        "deeper": await call("info", {"path": "sub/../../outside/arm.urdf"}),
        "symlink": await call("matrix", {"paths": ["link.urdf"]}),
        "text": await call("check", {"text": "<robot/>", "name": "../outside/t.urdf"}),
        "package": await call(
            "check", {"paths": ["find.urdf.xacro"], "package_paths": {"out": str(outside)}}
        ),
        "cwd": await call("check", {"paths": [str(root.parent / "here.urdf")]}),
        "include": await call("check", {"paths": ["include.urdf.xacro"]}),
        "find": await call("check", {"paths": ["find.urdf.xacro"]}),
        "mesh": await call("check", {"paths": ["mesh.urdf"], "select": ["C004"]}),
        "folder": await call("check", {"paths": ["."]}),
    }


@pytest.fixture(scope="module")
def rooted(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    sdk()
    folder = tmp_path_factory.mktemp("rooted")
    root, outside = _world(folder)

    async def scenario(session: Any) -> dict[str, Any]:
        fixing = await _fixing(session, root, outside)
        return {**fixing, **await _confined(session, root, outside), "outside_folder": outside}

    return talk(folder, scenario, roots=[root])  # the server runs in folder, not a root


def test_fix_shows_edits_that_clear_the_fixable_findings_and_writes_only_when_asked(
    rooted: dict[str, Any],
) -> None:
    done = rooted
    preview = done["preview"].structured_content
    fixed = {fix["code"] for fix in preview["fixes"]}
    assert fixed == {"X007", "G001"}  # the safe ones; two more only with unsafe=true
    assert preview["unsafe_left"] == 2 and preview["written"] == []
    assert done["untouched"] == BROKEN.read_bytes()  # write=false writes nothing
    assert "+    <collision>" in preview["diff"] and done["later"] == []
    before, after = codes(done["before"]), codes(done["as_text"])
    assert fixed <= set(before) and not fixed & set(after)  # the edits clear their findings
    assert set(after) <= set(before)
    assert not done["write"].is_error and done["write"].structured_content["applied"] == 2
    assert done["written"] == done["applied"]  # write=true wrote what the edits make
    assert codes(done["after"]) == after
    assert "outside the allowed roots" in refused(done["outside"])
    assert (done["outside_folder"] / "arm.urdf").read_bytes() == BROKEN.read_bytes()
    assert "write=true needs files" in refused(done["text_write"])


def test_paths_outside_the_roots_are_refused_and_reads_beyond_them_are_findings(
    rooted: dict[str, Any],
) -> None:
    got = rooted
    for key in ("absolute", "dotdot", "deeper", "symlink", "text", "package", "cwd"):
        assert "outside the allowed roots" in refused(got[key]), key
    assert codes(got["include"]) == ["X010"]
    message = got["include"].structured_content["findings"][0]["message"]
    assert "outside the allowed folder" in message
    assert codes(got["find"]) == ["X010"]  # $(find out): no package outside the root is seen
    assert codes(got["mesh"]) == ["C004", "C004"]
    found = got["mesh"].structured_content["findings"]
    assert all("outside the allowed folder" in f["message"] for f in found)
    folder = got["folder"].structured_content  # every file below, but the link's target
    assert [e for e in folder["errors"] if "outside the allowed roots" in e] == [
        f"{got['outside_folder'].parent / 'root' / 'link.urdf'}: outside the allowed roots"
    ]
    assert folder["summary"]["files"] == 4  # arm, include, find and mesh
    answers = [r.structured_content for r in got.values() if hasattr(r, "structured_content")]
    assert "secret_link" not in json.dumps(answers)


# -- bad input (from the repository) ------------------------------------------------------------


async def _bad_input(session: Any) -> dict[str, Any]:
    call = session.call_tool
    evil = "${''.__class__.__mro__[1].__subclasses__()}"
    hostile = (
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        f'<xacro:property name="p" value="{evil}"/><link name="${{p}}"/></robot>'
    )
    return {
        "bad": await call("check", {"paths": [MALFORMED_SHOWN]}),
        "typed": await call("check", {"text": "<robot", "name": "typed.urdf"}),
        "hostile": await call("check", {"text": hostile, "name": "hostile.urdf.xacro"}),
        "text": await call("check", {"text": BROKEN.read_text(), "name": BROKEN_SHOWN}),
        "info_bad": await call("info", {"text": "<robot", "name": "typed.urdf"}),
        "fix_bad": await call("fix", {"paths": [MALFORMED_SHOWN], "select": ["X"]}),
        "missing": await call("check", {"paths": ["missing.urdf"]}),
        "option": await call("check", {"paths": [BROKEN_SHOWN], "select": ["Q9"]}),
    }


def test_without_roots_the_working_directory_is_the_root(repository: dict[str, Any]) -> None:
    assert "X007" in codes(repository["check"])
    assert "outside the allowed roots" in refused(repository["elsewhere"])


def test_malformed_and_hostile_input_are_findings_and_a_text_is_linted_like_its_file(
    repository: dict[str, Any],
) -> None:
    got = repository
    expected = json.loads(cli("check", "--format", "json", MALFORMED_SHOWN))
    assert "X001" in codes(got["bad"])
    assert got["bad"].structured_content["findings"] == expected["findings"]
    assert codes(got["typed"]) == ["X001"]
    assert codes(got["hostile"]) == ["X010"]  # the xacro sandbox's refusal, as a finding
    assert "not allowed" in got["hostile"].structured_content["findings"][0]["message"]
    file = got["check"].structured_content["findings"]
    assert got["text"].structured_content["findings"] == file
    assert got["info_bad"].structured_content["built"] is False
    assert "X001" in got["info_bad"].content[0].text
    assert not got["fix_bad"].is_error and got["fix_bad"].structured_content["fixes"] == []
    assert "no such file" in refused(got["missing"])
    assert "Q9" in refused(got["option"])


# -- the command -------------------------------------------------------------------------------


def test_root_on_the_command_line_confines_a_client_without_roots(tmp_path: Path) -> None:
    sdk()
    here, there = tmp_path / "here", tmp_path / "there"
    for folder in (here, there):
        folder.mkdir()
        shutil.copy(SMALL, folder / "arm.urdf")

    async def scenario(session: Any) -> dict[str, Any]:
        call = session.call_tool
        return {
            "relative": await call("check", {"paths": ["arm.urdf"]}),  # the root's
            "there": await call("check", {"paths": [str(there / "arm.urdf")]}),
            "here": await call("check", {"paths": [str(here / "arm.urdf")]}),
        }

    got = talk(here, scenario, options=("--root", str(there)))  # started in here
    assert codes(got["relative"]) == [] and codes(got["there"]) == []
    assert got["relative"].structured_content["findings"] == []
    assert got["relative"].structured_content["summary"]["files"] == 1
    assert "outside the allowed roots" in refused(got["here"])
    stderr = io.StringIO()
    with contextlib.redirect_stderr(stderr):
        assert main(["mcp", "--root", str(tmp_path / "none")]) == 2
    assert stderr.getvalue().strip().endswith("none: no such folder")


def test_without_the_sdk_the_command_says_how_to_install_it_in_one_line() -> None:
    code = "import sys; sys.modules['mcp'] = None\nimport urdflint.cli as c\nexit(c.main(['mcp']))"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    lines = done.stderr.strip().splitlines()
    assert done.returncode == 2 and len(lines) == 1
    assert lines[0].startswith("urdflint: error: urdflint mcp needs")
    assert "pip install" in lines[0] and "[mcp]" in lines[0]


def test_help_and_check_import_no_sdk_and_the_server_no_heavy_rule_dependency() -> None:
    for argv in (["--help"], ["check", "--isolated", "--exit-zero", "--no-cache", str(SMALL)]):
        loaded = imported_after(
            "import contextlib, io\nfrom urdflint.cli import main\n"
            "with contextlib.redirect_stdout(io.StringIO()), contextlib.suppress(SystemExit):\n"
            f"    main({argv!r})"
        )
        assert "urdflint.cli.check" in loaded
        assert "mcp" not in loaded and not {m for m in loaded if m.startswith("urdflint.mcp")}
    sdk()
    loaded = imported_after("from urdflint.mcp import server\nserver.build()")
    assert "mcp" in loaded
    heavy = {"numpy", "trimesh", "pinocchio", "fastapi", "pygls"}
    assert heavy & loaded == set()
    assert not {m for m in loaded if m.startswith("urdflint.rules.")}
