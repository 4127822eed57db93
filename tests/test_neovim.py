"""The language server in a real editor: headless Neovim, set up as the README says with
editors/nvim (filetype detection, the server's configuration), opens program files by their
names, starts the server, shows its diagnostics and asks for a hover (tests/nvim/init.lua writes
what it got to a JSON file). The README's own Neovim block for the installed version is run as
written, so that it cannot stop working unseen. The set-up's files are checked against
package.json and pyproject.toml without Neovim."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SEEDS = ROOT / "tests" / "fixtures" / "seeds"
INIT = ROOT / "tests" / "nvim" / "init.lua"
README_CHECK = ROOT / "tests" / "nvim" / "readme_check.lua"
RUNTIME = ROOT / "editors" / "nvim"
NVIM = shutil.which("nvim")
SEED = SEEDS / "o2_arc_thread_roughing.nc"
MB601_LINES = {29, 63}  # 0-based: "M#1" with #1 = 93.82, in the seed


def _lua_strings(text: str, name: str) -> list[str]:
    """The strings of ``name = { "a", "b" }`` in a Lua file."""
    m = re.search(rf"\b{name}\s*=\s*\{{([^}}]*)\}}", text)
    assert m is not None, f"no {name} = {{...}}"
    return re.findall(r'"([^"]*)"', m.group(1))


def test_ftdetect_knows_the_extensions_the_vs_code_extension_declares() -> None:
    package = json.loads((ROOT / "package.json").read_text("utf-8"))
    [language] = [x for x in package["contributes"]["languages"] if x["id"] == "fanuc-macro"]
    text = (RUNTIME / "ftdetect" / "fanuc-macro.lua").read_text("utf-8")
    declared = [e.removeprefix(".") for e in language["extensions"]]
    assert _lua_strings(text, "local extensions") == declared
    assert text.count('"fanuc-macro"') >= 3  # the filetype, by extension, name and first line


def test_lsp_config_runs_the_servers_entry_point_for_the_filetype() -> None:
    text = (RUNTIME / "lsp" / "fanuc_macro.lua").read_text("utf-8")
    pyproject = (ROOT / "pyproject.toml").read_text("utf-8")
    scripts = re.search(r"\[project\.scripts\]\n(.*?)\n\n", pyproject, re.S)
    assert scripts is not None
    entry = {
        name: target
        for name, target in re.findall(r'^([\w-]+) = "([^"]+)"$', scripts.group(1), re.M)
    }
    [command] = _lua_strings(text, "cmd")
    assert entry[command] == "fanuc_macro.lsp.server:main"
    assert _lua_strings(text, "filetypes") == ["fanuc-macro"]
    readme = (ROOT / "README.md").read_text("utf-8")
    assert f'cmd = {{ "{command}" }}' in readme and "editors/nvim" in readme


@pytest.mark.skipif(NVIM is None, reason="nvim (Neovim) is not on PATH")
def test_neovim_detects_programs_shows_diagnostics_and_hover(tmp_path: Path) -> None:
    assert NVIM is not None
    out = tmp_path / "result.json"
    files = tmp_path / "files"
    files.mkdir()
    program = SEED.read_bytes()
    # By extension (".mac" is also an assembler's, which Neovim guesses first), by a name that
    # is a program number, by a first line "%"; and two files that are not programs.
    programs = ["prog.mac", "PROG.NC", "O0002", "tape"]
    not_programs = {"notes.txt": program, "readme": b"READ ME\n" + program}
    for name in programs:
        (files / name).write_bytes(program if name != "O0002" else program.lstrip(b"%\r\n"))
    for name, data in not_programs.items():
        (files / name).write_bytes(data)
    env = {
        **os.environ,
        "PYTHONPATH": os.pathsep.join(
            p for p in (str(ROOT / "server"), os.environ.get("PYTHONPATH", "")) if p
        ),
        "FANUC_NVIM_OUT": str(out),
        "FANUC_NVIM_SEED": str(SEED),
        "FANUC_NVIM_RUNTIME": str(RUNTIME),
        "FANUC_NVIM_OTHERS": "\n".join(str(files / n) for n in [*programs, *not_programs]),
        "FANUC_NVIM_ROOT": str(SEEDS),
        "FANUC_NVIM_PYTHON": sys.executable,
        "FANUC_NVIM_TIMEOUT": "60000",
        # "N22 G54 S#19 M#1": the hover asks about #1 (0-based line 29, column 14).
        "FANUC_NVIM_HOVER_LINE": "29",
        "FANUC_NVIM_HOVER_COL": "14",
        "XDG_STATE_HOME": str(tmp_path / "state"),  # Neovim's LSP log goes there
        "XDG_DATA_HOME": str(tmp_path / "data"),
        "XDG_CACHE_HOME": str(tmp_path / "cache"),
        "XDG_CONFIG_HOME": str(tmp_path / "config"),  # no user's ftdetect or plugin
    }
    done = subprocess.run(
        [NVIM, "--headless", "-n", "-i", "NONE", "--noplugin", "-u", str(INIT)],
        env=env,
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=240,
    )
    assert out.exists(), f"nvim wrote no result (rc {done.returncode}): {done.stderr[-2000:]}"
    result = json.loads(out.read_text("utf-8"))
    assert "error" not in result, result
    assert result["filetype"] == "fanuc-macro", result
    assert result["got_diagnostics"], result
    mb601 = [d for d in result["diagnostics"] if d["code"] == "MB601"]
    assert {d["lnum"] for d in mb601} == MB601_LINES, result["diagnostics"]
    assert all(d["source"] == "fanuc-macro" and "93.82" in d["message"] for d in mb601)
    assert "#1" in result["hover"] and "93.82" in result["hover"], result
    others = {Path(o["path"]).name: o for o in result["others"]}
    assert list(others) == [*programs, *not_programs]
    for name in programs:
        shown = others[name]
        assert (shown["filetype"], shown["got_diagnostics"], shown["clients"]) == (
            "fanuc-macro",
            True,
            1,
        ), shown
        shift = 0 if name != "O0002" else -1  # the "%" line left out
        codes = {(d["lnum"], d["code"]) for d in shown["diagnostics"]}
        assert {(n + shift, "MB601") for n in MB601_LINES} <= codes, shown
    for name in not_programs:
        shown = others[name]
        assert shown["filetype"] != "fanuc-macro" and shown["clients"] == 0, shown
        assert shown["diagnostics"] == [], shown


# The README's Neovim blocks begin "-- Neovim 0.8 to 0.10", "-- Neovim 0.11 and later" or
# "-- Neovim 0.7" (that version alone).
_BLOCK_VERSIONS = re.compile(r"-- Neovim (\d+)\.(\d+)(?: to (\d+)\.(\d+)|( and later))?\b")
_RUNTIMEPATH_LINE = 'vim.opt.runtimepath:append(vim.fn.expand("~/src/fanuc-macro/editors/nvim"))'


def readme_neovim_blocks() -> list[tuple[tuple[int, int], tuple[int, int] | None, str]]:
    """The Lua blocks of the README's Neovim paragraphs: the first and last version each is for
    (None: and later), and its code."""
    readme = (ROOT / "README.md").read_text("utf-8")
    section = readme[readme.index("**Neovim.**") : readme.index("Other editors:")]
    blocks = []
    for code in re.findall(r"^```lua\n(.*?)^```$", section, re.M | re.S):
        m = _BLOCK_VERSIONS.match(code)
        assert m is not None, f"a Neovim block that does not say its versions:\n{code}"
        first = (int(m[1]), int(m[2]))
        last = None if m[5] else (int(m[3]), int(m[4])) if m[3] else first
        blocks.append((first, last, code))
    return blocks


def _nvim_version() -> tuple[int, int]:
    assert NVIM is not None
    shown = subprocess.run([NVIM, "--version"], capture_output=True, text=True, timeout=60)
    m = re.match(r"NVIM v(\d+)\.(\d+)", shown.stdout)
    assert m is not None, shown.stdout
    return int(m[1]), int(m[2])


def test_readme_has_a_neovim_block_for_every_version_from_0_7() -> None:
    blocks = readme_neovim_blocks()
    ranges = sorted((first, last) for first, last, _ in blocks)
    assert ranges == [((0, 7), (0, 7)), ((0, 8), (0, 10)), ((0, 11), None)]
    for _, _, code in blocks:
        assert code.splitlines()[1] == _RUNTIMEPATH_LINE, code
    old = [code for first, _, code in blocks if first < (0, 11)]
    # Neovim 0.7 has neither vim.fs nor vim.lsp.start; 0.8 has both.
    assert all(("vim.fs." in code) == ("vim.lsp.start(" in code) for code in old)
    assert [first for first, _, code in blocks if "vim.fs." in code] == [(0, 8)]


@pytest.mark.skipif(NVIM is None, reason="nvim (Neovim) is not on PATH")
def test_the_readmes_neovim_block_for_the_installed_neovim_shows_diagnostics(
    tmp_path: Path,
) -> None:
    version = _nvim_version()
    [init] = [
        code
        for first, last, code in readme_neovim_blocks()
        if first <= version and (last is None or version <= last)
    ]
    # The block as written: its "~/src/fanuc-macro" is this repository under a home of the
    # test's, and its "fanuc-macro-ls" runs this interpreter's server.
    home = tmp_path / "home"
    (home / "src").mkdir(parents=True)
    (home / "src" / "fanuc-macro").symlink_to(ROOT, target_is_directory=True)
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    server = bin_dir / "fanuc-macro-ls"
    server.write_text(f'#!/bin/sh\nexec "{sys.executable}" -m fanuc_macro.lsp.server "$@"\n')
    server.chmod(0o755)
    (tmp_path / "init.lua").write_text(init, "utf-8")
    project = tmp_path / "project"
    (project / ".git").mkdir(parents=True)
    (project / "cut").mkdir()
    program = project / "cut" / "thread.nc"
    program.write_bytes(SEED.read_bytes())
    out = tmp_path / "result.json"
    env = {
        **os.environ,
        "HOME": str(home),
        "PATH": os.pathsep.join([str(bin_dir), os.environ.get("PATH", "")]),
        "PYTHONPATH": os.pathsep.join(
            p for p in (str(ROOT / "server"), os.environ.get("PYTHONPATH", "")) if p
        ),
        "FANUC_NVIM_OUT": str(out),
        "FANUC_NVIM_PROGRAM": str(program),
        "FANUC_NVIM_TIMEOUT": "60000",
        "XDG_STATE_HOME": str(tmp_path / "state"),
        "XDG_DATA_HOME": str(tmp_path / "data"),
        "XDG_CACHE_HOME": str(tmp_path / "cache"),
        "XDG_CONFIG_HOME": str(tmp_path / "config"),
    }
    startup = ["-u", str(tmp_path / "init.lua"), "-c", f"luafile {README_CHECK}"]
    done = subprocess.run(
        [NVIM, "--headless", "-n", "-i", "NONE", "--noplugin", *startup],
        env=env,
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=240,
    )
    assert out.exists(), f"nvim wrote no result (rc {done.returncode}): {done.stderr[-2000:]}"
    result = json.loads(out.read_text("utf-8"))
    assert "error" not in result, (result, done.stderr[-2000:])
    assert result["nvim"] == f"{version[0]}.{version[1]}"
    assert result["filetype"] == "fanuc-macro", result
    assert result["got_diagnostics"], (result, done.stderr[-2000:])
    [client] = result["clients"]
    assert Path(client["root_dir"]).resolve() == project.resolve(), client  # found by its .git
    mb601 = [d for d in result["diagnostics"] if d["code"] == "MB601"]
    assert {d["lnum"] for d in mb601} == MB601_LINES, result["diagnostics"]
    assert all(d["source"] == "fanuc-macro" for d in mb601)
