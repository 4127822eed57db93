"""docs/configuration.md says only what is true: its files (a fenced block whose first line is
``# file: PATH`` or ``(file: PATH)``) are written into a folder, and each ``$ command`` it shows
is run there and must print exactly what the page shows."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from test_readme import FENCE, run_in_shell, shim_path

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "configuration.md"
MARK = re.compile(r"^(?:# file: (?P<toml>\S+)|\(file: (?P<nc>\S+)\))$")


def _blocks() -> list[tuple[int, str, str]]:
    text = PAGE.read_text(encoding="utf-8")
    return [
        (text.count("\n", 0, m.start()) + 1, m.group("lang"), m.group("body"))
        for m in FENCE.finditer(text)
    ]


def _files() -> dict[str, str]:
    """Each file the page shows: a TOML file whole (its first line is a comment), a program
    without the line that names it."""
    found: dict[str, str] = {}
    for _line, _lang, body in _blocks():
        first, _, rest = body.partition("\n")
        mark = MARK.match(first)
        if mark is not None:
            found[mark.group("toml") or mark.group("nc")] = body if mark.group("toml") else rest
    return found


def _sessions() -> list[tuple[int, str, list[str]]]:
    shown: list[tuple[int, str, list[str]]] = []
    for fence_line, lang, body in _blocks():
        lines = body.splitlines()
        if lang != "text" or not lines or not lines[0].startswith("$ "):
            continue
        for i, text in enumerate(lines):
            if text.startswith("$ "):
                shown.append((fence_line + 1 + i, text[2:], []))
            else:
                shown[-1][2].append(text)
    return shown


SESSIONS = _sessions()


def test_the_page_shows_files_and_commands() -> None:
    files = _files()
    assert "shop/fanuc-macro.toml" in files and "shop/lathe/o1000.nc" in files, files
    assert len(SESSIONS) >= 4, SESSIONS


@pytest.mark.parametrize(
    "session", SESSIONS, ids=[f"configuration.md:{line}" for line, _c, _o in SESSIONS]
)
def test_a_shown_command_prints_what_the_page_shows(
    session: tuple[int, str, list[str]], tmp_path: Path
) -> None:
    line, command, output = session
    work = tmp_path / "work"
    for name, body in _files().items():
        (work / name).parent.mkdir(parents=True, exist_ok=True)
        (work / name).write_text(body, encoding="utf-8")
    printed = run_in_shell(command, work, shim_path(tmp_path), timeout=120)
    assert [text.rstrip() for text in printed.splitlines()] == [text.rstrip() for text in output], (
        f"docs/configuration.md:{line}: `{command}` prints otherwise:\n{printed}"
    )
