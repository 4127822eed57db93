"""The server's commands (workspace/executeCommand): the trace and the toolpath of a program,
thread modules, and the arc-thread and drum-groove programs."""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from typing import Any

from .engine import Engine, key_of

log = logging.getLogger(__name__)

TRACE = "fanuc-macro.trace"
TOOLPATH = "fanuc-macro.toolpath"
THREAD_MODULE = "fanuc-macro.threadModule"
ARC_THREAD = "fanuc-macro.arcThread"
DRUM_GROOVE = "fanuc-macro.drumGroove"


def _uri_argument(args: tuple[Any, ...]) -> str | None:
    if not args:
        return None
    first = args[0]
    if isinstance(first, dict):
        first = first.get("uri")
    return first if isinstance(first, str) and first else None


# An ide function answering for one document: (key, doc, index, others, config) -> JSON.
Answer = Callable[..., dict[str, Any]]


def _trace() -> Answer:
    from ..ide import trace  # the evaluator: loaded by the worker after start-up

    return trace


def _toolpath_view() -> Answer:
    from ..ide import toolpath_view

    return toolpath_view


async def _on_document(
    engine: Engine, command: str, args: tuple[Any, ...], load: Callable[[], Answer]
) -> dict[str, Any]:
    """``[uri]`` -> what the function ``load`` gives answers for that document, with the
    workspace's documents for its calls, computed in the engine's worker."""
    uri = _uri_argument(args)
    if uri is None:
        return {"error": f"{command} takes the document's URI as its argument"}
    key = key_of(uri)
    config = engine.config

    def job() -> dict[str, Any]:
        if not engine.load(key):
            return {"error": f"{uri} is neither open nor a readable program file"}
        documents = engine.trace_documents(key)
        if documents is None:
            return {"error": f"{uri} is not in the workspace"}
        (_, doc, index), *others = documents
        return load()(key, doc, index, others, config)

    try:
        return await engine.in_worker(job)
    except Exception as err:  # the client shows the message
        log.exception("%s of %s failed", command, uri)
        return {"error": f"{command} failed: {err!r}"}


async def run_trace(engine: Engine, args: tuple[Any, ...]) -> dict[str, Any]:
    """``[uri]`` -> the trace of that document."""
    return await _on_document(engine, TRACE, args, _trace)


async def run_toolpath(engine: Engine, args: tuple[Any, ...]) -> dict[str, Any]:
    """``[uri]`` -> the Toolpath view's data of that document (ide/toolpath_view.py)."""
    return await _on_document(engine, TOOLPATH, args, _toolpath_view)


ThreadArguments = tuple[str, float, bool | None, dict[str, Any]]


def _thread_arguments(args: tuple[Any, ...]) -> ThreadArguments | str:
    """(designation, length, internal, the module's options) or what is wrong."""
    if not args or not isinstance(args[0], dict):
        return 'expected one argument {"designation": str, "length": number, "internal": ...}'
    spec = args[0]
    designation = spec.get("designation")
    length = spec.get("length")
    internal = spec.get("internal")
    options: dict[str, Any] = {}
    infeed = spec.get("infeed")
    if infeed is not None:
        if not isinstance(infeed, str):
            return "infeed must be symmetric, alternate, left or right"
        options["infeed"] = infeed  # the generator refuses a name it does not know
    taper = spec.get("taper")
    if taper is not None:
        if isinstance(taper, bool) or not isinstance(taper, int | float):
            return "the taper must be a number: the diameter change per mm (0.0625 for 1:16)"
        options["taper"] = float(taper)
    if not isinstance(designation, str) or not designation.strip():
        return "the thread designation is missing (for example M50x3-5g6g)"
    if isinstance(length, bool) or not isinstance(length, int | float) or length <= 0:
        return "the thread length must be a positive number of millimetres"
    if internal is not None and not isinstance(internal, bool):
        return "internal must be true, false or null"
    return designation.strip(), float(length), internal, options


async def run_thread_module(args: tuple[Any, ...]) -> dict[str, Any]:
    """``[{designation, length, internal, infeed?, taper?}]`` -> ``{"text": ...}`` or
    ``{"error": ...}``.  ``internal`` (true, false or null) says the kind of thread when the
    designation does not (all capitals with a class both kinds have, or no class): such a
    designation with ``internal`` null, or one whose class contradicts ``internal``, is refused,
    never guessed."""
    parsed = _thread_arguments(args)
    if isinstance(parsed, str):
        return {"error": parsed}
    designation, length, internal, options = parsed
    from ..generators import NoGenerator, SideConflict, SideUndecided, load_generator

    try:
        generate = load_generator()
    except NoGenerator as err:
        return {"error": str(err)}
    except ModuleNotFoundError as err:
        log.exception("the thread module generator cannot be imported")
        return {"error": f"the thread module generator cannot be loaded: {err}"}
    except Exception as err:
        log.exception("the thread module generator cannot be imported")
        return {"error": f"the thread module generator cannot be loaded: {err}"}
    try:
        text = await asyncio.to_thread(generate, designation, length, internal, **options)
    except SideUndecided as err:
        return {"error": err.question('with "internal": false (external) or true (internal)')}
    except SideConflict as err:
        return {"error": err.refusal(f'"internal": {"true" if internal else "false"} was sent')}
    except ValueError as err:  # a designation the generator does not accept: its message
        return {"error": str(err)}
    except Exception as err:
        log.exception("thread module %s failed", designation)
        return {"error": f"the thread module generator failed ({err}); the server's log has more"}
    if not isinstance(text, str):
        return {"error": "the thread module generator returned no text"}
    return {"text": text}


async def _generated(
    command: str, args: tuple[Any, ...], request: Callable[[Any], dict[str, Any]]
) -> dict[str, Any]:
    # A generator runs its program on the evaluator: off the event loop, as the thread module.
    if len(args) > 1:
        return {"error": f"{command} takes one argument, the object of its parameters"}
    try:
        return await asyncio.to_thread(request, args[0] if args else None)
    except Exception as err:
        log.exception("%s failed", command)
        return {"error": f"{command} failed: {err!r}"}


async def run_arc_thread(args: tuple[Any, ...]) -> dict[str, Any]:
    """``[{parameter: value}]`` -> ``{"text", "summary"}`` or ``{"error"}``
    (ide/generator_requests.py)."""
    from ..generators import arc_thread_request

    return await _generated(ARC_THREAD, args, arc_thread_request)


async def run_drum_groove(args: tuple[Any, ...]) -> dict[str, Any]:
    """``[{parameter: value}]`` (``pitch`` required) -> ``{"text", "summary"}`` or
    ``{"error"}``."""
    from ..generators import drum_groove_request

    return await _generated(DRUM_GROOVE, args, drum_groove_request)
