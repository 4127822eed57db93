"""The README says only what is true: every command it shows with its output (a ``text`` block
of ``$ command`` lines, each followed by what it prints) is run here and must print exactly
that, and its first command, run on a fresh clone, installs the package in a venv and checks the
bundled example."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
FENCE = re.compile(r"^```(?P<lang>\w*)\n(?P<body>.*?)^```$", re.M | re.S)


@dataclass(frozen=True)
class ShownCommand:
    command: str
    output: list[str]
    line: int  # 1-based, in README.md


def fenced_blocks(lang: str) -> list[tuple[int, str]]:
    """The README's fenced blocks of a language: (the line of the opening fence, the body)."""
    text = README.read_text(encoding="utf-8")
    return [
        (text.count("\n", 0, m.start()) + 1, m.group("body"))
        for m in FENCE.finditer(text)
        if m.group("lang") == lang
    ]


def shown_commands() -> list[ShownCommand]:
    """Each ``$ command`` of a ``text`` block with the lines under it, up to the next ``$``."""
    shown: list[ShownCommand] = []
    for fence_line, body in fenced_blocks("text"):
        lines = body.splitlines()
        if not lines or not lines[0].startswith("$ "):
            continue  # a synopsis, not a session
        for i, text in enumerate(lines):
            if text.startswith("$ "):
                shown.append(ShownCommand(text[2:], [], fence_line + 1 + i))
            else:
                shown[-1].output.append(text)
    return shown


def shim_path(tmp: Path) -> str:
    """A PATH on which ``fanuc-macro`` is this interpreter's package from this checkout, so the
    README's commands run the code under test whatever the environment has installed."""
    bin_dir = tmp / "bin"
    bin_dir.mkdir()
    shim = bin_dir / "fanuc-macro"
    shim.write_text(
        f'#!/bin/sh\nPYTHONPATH="{ROOT / "server"}" exec "{sys.executable}" '
        '-m fanuc_macro.cli "$@"\n',
        encoding="utf-8",
    )
    shim.chmod(0o755)
    return f"{bin_dir}{os.pathsep}{os.environ.get('PATH', '')}"


def run_in_shell(command: str, cwd: Path, path: str, timeout: float) -> str:
    """What ``command`` prints on a terminal: standard output and error in the order written."""
    env = dict(os.environ, PATH=path, PYTHONUNBUFFERED="1", PYTHONIOENCODING="utf-8")
    env.pop("PYTHONPATH", None)
    done = subprocess.run(
        ["bash", "-c", f"{command} 2>&1"],
        cwd=cwd,
        env=env,
        stdout=subprocess.PIPE,
        text=True,
        encoding="utf-8",
        timeout=timeout,
        check=False,
    )
    return done.stdout


SHOWN = shown_commands()


def test_the_readme_shows_commands_with_their_output() -> None:
    # The parse above must find the sessions, or the test below would check nothing.
    assert len(SHOWN) >= 2, SHOWN
    assert any(s.command.startswith("fanuc-macro check") for s in SHOWN)


@pytest.mark.parametrize("shown", SHOWN, ids=[f"README.md:{s.line}" for s in SHOWN])
def test_a_shown_command_prints_what_the_readme_shows(shown: ShownCommand, tmp_path: Path) -> None:
    printed = run_in_shell(shown.command, ROOT, shim_path(tmp_path), timeout=120)
    assert [line.rstrip() for line in printed.splitlines()] == [
        line.rstrip() for line in shown.output
    ], f"README.md:{shown.line}: `{shown.command}` prints otherwise"


def first_commands() -> list[str]:
    """The README's first ``sh`` block: the clone, then the one command that installs and runs."""
    _, body = fenced_blocks("sh")[0]
    return [line for line in body.splitlines() if line.strip()]


@pytest.mark.skipif(
    shutil.which("git") is None or not (ROOT / ".git").exists(),
    reason="needs git and this checkout's history to clone",
)
def test_the_first_command_installs_and_checks_the_example_on_a_fresh_clone(
    tmp_path: Path,
) -> None:
    clone_line, install_line = first_commands()
    match = re.fullmatch(r"git clone (\S+) && cd (\S+)", clone_line)
    assert match is not None, clone_line
    url, folder = match.groups()
    assert url.startswith("https://"), url
    # The clone of this checkout's committed state stands for the public repository's.
    subprocess.run(
        ["git", "clone", "--quiet", str(ROOT), str(tmp_path / folder)],
        check=True,
        timeout=120,
    )
    # `python3` is the interpreter running the tests, as on the user's PATH.
    path = f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}"
    printed = run_in_shell(install_line, tmp_path / folder, path, timeout=900)
    shown = next(s for s in SHOWN if install_line.endswith(s.command))
    tail = [line.rstrip() for line in printed.splitlines()][-len(shown.output) :]
    assert tail == [line.rstrip() for line in shown.output], printed[-3000:]
