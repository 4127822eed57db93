"""The language server's handler tables: every protocol method and command registered from
them, and every handler run inside the workspace's analysis database, as are the worker's
jobs."""

from __future__ import annotations

import asyncio
from typing import Any

from lsprotocol import types

from fanuc_macro import database
from fanuc_macro.lsp.commands import EDITOR_COMMANDS, TRACE
from fanuc_macro.lsp.handlers import Command, Route, commands, register, routes
from fanuc_macro.lsp.server import FanucMacroLanguageServer, create_server


def test_the_server_registers_every_route_and_command_of_the_tables() -> None:
    server = create_server()
    features = server.protocol.fm.features
    table = routes()
    assert len({route.method for route in table}) == len(table)  # one handler a method
    for route in table:
        assert route.method in features, route.method
        assert features[route.method].__name__ == route.handler.__name__
    names = {command.name for command in commands()}
    assert {TRACE, *EDITOR_COMMANDS} <= names
    assert names == set(server.protocol.fm.commands)
    # What the server declares comes from the tables' options.
    options = server.protocol.fm.feature_options
    assert options[types.TEXT_DOCUMENT_COMPLETION].trigger_characters == ["#"]
    assert "a" in options[types.TEXT_DOCUMENT_SIGNATURE_HELP].trigger_characters


def test_every_handler_runs_inside_the_workspace_database() -> None:
    server = create_server()
    seen: list[tuple[str, database.Database]] = []

    def sync_handler(ls: FanucMacroLanguageServer, params: Any) -> None:
        assert ls is server
        seen.append(("sync", database.current()))

    async def async_handler(ls: FanucMacroLanguageServer, params: Any) -> None:
        # A feature's thread (asyncio.to_thread) copies the context: it sees the database.
        seen.append(("async", database.current()))
        seen.append(("thread", await asyncio.to_thread(database.current)))

    async def command(ls: FanucMacroLanguageServer, args: tuple[Any, ...]) -> tuple[Any, ...]:
        seen.append(("command", database.current()))
        return args

    register(
        server,
        [
            Route("fanuc-macro/testSync", sync_handler),
            Route("fanuc-macro/testAsync", async_handler),
        ],
        [Command("fanuc-macro.testCommand", command)],
    )
    features, commands_run = server.protocol.fm.features, server.protocol.fm.commands
    features["fanuc-macro/testSync"](None)
    asyncio.run(features["fanuc-macro/testAsync"](None))
    assert asyncio.run(commands_run["fanuc-macro.testCommand"](1, "two")) == (1, "two")
    assert [kind for kind, _ in seen] == ["sync", "async", "thread", "command"]
    assert all(db is server.engine.database for _, db in seen), seen
    assert database.current() is database.default()  # outside a handler: the process default


def test_the_worker_runs_inside_the_database_its_workspace_owns() -> None:
    server = create_server()
    engine = server.engine

    async def run() -> tuple[database.Database, database.Database]:
        engine.bind_loop(asyncio.get_running_loop())
        try:
            return await engine.in_worker(lambda: (database.current(), engine._ws.db))
        finally:
            engine.shutdown()

    current, owned = asyncio.run(run())
    assert current is engine.database and owned is engine.database
