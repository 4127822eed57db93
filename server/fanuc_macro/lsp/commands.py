"""The server's commands (workspace/executeCommand): the trace of a program and thread modules."""

from __future__ import annotations

import asyncio
import logging
from typing import Any

from .engine import Engine, key_of

log = logging.getLogger(__name__)

TRACE = "fanuc-macro.trace"
THREAD_MODULE = "fanuc-macro.threadModule"


def _uri_argument(args: tuple[Any, ...]) -> str | None:
    if not args:
        return None
    first = args[0]
    if isinstance(first, dict):
        first = first.get("uri")
    return first if isinstance(first, str) and first else None


async def run_trace(engine: Engine, args: tuple[Any, ...]) -> dict[str, Any]:
    """``[uri]`` -> the trace of that document, with the workspace's documents for its calls."""
    uri = _uri_argument(args)
    if uri is None:
        return {"error": "fanuc-macro.trace takes the document's URI as its argument"}
    key = key_of(uri)
    config = engine.config

    def job() -> dict[str, Any]:
        if not engine.load(key):
            return {"error": f"{uri} is neither open nor a readable program file"}
        documents = engine.trace_documents(key)
        if documents is None:
            return {"error": f"{uri} is not in the workspace"}
        (_, doc, index), *others = documents
        from ..ide.trace import trace  # the evaluator: loaded by the worker after start-up

        return trace(key, doc, index, others, config)

    try:
        return await engine.in_worker(job)
    except Exception as err:  # the client shows the message
        log.exception("trace of %s failed", uri)
        return {"error": f"the trace failed: {err!r}"}


def _thread_arguments(args: tuple[Any, ...]) -> tuple[str, float, bool | None] | str:
    if not args or not isinstance(args[0], dict):
        return 'expected one argument {"designation": str, "length": number, "internal": ...}'
    spec = args[0]
    designation = spec.get("designation")
    length = spec.get("length")
    internal = spec.get("internal")
    if not isinstance(designation, str) or not designation.strip():
        return "the thread designation is missing (for example M50x3-5g6g)"
    if isinstance(length, bool) or not isinstance(length, int | float) or length <= 0:
        return "the thread length must be a positive number of millimetres"
    if internal is not None and not isinstance(internal, bool):
        return "internal must be true, false or null"
    return designation.strip(), float(length), internal


async def run_thread_module(args: tuple[Any, ...]) -> dict[str, Any]:
    """``[{designation, length, internal}]`` -> ``{"text": ...}`` or ``{"error": ...}``."""
    parsed = _thread_arguments(args)
    if isinstance(parsed, str):
        return {"error": parsed}
    designation, length, internal = parsed
    from ..ide.thread_module import NoGenerator, load_generator

    try:
        generate = load_generator()
    except NoGenerator as err:
        return {"error": str(err)}
    except ModuleNotFoundError as err:
        log.exception("the thread module generator cannot be imported")
        return {"error": f"the thread module generator cannot be loaded: {err}"}
    except Exception as err:
        log.exception("the thread module generator cannot be imported")
        return {"error": f"the thread module generator cannot be loaded: {err!r}"}
    try:
        text = await asyncio.to_thread(generate, designation, length, internal)
    except ValueError as err:  # a designation the generator does not accept: its message
        return {"error": str(err)}
    except Exception as err:
        log.exception("thread module %s failed", designation)
        return {"error": f"the thread module generator failed: {err!r}"}
    if not isinstance(text, str):
        return {"error": "the thread module generator returned no text"}
    return {"text": text}
