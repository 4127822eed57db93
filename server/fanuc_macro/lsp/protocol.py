"""The protocol's edge: pygls' protocol, made to answer every request it cannot read.

pygls logs and drops a request whose parameters do not validate, or that is no JSON-RPC 2.0
request, and the client waits for ever: :class:`AnsweringProtocol` answers it with the
JSON-RPC error. It also keeps the open documents out of pygls' workspace (the engine keeps
their texts, :mod:`.documents`).
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterator
from concurrent.futures import Future
from typing import Any

from lsprotocol import types
from pygls.exceptions import JsonRpcException, JsonRpcInvalidParams, JsonRpcInvalidRequest
from pygls.protocol import LanguageServerProtocol
from pygls.protocol.language_server import lsp_method

from . import resume_the_collector

log = logging.getLogger(__name__)


class _Unreadable:
    """A request whose parameters did not validate: answered with InvalidParams."""

    def __init__(self, msg_id: int | str, method: str, error: JsonRpcException) -> None:
        self.id = msg_id
        self.method = method
        self.error = error


# What pygls' built-in notification handlers yield: the server's handler to run next.
Handled = Iterator[tuple[Callable[..., Any], tuple[object, ...], None]]


class AnsweringProtocol(LanguageServerProtocol):
    """pygls logs and drops a request whose parameters do not validate (a position character
    of 2**31), and the client waits for ever: here it gets the JSON-RPC error InvalidParams."""

    def structure_message(self, data: dict[str, Any]) -> Any:
        # pygls calls this for every object of the JSON (json.loads' object_hook), the
        # innermost first: an object without "jsonrpc" may be a message's params (the
        # {"id": 7} of $/cancelRequest), so it stays a dict, and handle_message judges what
        # reaches it as a message.
        if "jsonrpc" not in data:
            return data
        wrong = _invalid_request(data)
        if wrong is not None:
            # pygls reads these as responses (no "method"): a client that sent one would
            # wait for ever. The id is all that is needed.
            return _Unreadable(wrong[0], "", JsonRpcInvalidRequest(wrong[1]))
        try:
            return super().structure_message(data)
        except JsonRpcException as error:
            msg_id = data.get("id")
            method = data.get("method")
            if "jsonrpc" not in data or not isinstance(method, str):
                raise  # a notification or a response: nobody waits for an answer
            if isinstance(msg_id, bool) or not isinstance(msg_id, int | str):
                raise
            detail = _validation_errors(error.__cause__)
            message = f"invalid parameters of {method}" + (f": {detail}" if detail else "")
            return _Unreadable(msg_id, method, JsonRpcInvalidParams(message))

    _collector_resumed = False  # the instance's once resume_collector ran

    def resume_collector(self) -> None:
        """The collector back on (lsp/__init__.py paused it for the start), once."""
        if not self._collector_resumed:
            self._collector_resumed = True
            resume_the_collector()

    def handle_message(self, message: Any) -> None:
        if not self._collector_resumed and getattr(message, "method", None) != types.INITIALIZE:
            # The initialize handler resumes it once answered; a client that sends something
            # else first must not leave the server without it.
            self.resume_collector()
        if isinstance(message, dict):  # a message without "jsonrpc"
            wrong = _invalid_request(message)
            if wrong is None:
                log.warning("a message without jsonrpc, dropped: %.200r", message)
                return
            message = _Unreadable(wrong[0], "", JsonRpcInvalidRequest(wrong[1]))
        if isinstance(message, _Unreadable):
            log.warning("%s (request %r)", message.error, message.id)
            self._send_response(message.id, None, message.error.to_response_error())
            return
        super().handle_message(message)

    def _check_handler_result(self, future: Future[Any]) -> None:
        # pygls files the future of a notification whose handler is a generator (did_open,
        # did_change, did_close below) in _request_futures under a made-up id, and only a
        # response takes it out: 2 KB kept a keystroke. Done, it goes.
        super()._check_handler_result(future)
        for msg_id, kept in list(self._request_futures.items()):
            if kept is future:
                self._request_futures.pop(msg_id, None)
                break

    # The engine keeps the open documents' texts (lsp/documents.py). pygls' workspace would
    # keep a second copy and apply every change to it again, splitting the whole text into
    # lines per keystroke: the documents are not put there, and these only pass the
    # notifications on to the server's handlers.
    @lsp_method(types.TEXT_DOCUMENT_DID_OPEN)
    def lsp_text_document__did_open(self, params: types.DidOpenTextDocumentParams) -> Handled:
        yield from self._handled(types.TEXT_DOCUMENT_DID_OPEN, params)

    @lsp_method(types.TEXT_DOCUMENT_DID_CHANGE)
    def lsp_text_document__did_change(self, params: types.DidChangeTextDocumentParams) -> Handled:
        yield from self._handled(types.TEXT_DOCUMENT_DID_CHANGE, params)

    @lsp_method(types.TEXT_DOCUMENT_DID_CLOSE)
    def lsp_text_document__did_close(self, params: types.DidCloseTextDocumentParams) -> Handled:
        yield from self._handled(types.TEXT_DOCUMENT_DID_CLOSE, params)

    def _handled(self, method: str, params: object) -> Handled:
        handler = self.fm.features.get(method)
        if handler is not None:
            yield handler, (params,), None


def _invalid_request(data: Any) -> tuple[int | str, str] | None:
    """The id and what is wrong, for a message with an id that is neither a request nor a
    response (JSON-RPC 2.0, "Request object"); None for anything else."""
    if not isinstance(data, dict):
        return None
    msg_id = data.get("id")
    if isinstance(msg_id, bool) or not isinstance(msg_id, int | str):
        return None  # a notification, or an id nothing can be answered to
    if "result" in data or "error" in data:
        return None  # a response of the client
    if data.get("jsonrpc") != "2.0":
        return msg_id, 'invalid request: "jsonrpc" must be "2.0"'
    if "method" not in data:
        return msg_id, "invalid request: no method"
    if not isinstance(data["method"], str):
        return msg_id, "invalid request: the method is not a string"
    return None


def _validation_errors(error: BaseException | None) -> str:
    """The messages at the leaves of cattrs' nested validation errors (an explicit stack:
    the nesting follows the client's JSON)."""
    found: list[str] = []
    stack = [error] if error is not None else []
    while stack and len(found) < 5:
        exc = stack.pop()
        inner = getattr(exc, "exceptions", None)
        if isinstance(inner, tuple | list) and inner:
            stack.extend(reversed(inner))
        elif str(exc):
            found.append(str(exc))
    return "; ".join(found)


__all__ = ("AnsweringProtocol",)
