"""The server bundled in the VS Code extension.

`client/scripts/bundle-server.mjs` builds a folder (`bundled/python` in the .vsix) holding
`fanuc_macro` and its pure-Python dependencies; the extension runs a bare Python (no pip
install) on it with `PYTHONPATH=<that folder> python -m fanuc_macro.lsp.server`. These tests
build the folder into a temporary directory and start the server the way the extension does,
with a minimal environment and `python -S` (no site-packages: only the bundle and the
standard library).

The script is run by a Python that has none of the project's dependencies (a fresh venv
without packages): the bundle must come from pyproject.toml through the script's own
temporary venv, never from what the Python running it has installed. pip reaches PyPI.
"""

from __future__ import annotations

import asyncio
import json
import os
import shutil
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from lsprotocol import types
from packaging.requirements import Requirement
from pytest_lsp import ClientServerConfig, LanguageClient

import fanuc_macro

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "client" / "scripts" / "bundle-server.mjs"
SEEDS = ROOT / "tests" / "fixtures" / "seeds"
MODULE = "fanuc_macro.lsp.server"
# Debian's /usr/bin/python3 has none of our packages: a stand-in for a user's bare Python.
BARE_PYTHON = "/usr/bin/python3" if Path("/usr/bin/python3").exists() else sys.executable
VERSION_LINE = f"fanuc-macro-ls {fanuc_macro.__version__}"
WAIT = 60.0
PURE_DISTRIBUTIONS = {
    "attrs",
    "babel",
    "cattrs",
    "exceptiongroup",
    "lark",
    "lsprotocol",
    "pygls",
    "tomli",
    "typing-extensions",
}
pytestmark = pytest.mark.skipif(shutil.which("node") is None, reason="node is not installed")


def norm(name: str) -> str:
    return name.lower().replace("_", "-").replace(".", "-")


def minimal_env(pythonpath: str) -> dict[str, str]:
    """What `env -i PATH=/usr/bin:/bin PYTHONPATH=...` gives, and no bytecode in the bundle."""
    env = {"PATH": os.defpath, "PYTHONPATH": pythonpath, "PYTHONDONTWRITEBYTECODE": "1"}
    if sys.platform == "win32":
        env["SYSTEMROOT"] = os.environ.get("SYSTEMROOT", r"C:\Windows")
    return env


def project_dependencies() -> list[Requirement]:
    text = (ROOT / "pyproject.toml").read_text("utf-8")
    block = text.split("\ndependencies = [", 1)[1].split("]", 1)[0]
    lines = [line.strip().strip(",").strip('"') for line in block.splitlines() if '"' in line]
    return [Requirement(line) for line in lines]


@pytest.fixture(scope="module")
def empty_python(tmp_path_factory: pytest.TempPathFactory) -> str:
    """A Python with no package at all: a venv without pip, of this interpreter."""
    venv = tmp_path_factory.mktemp("empty") / "venv"
    made = [sys.executable, "-m", "venv", "--without-pip", str(venv)]
    subprocess.run(made, check=True, timeout=120)
    python = venv / ("Scripts/python.exe" if sys.platform == "win32" else "bin/python")
    for module in ("lark", "pygls", "lsprotocol", "fanuc_macro"):
        missing = subprocess.run(
            [str(python), "-c", f"import {module}"], capture_output=True, cwd=venv, env=clean_env()
        )
        assert missing.returncode != 0, f"{module} is importable in the empty venv"
    return str(python)


def clean_env(**extra: str) -> dict[str, str]:
    """This environment without a PYTHONPATH (the tests' own points at the package)."""
    return {**{k: v for k, v in os.environ.items() if k != "PYTHONPATH"}, **extra}


def run_script(out: Path, python: str, **env: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        ["node", str(SCRIPT), str(out), "--strict"],
        cwd=ROOT,
        env=clean_env(PYTHON=python, **env),
        capture_output=True,
        text=True,
        timeout=300,
    )


@pytest.fixture(scope="module")
def bundle(tmp_path_factory: pytest.TempPathFactory, empty_python: str) -> Path:
    out = tmp_path_factory.mktemp("bundle") / "python"
    done = run_script(out, empty_python)
    assert done.returncode == 0, done.stdout + done.stderr
    return out


@pytest.fixture(scope="module")
def bare_start(
    bundle: Path, tmp_path_factory: pytest.TempPathFactory
) -> subprocess.CompletedProcess[str]:
    """`--version` of the bundled server in a bare Python."""
    return subprocess.run(
        [BARE_PYTHON, "-S", "-m", MODULE, "--version"],
        cwd=tmp_path_factory.mktemp("cwd"),
        env=minimal_env(str(bundle)),
        capture_output=True,
        text=True,
        timeout=WAIT,
    )


def files_under(folder: Path) -> Iterator[Path]:
    for dirpath, dirnames, filenames in os.walk(folder):
        for name in dirnames + filenames:
            yield Path(dirpath) / name


def test_bundle_holds_pure_python_wheels_of_the_project_dependencies(bundle: Path) -> None:
    manifest = json.loads((bundle / "fanuc-macro-bundle.json").read_text("utf-8"))
    assert manifest["server"]["version"] == fanuc_macro.__version__
    assert manifest["notBundled"] == ["numpy"]
    bundled = {norm(p["name"]): p["version"] for p in manifest["packages"]}
    assert set(bundled) == PURE_DISTRIBUTIONS
    # The versions pip resolved from pyproject.toml's ranges (numpy excepted), as installed.
    for requirement in project_dependencies():
        if norm(requirement.name) == "numpy":
            continue
        assert requirement.specifier.contains(bundled[norm(requirement.name)]), requirement
    stems = (d.name.removesuffix(".dist-info").rsplit("-", 1) for d in bundle.glob("*.dist-info"))
    installed = {norm(name): version for name, version in stems}
    assert installed == bundled
    wheels = sorted(bundle.glob("*.dist-info/WHEEL"))
    assert len(wheels) == len(PURE_DISTRIBUTIONS)
    for wheel in wheels:
        tags = [
            ln.split(":", 1)[1].strip()
            for ln in wheel.read_text().splitlines()
            if ln.startswith("Tag:")
        ]
        assert tags and all(t.endswith("-none-any") for t in tags), (wheel, tags)
    assert not (bundle / "numpy").exists()
    assert not (bundle / "bin").exists()


def test_a_failed_build_keeps_the_previous_bundle(bundle: Path, empty_python: str) -> None:
    before = sorted(str(p.relative_to(bundle)) for p in files_under(bundle))
    manifest = (bundle / "fanuc-macro-bundle.json").read_bytes()
    # pip cannot reach its index: the build fails after it began its folder.
    failed = run_script(
        bundle,
        empty_python,
        PIP_INDEX_URL="http://127.0.0.1:9/simple",
        PIP_NO_CACHE_DIR="1",
        PIP_RETRIES="0",
        PIP_TIMEOUT="2",
    )
    assert failed.returncode == 1, failed.stdout + failed.stderr
    assert "is left as it was" in failed.stderr
    assert sorted(str(p.relative_to(bundle)) for p in files_under(bundle)) == before
    assert (bundle / "fanuc-macro-bundle.json").read_bytes() == manifest
    assert sorted(p.name for p in bundle.parent.iterdir()) == ["python"]


def test_bundle_copies_the_package_without_symlinks_or_bytecode(bundle: Path) -> None:
    source = ROOT / "server" / "fanuc_macro"
    for path in files_under(bundle):
        assert not path.is_symlink(), path
        assert path.name != "__pycache__" and path.suffix != ".pyc", path
    for name in ("macro_b.lark", "fanuc-macro.code-snippets"):
        copy = bundle / "fanuc_macro" / "data" / name
        assert copy.is_file() and not copy.is_symlink()
        assert copy.read_bytes() == (source / "data" / name).read_bytes()
    expected = {
        p.relative_to(source)
        for p in source.rglob("*")
        if p.is_file() and "__pycache__" not in p.parts and p.suffix != ".pyc"
    }
    copied = {
        p.relative_to(bundle / "fanuc_macro")
        for p in (bundle / "fanuc_macro").rglob("*")
        if p.is_file()
    }
    assert copied == expected


def test_bare_python_runs_the_bundled_server(bare_start: subprocess.CompletedProcess[str]) -> None:
    # No numpy in the bundle (it is binary): the server must start without it.
    assert bare_start.returncode == 0, bare_start.stderr
    assert bare_start.stdout.strip() == VERSION_LINE


async def test_lsp_round_trip_with_the_bundled_server(
    bundle: Path, bare_start: subprocess.CompletedProcess[str], tmp_path: Path
) -> None:
    assert bare_start.returncode == 0, bare_start.stderr
    command = [BARE_PYTHON, "-S", "-m", MODULE]
    env = minimal_env(str(bundle))

    client = await asyncio.wait_for(
        ClientServerConfig(server_command=command, server_env=env).start(), WAIT
    )
    assert isinstance(client, LanguageClient)
    try:
        result = await asyncio.wait_for(
            client.initialize_session(
                types.InitializeParams(
                    capabilities=types.ClientCapabilities(),
                    root_uri=SEEDS.as_uri(),
                    workspace_folders=[types.WorkspaceFolder(uri=SEEDS.as_uri(), name=SEEDS.name)],
                    initialization_options={"analysis": {"debounceMs": 20}},
                )
            ),
            WAIT,
        )
        assert result.server_info is not None
        assert result.server_info.version == fanuc_macro.__version__
        seed = SEEDS / "o2_arc_thread_roughing.nc"
        uri = seed.as_uri()
        client.text_document_did_open(
            types.DidOpenTextDocumentParams(
                text_document=types.TextDocumentItem(
                    uri=uri, language_id="fanuc-macro", version=1, text=seed.read_text("utf-8")
                )
            )
        )
        deadline = time.monotonic() + WAIT
        while not any(d.code == "MB601" for d in client.diagnostics.get(uri, [])):
            assert time.monotonic() < deadline, f"no MB601 for {uri}: {client.diagnostics.get(uri)}"
            await asyncio.sleep(0.02)
        mb601 = [d for d in client.diagnostics[uri] if d.code == "MB601"]
        assert any(d.range.start.line == 29 and "93.82" in d.message for d in mb601), mb601
        await asyncio.wait_for(client.shutdown_session(), WAIT)
    finally:
        await client.stop()
