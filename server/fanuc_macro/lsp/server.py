"""fanuc-macro-ls: the language server. It translates between the protocol and the package.

Run ``fanuc-macro-ls`` (or ``python -m fanuc_macro.lsp.server``); it speaks LSP over stdio.
The handlers are top-level functions in :mod:`.handlers`, registered from their tables.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import logging
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, BinaryIO, TypeVar, cast

from lsprotocol import types
from pygls.exceptions import JsonRpcInternalError
from pygls.lsp.server import LanguageServer

from .. import __version__
from ..diagnostics import REPORT_INTERNAL_ERROR
from ..framing import Reframed
from .client import CompletionSupport
from .documents import OpenDocument
from .engine import Engine, Result
from .handlers import commands, register, routes
from .handlers.presentation import SentTokens
from .protocol import AnsweringProtocol

if TYPE_CHECKING:  # the features import the analysis: loaded after initialize (Engine.preload)
    from .features import View

log = logging.getLogger(__name__)

NAME = "fanuc-macro-ls"
FEATURE_TIMEOUT = 60.0  # seconds a request waits for the analysis of the current version

T = TypeVar("T")


@dataclass(frozen=True)
class TypedAt:
    """The newest text of a document at the position typed, and the newest analysis."""

    doc: OpenDocument
    line_text: str
    column: int
    view: View | None


class FanucMacroLanguageServer(LanguageServer):
    def __init__(self) -> None:
        super().__init__(
            NAME,
            __version__,
            text_document_sync_kind=types.TextDocumentSyncKind.Incremental,
            protocol_cls=AnsweringProtocol,
        )
        self.engine = Engine(self.publish_result, self.log_to_client, None, self.show_to_client)
        self.completion_support = CompletionSupport()
        self.sent_tokens = SentTokens()  # for semantic token deltas
        self.markdown_hover = True
        self.inlay_refresh = False
        self.code_lens_refresh = False
        self.watch_files = False
        self.pull_configuration = False

    # ---- to the client ---------------------------------------------------------------------
    def log_to_client(self, message: str, kind: types.MessageType) -> None:
        try:
            self.window_log_message(types.LogMessageParams(type=kind, message=message))
        except Exception:  # no client yet, or the connection is gone
            log.debug("cannot send a log message", exc_info=True)

    def show_to_client(self, message: str, kind: types.MessageType) -> None:
        try:
            self.window_show_message(types.ShowMessageParams(type=kind, message=message))
        except Exception:  # no client yet, or the connection is gone
            log.debug("cannot send a message", exc_info=True)

    def publish_result(self, doc: OpenDocument, result: Result) -> None:
        self.text_document_publish_diagnostics(
            types.PublishDiagnosticsParams(
                uri=doc.uri, diagnostics=result.diagnostics, version=doc.version
            )
        )
        if self.inlay_refresh:
            # The hints show values of this analysis: ask the client to fetch them again.
            future = self.workspace_inlay_hint_refresh(None)
            future.add_done_callback(_ignore_failure)
        if self.code_lens_refresh:
            # So do the lenses (runs, cuts), and a caller may be in the document analysed.
            future = self.workspace_code_lens_refresh(None)
            future.add_done_callback(_ignore_failure)

    # ---- helpers for the features ----------------------------------------------------------
    async def view(self, uri: str) -> View | None:
        result = await self.engine.fresh(uri, FEATURE_TIMEOUT)
        if result is None or result.analysis is None:
            return None
        return self.make_view(result)

    def typed_at(self, uri: str, position: types.Position) -> TypedAt | None:
        """Where the user types in the newest text, with the newest analysis there is (it may
        be of an older version): completion and signature help must not wait for one."""
        doc = self.engine.document(uri)
        if doc is None:
            return None
        line_text = doc.line(position.line)
        column = self.engine.codec.from_client(line_text, position.character)
        result = self.engine.results.get(doc.key)
        view = self.make_view(result) if result is not None and result.analysis else None
        return TypedAt(doc, line_text, column, view)

    def make_view(self, result: Result) -> View:
        from .features import View

        return View(
            key=result.key,
            uri=self.engine.client_uri(result.key),
            analysis=result.analysis,  # type: ignore[arg-type]
            lines=result.lines,
            config=self.engine.config_for(result.key),
            workspace=self.engine.indexes,
            client_uri=self.engine.client_uri,
            markdown=self.markdown_hover,
            locale=self.engine.catalogue.locale,
        )

    async def answer(self, uri: str, what: str, fn: Callable[[View], T]) -> T | None:
        """A feature of one document, from its fresh analysis (None when there is none)."""
        view = await self.view(uri)
        if view is None:
            return None
        return await self.compute(what, lambda: fn(view))

    async def compute(self, what: str, fn: Callable[[], T]) -> T | None:
        """Run a feature off the event loop; a bug in it is logged, and the request gets an
        error response (the server goes on)."""
        try:
            self.engine.check_feature_fault()
            return await asyncio.to_thread(fn)
        except Exception as err:
            log.exception("%s failed", what)
            message = f"fanuc-macro: {what} failed: {err!r}; {REPORT_INTERNAL_ERROR}"
            self.log_to_client(message, types.MessageType.Error)
            raise JsonRpcInternalError(message) from err


def _ignore_failure(future: Any) -> None:
    """A refresh the client did not take is no error of ours."""
    if not future.cancelled() and future.exception() is not None:
        log.debug("the client refused a refresh: %s", future.exception())


def create_server() -> FanucMacroLanguageServer:
    """The server, every handler of the tables registered (:mod:`.handlers`)."""
    server = FanucMacroLanguageServer()
    register(server, routes(), commands())
    _forward_package_errors(server)
    return server


class _ClientLogHandler(logging.Handler):
    """Errors logged by the package (a rule that failed...) go to the client's log too."""

    def __init__(self, server: FanucMacroLanguageServer) -> None:
        super().__init__(logging.ERROR)
        self.server = server

    def emit(self, record: logging.LogRecord) -> None:
        if record.name.startswith("fanuc_macro.lsp"):
            return  # the server reports its own errors
        loop = self.server.engine.bound_loop
        if loop is None or loop.is_closed():
            return
        message = f"fanuc-macro: {self.format(record)}"
        with contextlib.suppress(RuntimeError):  # the loop closed meanwhile
            loop.call_soon_threadsafe(self.server.log_to_client, message, types.MessageType.Error)


def _forward_package_errors(server: FanucMacroLanguageServer) -> None:
    package = logging.getLogger("fanuc_macro")
    for handler in list(package.handlers):
        if isinstance(handler, _ClientLogHandler):
            package.removeHandler(handler)
    package.addHandler(_ClientLogHandler(server))


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog=NAME, description="Language server for FANUC Custom Macro B programs (LSP, stdio)."
    )
    parser.add_argument("--version", action="store_true", help="print the version and exit")
    parser.add_argument(
        "--stdio", action="store_true", help="speak LSP on stdin/stdout (the default)"
    )
    parser.add_argument("--log-file", help="write the server's log to this file")
    parser.add_argument(
        "--log-level", default="WARNING", choices=["DEBUG", "INFO", "WARNING", "ERROR"]
    )
    args = parser.parse_args(argv)
    if args.version:
        print(f"{NAME} {__version__}")
        return 0
    handler: logging.Handler = (
        logging.FileHandler(args.log_file, encoding="utf-8")
        if args.log_file
        else logging.StreamHandler(sys.stderr)
    )
    logging.basicConfig(
        level=args.log_level,
        handlers=[handler],
        format="%(asctime)s %(levelname)s %(name)s: %(message)s",
    )
    stdin, stdout = sys.stdin.buffer, sys.stdout.buffer
    sys.stdout = sys.stderr  # a stray print must not corrupt the protocol stream
    # pygls' reader takes each Content-Length on trust: one wrong length or a stray byte and it
    # reads every later message out of step. The reframed input resynchronises on the next header.
    create_server().start_io(cast(BinaryIO, Reframed(stdin)), stdout)
    return 0


__all__ = ("FanucMacroLanguageServer", "create_server", "main")

if __name__ == "__main__":
    sys.exit(main())
