"""The commands (``workspace/executeCommand``) of ``lsp/commands.py``, as one table: its five
first commands by name, then every one of its ``EDITOR_COMMANDS``, which it extends."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..commands import (
    ARC_THREAD,
    DRUM_GROOVE,
    EDITOR_COMMANDS,
    THREAD_MODULE,
    TOOLPATH,
    TRACE,
    CommandRefusal,
    EditorCommand,
    ThreadModuleText,
    run_arc_thread,
    run_drum_groove,
    run_thread_module,
    run_toolpath,
    run_trace,
)
from . import Command

if TYPE_CHECKING:
    from ...generators import ArcThreadAnswer, DrumGrooveAnswer, GeneratorRefusal
    from ...ide import NoToolpathView, ToolpathViewData, Trace
    from ..server import FanucMacroLanguageServer


async def trace(ls: FanucMacroLanguageServer, args: tuple[Any, ...]) -> Trace | CommandRefusal:
    return await run_trace(ls.engine, args)


async def toolpath(
    ls: FanucMacroLanguageServer, args: tuple[Any, ...]
) -> ToolpathViewData | NoToolpathView | CommandRefusal:
    return await run_toolpath(ls.engine, args)


async def thread_module(
    ls: FanucMacroLanguageServer, args: tuple[Any, ...]
) -> ThreadModuleText | CommandRefusal:
    return await run_thread_module(ls.engine, args)


async def arc_thread(
    ls: FanucMacroLanguageServer, args: tuple[Any, ...]
) -> ArcThreadAnswer | GeneratorRefusal | CommandRefusal:
    return await run_arc_thread(ls.engine, args)


async def drum_groove(
    ls: FanucMacroLanguageServer, args: tuple[Any, ...]
) -> DrumGrooveAnswer | GeneratorRefusal | CommandRefusal:
    return await run_drum_groove(ls.engine, args)


def _editor_command(name: str, run: EditorCommand) -> Command:
    async def editor_command(ls: FanucMacroLanguageServer, args: tuple[Any, ...]) -> Any:
        return await run(ls.engine, args)

    editor_command.__name__ = name
    return Command(name, editor_command)


COMMANDS = (
    Command(TRACE, trace),
    Command(TOOLPATH, toolpath),
    Command(THREAD_MODULE, thread_module),
    Command(ARC_THREAD, arc_thread),
    Command(DRUM_GROOVE, drum_groove),
    *(_editor_command(name, run) for name, run in EDITOR_COMMANDS.items()),
)
