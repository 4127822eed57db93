"""The language server's handlers: a top-level function per protocol method, of the server
and the request's parameters, each module listing its own in a table of :class:`Route`.

:func:`register` registers the tables and is the one place that runs a handler inside the
workspace's database (:meth:`~fanuc_macro.lsp.engine.Engine.active`). Handlers are imported
with the server; what they answer with (``lsp/features.py`` ...) is imported when first
asked, after the analysis was loaded.
"""

from __future__ import annotations

import inspect
from collections.abc import Awaitable, Callable, Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..server import FanucMacroLanguageServer

Handler = Callable[["FanucMacroLanguageServer", Any], Any]
CommandHandler = Callable[["FanucMacroLanguageServer", tuple[Any, ...]], Awaitable[Any]]


@dataclass(frozen=True)
class Route:
    """A protocol method, its handler and what the server declares for it (made when the
    server registers it: the protocol's option objects are mutable)."""

    method: str
    handler: Handler
    options: Callable[[], Any] | None = None


@dataclass(frozen=True)
class Command:
    """A ``workspace/executeCommand`` command and its handler (of the command's arguments)."""

    name: str
    handler: CommandHandler


def register(
    server: FanucMacroLanguageServer, routes: Iterable[Route], commands: Iterable[Command]
) -> None:
    """Register each handler with pygls, wrapped to run inside the workspace's database."""
    for route in routes:
        options = route.options() if route.options is not None else None
        server.feature(route.method, options)(_in_database(server, route.handler))
    for command in commands:
        server.command(command.name)(_command_in_database(server, command.handler))


def _in_database(server: FanucMacroLanguageServer, handler: Handler) -> Callable[[Any], Any]:
    # The wrapper's one parameter is not named ``ls``: pygls passes it the parameters alone.
    if inspect.iscoroutinefunction(handler):

        async def run_async(params: Any) -> Any:
            with server.engine.active():
                return await handler(server, params)

        run_async.__name__ = handler.__name__
        return run_async

    def run(params: Any) -> Any:
        with server.engine.active():
            return handler(server, params)

    run.__name__ = handler.__name__
    return run


def _command_in_database(
    server: FanucMacroLanguageServer, handler: CommandHandler
) -> Callable[..., Awaitable[Any]]:
    # Named ``ls``, pygls passes the server first and the command's arguments after it, on
    # every Python (without it, pygls guesses from the first annotation with issubclass, and
    # before Python 3.11 ``Any`` is no class and ``object`` takes the server).
    async def run(ls: object, *args: object) -> Any:
        with server.engine.active():
            return await handler(server, args)

    run.__name__ = handler.__name__
    return run


def routes() -> tuple[Route, ...]:
    """Every protocol method the server answers."""
    from . import answers, navigation, presentation, session

    return (*session.ROUTES, *answers.ROUTES, *navigation.ROUTES, *presentation.ROUTES)


def commands() -> tuple[Command, ...]:
    """Every command the server runs: those of ``lsp/commands.py``."""
    from .commands import COMMANDS

    return COMMANDS


__all__ = ("Command", "Route", "commands", "register", "routes")
