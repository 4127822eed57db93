"""The configuration file through the language server: a real server over stdio (pytest-lsp)
reads the fanuc-macro.toml of its workspace folder, whose values win over the editor's
settings, reads it again when it changes, and tells a bad one to the user."""

from __future__ import annotations

import asyncio
from collections.abc import Sequence
from pathlib import Path

from lsprotocol import types
from pytest_lsp import LanguageClient

from test_lsp import client, codes, diagnostics, open_text, start

__all__ = ["client"]  # the fixture, imported for the tests here

SPINDLE = "O1000\nG97 S5000 M03\nG00 X10. Z2.\nM30\n"


async def test_the_file_wins_over_the_editor_and_is_read_again_when_it_changes(
    client: LanguageClient, tmp_path: Path
) -> None:
    config = tmp_path / "fanuc-macro.toml"
    config.write_text("[machine]\nmax-spindle-speed = 3000\n", encoding="utf-8")
    program = tmp_path / "o1000.nc"
    program.write_text(SPINDLE, encoding="utf-8")
    # The editor says 9000 rpm and MB602 an error: the file's 3000 wins, the severity stays.
    editor = {"machine": {"maxSpindleSpeed": 9000}, "rules": {"severity": {"MB602": "error"}}}
    await start(client, tmp_path, editor)
    uri = program.as_uri()
    open_text(client, uri, SPINDLE)
    found = await diagnostics(client, uri, lambda d: "MB602" in codes(d))
    spindle = next(d for d in found if d.code == "MB602")
    assert "3000" in spindle.message
    assert spindle.severity == types.DiagnosticSeverity.Error
    config.write_text("[machine]\nmax-spindle-speed = 6000\n", encoding="utf-8")
    client.workspace_did_change_watched_files(
        types.DidChangeWatchedFilesParams(
            changes=[types.FileEvent(uri=config.as_uri(), type=types.FileChangeType.Changed)]
        )
    )
    await diagnostics(client, uri, lambda d: "MB602" not in codes(d))


async def test_a_bad_file_is_shown_to_the_user_and_the_editor_settings_serve(
    client: LanguageClient, tmp_path: Path
) -> None:
    (tmp_path / "fanuc-macro.toml").write_text(
        "[machine]\nmax-spindle-speed = 'fast'\n", encoding="utf-8"
    )
    program = tmp_path / "o1000.nc"
    program.write_text(SPINDLE, encoding="utf-8")
    await start(client, tmp_path, {"machine": {"maxSpindleSpeed": 3000}})
    uri = program.as_uri()
    open_text(client, uri, SPINDLE)
    found = await diagnostics(client, uri, lambda d: "MB602" in codes(d))
    assert "3000" in next(d for d in found if d.code == "MB602").message
    for _ in range(100):
        if client.messages:
            break
        await asyncio.sleep(0.05)
    shown = [m.message for m in client.messages]
    assert any(
        "fanuc-macro.toml:2: machine.max-spindle-speed: 'fast' is not a number" in m for m in shown
    ), shown


async def test_each_document_takes_the_file_nearest_it(
    client: LanguageClient, tmp_path: Path
) -> None:
    (tmp_path / "fanuc-macro.toml").write_text(
        "[machine]\nmax-spindle-speed = 8000\n", encoding="utf-8"
    )
    lathe_config = tmp_path / "lathe" / "fanuc-macro.toml"
    lathe_config.parent.mkdir()
    lathe_config.write_text(
        "extend = '../fanuc-macro.toml'\n[machine]\nmax-spindle-speed = 3000\n", encoding="utf-8"
    )
    (tmp_path / "mill").mkdir()
    lathe, mill = tmp_path / "lathe" / "o1000.nc", tmp_path / "mill" / "o2000.nc"
    lathe.write_text(SPINDLE, encoding="utf-8")
    mill_text = SPINDLE.replace("O1000", "O2000").replace("S5000", "S7000")
    mill.write_text(mill_text, encoding="utf-8")
    await start(client, tmp_path)
    open_text(client, lathe.as_uri(), SPINDLE)
    open_text(client, mill.as_uri(), mill_text)
    found = await diagnostics(client, lathe.as_uri(), lambda d: "MB602" in codes(d))
    assert "3000" in next(d for d in found if d.code == "MB602").message
    assert "MB602" not in codes(await diagnostics(client, mill.as_uri()))
    lathe_config.write_text("[machine]\nmax-spindle-speed = 6000\n", encoding="utf-8")
    client.workspace_did_change_watched_files(
        types.DidChangeWatchedFilesParams(
            changes=[types.FileEvent(uri=lathe_config.as_uri(), type=types.FileChangeType.Changed)]
        )
    )
    await diagnostics(client, lathe.as_uri(), lambda d: "MB602" not in codes(d))


async def test_the_folder_scan_reads_the_files_table(
    client: LanguageClient, tmp_path: Path
) -> None:
    (tmp_path / "fanuc-macro.toml").write_text(
        "[files]\nexclude = ['old']\nextensions = ['pgm']\n", encoding="utf-8"
    )
    (tmp_path / "subs").mkdir()
    (tmp_path / "subs" / "o2000.pgm").write_text("O2000\nG00 X1.\nM99\n", encoding="utf-8")
    (tmp_path / "old").mkdir()
    (tmp_path / "old" / "o3000.nc").write_text("O3000\nG00 X1.\nM99\n", encoding="utf-8")
    main = tmp_path / "o1000.nc"
    text = "O1000\nM98 P2000\nM98 P3000\nM30\n"
    main.write_text(text, encoding="utf-8")
    await start(client, tmp_path)
    open_text(client, main.as_uri(), text)

    def missing_only_o3000(now: Sequence[types.Diagnostic]) -> bool:
        return {d.range.start.line for d in now if d.code == "MB403"} == {2}

    found = await diagnostics(client, main.as_uri(), missing_only_o3000)
    # O2000 is read from its .pgm file; O3000's folder is excluded: its call is missing.
    assert [d.range.start.line for d in found if d.code == "MB403"] == [2]
