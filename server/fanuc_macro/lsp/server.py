"""fanuc-macro-ls: the language server. It translates between the protocol and the package.

Run ``fanuc-macro-ls`` (or ``python -m fanuc_macro.lsp.server``); it speaks LSP over stdio.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import logging
import sys
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, TypeVar

from lsprotocol import types
from pygls.exceptions import (
    JsonRpcException,
    JsonRpcInternalError,
    JsonRpcInvalidParams,
    JsonRpcInvalidRequest,
)
from pygls.lsp.server import LanguageServer
from pygls.protocol import LanguageServerProtocol
from pygls.protocol.language_server import lsp_method

from .. import __version__
from ..code_cache import save_code_cache
from ..diagnostics import REPORT_INTERNAL_ERROR
from ..ide import TOKEN_MODIFIERS, TOKEN_TYPES
from .client import CompletionSupport
from .commands import (
    ARC_THREAD,
    DRUM_GROOVE,
    THREAD_MODULE,
    TOOLPATH,
    TRACE,
    run_arc_thread,
    run_drum_groove,
    run_thread_module,
    run_toolpath,
    run_trace,
)
from .convert import Codec
from .documents import OpenDocument
from .engine import Engine, Result
from .formatting import RENUMBER_KIND, wants

if TYPE_CHECKING:  # the features import the analysis: loaded after initialize (Engine.preload)
    from .features import View

log = logging.getLogger(__name__)

NAME = "fanuc-macro-ls"
SETTINGS_SECTION = "fanuc-macro"
PROGRAM_GLOB = "**/*.{nc,NC,mac,MAC,tap,TAP,cnc,CNC,eia,EIA}"
FEATURE_TIMEOUT = 60.0  # seconds a request waits for the analysis of the current version
# Signature help opens on a macro call's argument letters (spec I; either case as typed).
SIGNATURE_LETTERS = [*"ABCDEFHIJKMQRSTUVWXYZ", *"abcdefhijkmqrstuvwxyz"]
KEPT_TOKEN_RESULTS = 8  # documents whose last semantic tokens are kept for a delta
SCAN_WAIT = 15.0  # seconds a definition waits for the workspace scan to find its target

T = TypeVar("T")


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
        wrong = _invalid_request(data)
        if wrong is not None:
            # pygls drops these (no "jsonrpc") or reads them as responses (no "method"):
            # a client that sent one would wait for ever. The id is all that is needed.
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

    def handle_message(self, message: Any) -> None:
        if isinstance(message, _Unreadable):
            log.warning("%s (request %r)", message.error, message.id)
            self._send_response(message.id, None, message.error.to_response_error())
            return
        super().handle_message(message)

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


@dataclass
class _Shown:
    title: str
    message: str
    percentage: int
    created: bool = False  # the client answered window/workDoneProgress/create
    ended: str | None = None  # the end's message, once the analysis ended


class ClientProgress:
    """Progress shown by the client (``window/workDoneProgress``): each token is created by a
    request, then begun, reported and ended by ``$/progress`` notifications. What comes before
    the client answers the request is kept and sent after. Event loop only."""

    def __init__(self, server: LanguageServer) -> None:
        self.server = server
        self._shown: dict[str, _Shown] = {}

    def begin(self, token: str, title: str, message: str, percentage: int) -> None:
        self._shown[token] = _Shown(title, message, percentage)
        try:
            future = self.server.window_work_done_progress_create(
                types.WorkDoneProgressCreateParams(token=token)
            )
        except Exception:  # the connection is gone
            log.debug("cannot create a progress", exc_info=True)
            self._shown.pop(token, None)
            return
        future.add_done_callback(lambda f: self._created(token, f))

    def _created(self, token: str, future: Any) -> None:
        shown = self._shown.get(token)
        if shown is None:
            return
        if future.cancelled() or future.exception() is not None:
            log.debug("the client refused a progress: %r", future.exception())
            self._shown.pop(token, None)
            return
        shown.created = True
        self._send(token, types.WorkDoneProgressBegin(
            title=shown.title, message=shown.message, percentage=shown.percentage,
            cancellable=False,
        ))  # fmt: skip
        if shown.ended is not None:
            self.end(token, shown.ended)

    def report(self, token: str, message: str, percentage: int) -> None:
        shown = self._shown.get(token)
        if shown is None:
            return
        shown.message, shown.percentage = message, percentage
        if shown.created:
            self._send(token, types.WorkDoneProgressReport(message=message, percentage=percentage))

    def end(self, token: str, message: str) -> None:
        shown = self._shown.get(token)
        if shown is None:
            return
        if not shown.created:
            shown.ended = message  # sent once the client has created it
            return
        del self._shown[token]
        self._send(token, types.WorkDoneProgressEnd(message=message))

    def _send(self, token: str, value: Any) -> None:
        try:
            self.server.protocol.notify(
                types.PROGRESS, types.ProgressParams(token=token, value=value)
            )
        except Exception:  # the connection is gone
            log.debug("cannot send progress", exc_info=True)


class FanucMacroLanguageServer(LanguageServer):
    def __init__(self) -> None:
        super().__init__(
            NAME,
            __version__,
            text_document_sync_kind=types.TextDocumentSyncKind.Incremental,
            protocol_cls=AnsweringProtocol,
        )
        self.engine = Engine(self.publish_result, self.log_to_client)
        self.completion_support = CompletionSupport()
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

    def make_view(self, result: Result) -> View:
        from .features import View

        return View(
            key=result.key,
            uri=self.engine.client_uri(result.key),
            analysis=result.analysis,  # type: ignore[arg-type]
            lines=result.lines,
            config=self.engine.config,
            workspace=self.engine.indexes,
            client_uri=self.engine.client_uri,
            markdown=self.markdown_hover,
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


def _contributes_snippets(options: Any) -> bool:
    """The client's initialization option ``contributesSnippets``: the editor has the package's
    snippets already (the VS Code extension contributes them), so completion leaves them out."""
    return isinstance(options, dict) and options.get("contributesSnippets") is True


def _ignore_failure(future: Any) -> None:
    """A refresh the client did not take is no error of ours."""
    if not future.cancelled() and future.exception() is not None:
        log.debug("the client refused a refresh: %s", future.exception())


def _settings_of(value: Any) -> dict[str, Any] | None:
    """The ``fanuc-macro`` settings object, whether sent bare or under its section name."""
    if not isinstance(value, dict):
        return None
    inner = value.get(SETTINGS_SECTION)
    if isinstance(inner, dict):
        return inner
    # Initialization options that say only what the client is (contributesSnippets) hold no
    # settings: those are then pulled from the client.
    bare = {k: v for k, v in value.items() if k != "contributesSnippets"}
    return bare or None


def _capability(root: Any, path: str) -> Any:
    for name in path.split("."):
        root = getattr(root, name, None)
        if root is None:
            return None
    return root


def create_server() -> FanucMacroLanguageServer:
    server = FanucMacroLanguageServer()
    engine = server.engine

    @server.feature(types.INITIALIZE)
    def initialize(ls: FanucMacroLanguageServer, params: types.InitializeParams) -> None:
        engine.bind_loop(asyncio.get_running_loop())
        engine.codec = Codec(ls.workspace.position_encoding)
        engine.client_locale = params.locale
        caps = params.capabilities
        ls.completion_support = CompletionSupport(
            snippets=bool(
                _capability(caps, "text_document.completion.completion_item.snippet_support")
            ),
            markdown=types.MarkupKind.Markdown
            in (
                _capability(caps, "text_document.completion.completion_item.documentation_format")
                or []
            ),
            builtin_snippets=_contributes_snippets(params.initialization_options),
        )
        hover_formats = _capability(caps, "text_document.hover.content_format")
        ls.markdown_hover = hover_formats is None or types.MarkupKind.Markdown in hover_formats
        ls.inlay_refresh = bool(_capability(caps, "workspace.inlay_hint.refresh_support"))
        ls.code_lens_refresh = bool(_capability(caps, "workspace.code_lens.refresh_support"))
        if _capability(caps, "window.work_done_progress"):
            engine.progress = ClientProgress(ls)
        ls.watch_files = bool(
            _capability(caps, "workspace.did_change_watched_files.dynamic_registration")
        )
        settings = _settings_of(params.initialization_options)
        ls.pull_configuration = settings is None and bool(
            _capability(caps, "workspace.configuration")
        )
        engine.configure(settings)

    @server.feature(types.INITIALIZED)
    async def initialized(ls: FanucMacroLanguageServer, params: types.InitializedParams) -> None:
        engine.preload()  # the analysis, loaded while the client opens its first documents
        folders = [f.uri for f in ls.workspace.folders.values()]
        if not folders and ls.workspace.root_uri:
            folders = [ls.workspace.root_uri]
        engine.add_folders(folders)
        if ls.watch_files:
            registration = types.Registration(
                id="fanuc-macro-watch",
                method=types.WORKSPACE_DID_CHANGE_WATCHED_FILES,
                register_options=types.DidChangeWatchedFilesRegistrationOptions(
                    watchers=[types.FileSystemWatcher(glob_pattern=PROGRAM_GLOB)]
                ),
            )
            try:
                await ls.client_register_capability_async(
                    types.RegistrationParams(registrations=[registration])
                )
            except Exception:
                log.warning("the client refused the file watcher", exc_info=True)
        if ls.pull_configuration:
            await pull_configuration(ls)

    async def pull_configuration(ls: FanucMacroLanguageServer) -> None:
        try:
            values = await ls.workspace_configuration_async(
                types.ConfigurationParams(items=[types.ConfigurationItem(section=SETTINGS_SECTION)])
            )
        except Exception:
            log.warning("workspace/configuration failed", exc_info=True)
            return
        if values:
            engine.configure(_settings_of(values[0]))

    @server.feature(types.SHUTDOWN)
    def shutdown(ls: FanucMacroLanguageServer, params: None) -> None:
        engine.shutdown()
        save_code_cache()  # with the converter hooks the messages since the start needed

    # ---- documents -------------------------------------------------------------------------
    @server.feature(types.TEXT_DOCUMENT_DID_OPEN)
    def did_open(ls: FanucMacroLanguageServer, params: types.DidOpenTextDocumentParams) -> None:
        doc = params.text_document
        engine.open(doc.uri, doc.text, doc.version, doc.language_id)

    @server.feature(types.TEXT_DOCUMENT_DID_CHANGE)
    def did_change(ls: FanucMacroLanguageServer, params: types.DidChangeTextDocumentParams) -> None:
        engine.change(
            params.text_document.uri, params.text_document.version, params.content_changes
        )

    @server.feature(types.TEXT_DOCUMENT_DID_CLOSE)
    def did_close(ls: FanucMacroLanguageServer, params: types.DidCloseTextDocumentParams) -> None:
        engine.close(params.text_document.uri)
        ls.text_document_publish_diagnostics(
            types.PublishDiagnosticsParams(uri=params.text_document.uri, diagnostics=[])
        )

    @server.feature(types.WORKSPACE_DID_CHANGE_CONFIGURATION)
    async def did_change_configuration(
        ls: FanucMacroLanguageServer, params: types.DidChangeConfigurationParams
    ) -> None:
        settings = _settings_of(params.settings)
        if settings is None or not settings:
            if _capability(ls.client_capabilities, "workspace.configuration"):
                await pull_configuration(ls)
            return
        engine.configure(settings)

    @server.feature(types.WORKSPACE_DID_CHANGE_WORKSPACE_FOLDERS)
    def did_change_workspace_folders(
        ls: FanucMacroLanguageServer, params: types.DidChangeWorkspaceFoldersParams
    ) -> None:
        engine.remove_folders(f.uri for f in params.event.removed)
        engine.add_folders(f.uri for f in params.event.added)

    @server.feature(types.WORKSPACE_DID_CHANGE_WATCHED_FILES)
    def did_change_watched_files(
        ls: FanucMacroLanguageServer, params: types.DidChangeWatchedFilesParams
    ) -> None:
        engine.files_changed(params.changes)

    # ---- features --------------------------------------------------------------------------
    @server.feature(types.TEXT_DOCUMENT_HOVER)
    async def on_hover(
        ls: FanucMacroLanguageServer, params: types.HoverParams
    ) -> types.Hover | None:
        from .features import hover

        return await ls.answer(
            params.text_document.uri, "hover", lambda view: hover(view, params.position)
        )

    @server.feature(types.TEXT_DOCUMENT_INLAY_HINT, types.InlayHintOptions(resolve_provider=False))
    async def on_inlay_hint(
        ls: FanucMacroLanguageServer, params: types.InlayHintParams
    ) -> list[types.InlayHint] | None:
        view = await ls.view(params.text_document.uri)
        if view is None:
            return None
        from .features import inlay_hints

        r = params.range
        return await ls.compute("inlay hints", lambda: inlay_hints(view, r.start.line, r.end.line))

    @server.feature(types.TEXT_DOCUMENT_DEFINITION)
    async def on_definition(
        ls: FanucMacroLanguageServer, params: types.DefinitionParams
    ) -> list[types.Location] | None:
        # Read before the view is made: a scan that ends after it may hold the target.
        scanned = engine.scan_done.is_set()
        view = await ls.view(params.text_document.uri)
        if view is None:
            return None
        from .features import definition

        found = await ls.compute("definition", lambda: definition(view, params.position))
        if found is None and not scanned:
            # A program in a file the workspace scan has not reached yet.
            try:
                await asyncio.wait_for(engine.scan_done.wait(), SCAN_WAIT)
            except asyncio.TimeoutError:
                return None
            later = await ls.view(params.text_document.uri)
            if later is not None:
                found = await ls.compute("definition", lambda: definition(later, params.position))
        return found

    @server.feature(types.TEXT_DOCUMENT_REFERENCES)
    async def on_references(
        ls: FanucMacroLanguageServer, params: types.ReferenceParams
    ) -> list[types.Location] | None:
        view = await ls.view(params.text_document.uri)
        if view is None:
            return None
        others = [
            ls.make_view(r)
            for r in engine.results.values()
            if r.analysis is not None and r.key != view.key
        ]
        from .features import references

        include = params.context.include_declaration
        return await ls.compute(
            "references", lambda: references(view, params.position, include, others)
        )

    @server.feature(types.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
    async def on_document_symbol(
        ls: FanucMacroLanguageServer, params: types.DocumentSymbolParams
    ) -> list[types.DocumentSymbol] | None:
        from .features import document_symbols

        return await ls.answer(params.text_document.uri, "document symbols", document_symbols)

    @server.feature(
        types.TEXT_DOCUMENT_COMPLETION,
        types.CompletionOptions(trigger_characters=["#"], resolve_provider=False),
    )
    async def on_completion(
        ls: FanucMacroLanguageServer, params: types.CompletionParams
    ) -> types.CompletionList | None:
        doc = engine.document(params.text_document.uri)
        if doc is None:
            return None
        line_text = doc.line(params.position.line)
        column = engine.codec.from_client(line_text, params.position.character)
        # Completion must not wait for an analysis: the newest one there is will do.
        result = engine.results.get(doc.key)
        view = ls.make_view(result) if result is not None and result.analysis else None
        from .features import completion

        support = ls.completion_support
        config = engine.config
        line_count = len(doc.lines())
        eol = "\r\n" if "\r\n" in doc.text[:65536] else "\n"
        return await ls.compute(
            "completion",
            lambda: completion(
                line_text,
                params.position.line,
                column,
                engine.codec,
                config,
                support,
                view,
                line_count,
                eol,
            ),
        )

    @server.feature(
        types.TEXT_DOCUMENT_CODE_ACTION,
        types.CodeActionOptions(code_action_kinds=[types.CodeActionKind.QuickFix, RENUMBER_KIND]),
    )
    async def on_code_action(
        ls: FanucMacroLanguageServer, params: types.CodeActionParams
    ) -> list[types.CodeAction] | None:
        doc = engine.document(params.text_document.uri)
        view = await ls.view(params.text_document.uri)
        if view is None or doc is None:
            return None
        eol = "\r\n" if "\r\n" in doc.text[:65536] else "\n"
        from .features import code_actions

        diagnostics = params.context.diagnostics
        actions = await ls.compute("code actions", lambda: code_actions(view, diagnostics, eol))
        if actions is not None and wants(params.context.only, RENUMBER_KIND):
            from .formatting import renumber_action

            line, step = params.range.start.line, engine.format_settings.renumber_step
            found = await ls.compute("renumbering", lambda: renumber_action(view, line, step))
            if found is not None:
                actions.append(found)
        return actions

    # ---- formatting: the open document's text, no analysis waited for ---------------------
    @server.feature(types.TEXT_DOCUMENT_FORMATTING)
    async def on_formatting(
        ls: FanucMacroLanguageServer, params: types.DocumentFormattingParams
    ) -> list[types.TextEdit] | None:
        doc = engine.document(params.text_document.uri)
        if doc is None:
            return None
        from .formatting import document_edits

        text, lines, codec = doc.text, doc.lines(), engine.codec
        settings, options = engine.format_settings, params.options
        return await ls.compute(
            "formatting", lambda: document_edits(text, lines, codec, settings, options)
        )

    @server.feature(types.TEXT_DOCUMENT_RANGE_FORMATTING)
    async def on_range_formatting(
        ls: FanucMacroLanguageServer, params: types.DocumentRangeFormattingParams
    ) -> list[types.TextEdit] | None:
        doc = engine.document(params.text_document.uri)
        if doc is None:
            return None
        from .formatting import range_edits

        text, lines, codec = doc.text, doc.lines(), engine.codec
        settings, options, asked = engine.format_settings, params.options, params.range
        return await ls.compute(
            "range formatting",
            lambda: range_edits(text, lines, codec, settings, options, asked),
        )

    # ---- navigation: rename, highlight, folding, selection, workspace symbols, calls ------
    def refused(answer: Any) -> Any:
        """A rename the ide layer refused is an error whose message the client shows."""
        from .navigation import Refused

        if isinstance(answer, Refused):
            raise JsonRpcException(answer.message, code=types.LSPErrorCodes.RequestFailed)
        return answer

    @server.feature(types.TEXT_DOCUMENT_PREPARE_RENAME)
    async def on_prepare_rename(
        ls: FanucMacroLanguageServer, params: types.PrepareRenameParams
    ) -> types.PrepareRenamePlaceholder | None:
        from .navigation import prepare_rename

        found = await ls.answer(
            params.text_document.uri,
            "prepare rename",
            lambda view: prepare_rename(view, params.position),
        )
        return refused(found)  # type: ignore[no-any-return]

    @server.feature(types.TEXT_DOCUMENT_RENAME, types.RenameOptions(prepare_provider=True))
    async def on_rename(
        ls: FanucMacroLanguageServer, params: types.RenameParams
    ) -> types.WorkspaceEdit | None:
        from .navigation import rename

        found = await ls.answer(
            params.text_document.uri,
            "rename",
            lambda view: rename(view, params.position, params.new_name),
        )
        return refused(found)  # type: ignore[no-any-return]

    @server.feature(types.TEXT_DOCUMENT_DOCUMENT_HIGHLIGHT)
    async def on_document_highlight(
        ls: FanucMacroLanguageServer, params: types.DocumentHighlightParams
    ) -> list[types.DocumentHighlight] | None:
        from .navigation import document_highlights

        return await ls.answer(
            params.text_document.uri,
            "document highlight",
            lambda view: document_highlights(view, params.position),
        )

    @server.feature(types.TEXT_DOCUMENT_FOLDING_RANGE)
    async def on_folding_range(
        ls: FanucMacroLanguageServer, params: types.FoldingRangeParams
    ) -> list[types.FoldingRange] | None:
        from .navigation import folding_ranges

        return await ls.answer(params.text_document.uri, "folding ranges", folding_ranges)

    @server.feature(types.TEXT_DOCUMENT_SELECTION_RANGE)
    async def on_selection_range(
        ls: FanucMacroLanguageServer, params: types.SelectionRangeParams
    ) -> list[types.SelectionRange] | None:
        from .navigation import selection_ranges

        return await ls.answer(
            params.text_document.uri,
            "selection ranges",
            lambda view: selection_ranges(view, params.positions),
        )

    @server.feature(types.WORKSPACE_SYMBOL)
    async def on_workspace_symbol(
        ls: FanucMacroLanguageServer, params: types.WorkspaceSymbolParams
    ) -> list[types.WorkspaceSymbol] | None:
        documents = engine.indexes  # replaced, never changed: safe to read from a thread
        from .navigation import workspace_symbols

        return await ls.compute(
            "workspace symbols",
            lambda: workspace_symbols(documents, params.query, engine.codec, engine.client_uri),
        )

    @server.feature(types.TEXT_DOCUMENT_PREPARE_CALL_HIERARCHY)
    async def on_prepare_call_hierarchy(
        ls: FanucMacroLanguageServer, params: types.CallHierarchyPrepareParams
    ) -> list[types.CallHierarchyItem] | None:
        from .navigation import prepare_call_hierarchy

        found = await ls.answer(
            params.text_document.uri,
            "call hierarchy",
            lambda view: prepare_call_hierarchy(view, params.position),
        )
        return found or None

    @server.feature(types.CALL_HIERARCHY_INCOMING_CALLS)
    async def on_incoming_calls(
        ls: FanucMacroLanguageServer, params: types.CallHierarchyIncomingCallsParams
    ) -> list[types.CallHierarchyIncomingCall] | None:
        documents = engine.indexes
        from .navigation import incoming_calls

        return await ls.compute(
            "incoming calls",
            lambda: incoming_calls(documents, params.item, engine.codec, engine.client_uri),
        )

    @server.feature(types.CALL_HIERARCHY_OUTGOING_CALLS)
    async def on_outgoing_calls(
        ls: FanucMacroLanguageServer, params: types.CallHierarchyOutgoingCallsParams
    ) -> list[types.CallHierarchyOutgoingCall] | None:
        documents = engine.indexes
        from .navigation import outgoing_calls

        return await ls.compute(
            "outgoing calls",
            lambda: outgoing_calls(documents, params.item, engine.codec, engine.client_uri),
        )

    # ---- semantic tokens, signature help, code lenses (lsp/presentation.py) ----------------
    legend = types.SemanticTokensLegend(
        token_types=list(TOKEN_TYPES), token_modifiers=list(TOKEN_MODIFIERS)
    )

    # The last full tokens sent of each document, for a delta: (result id, data). A few
    # documents, the most recent; an unknown id gets the full tokens again.
    sent_tokens: dict[str, tuple[str, list[int]]] = {}
    token_results = iter(range(1, 1 << 62))

    def keep_tokens(uri: str, tokens: types.SemanticTokens) -> types.SemanticTokens:
        sent_tokens.pop(uri, None)
        sent_tokens[uri] = (tokens.result_id or "", list(tokens.data))
        while len(sent_tokens) > KEPT_TOKEN_RESULTS:
            del sent_tokens[next(iter(sent_tokens))]
        return tokens

    @server.feature(
        types.TEXT_DOCUMENT_SEMANTIC_TOKENS_FULL,
        types.SemanticTokensRegistrationOptions(
            legend=legend, full=types.SemanticTokensFullDelta(delta=True), range=True
        ),
    )
    async def on_semantic_tokens(
        ls: FanucMacroLanguageServer, params: types.SemanticTokensParams
    ) -> types.SemanticTokens | None:
        uri = params.text_document.uri
        view = await ls.view(uri)
        if view is None:
            return None
        from .presentation import semantic_tokens

        result_id = str(next(token_results))
        found = await ls.compute("semantic tokens", lambda: semantic_tokens(view, None, result_id))
        return None if found is None else keep_tokens(uri, found)

    @server.feature(types.TEXT_DOCUMENT_SEMANTIC_TOKENS_FULL_DELTA)
    async def on_semantic_tokens_delta(
        ls: FanucMacroLanguageServer, params: types.SemanticTokensDeltaParams
    ) -> types.SemanticTokens | types.SemanticTokensDelta | None:
        uri = params.text_document.uri
        view = await ls.view(uri)
        if view is None:
            return None
        from .presentation import semantic_tokens, token_edits

        result_id = str(next(token_results))
        found = await ls.compute("semantic tokens", lambda: semantic_tokens(view, None, result_id))
        if found is None:
            return None
        before = sent_tokens.get(uri)
        keep_tokens(uri, found)
        if before is None or before[0] != params.previous_result_id:
            return found
        edits = token_edits(before[1], found.data)
        return types.SemanticTokensDelta(edits=edits, result_id=result_id)

    @server.feature(types.TEXT_DOCUMENT_SEMANTIC_TOKENS_RANGE)
    async def on_semantic_tokens_range(
        ls: FanucMacroLanguageServer, params: types.SemanticTokensRangeParams
    ) -> types.SemanticTokens | None:
        view = await ls.view(params.text_document.uri)
        if view is None:
            return None
        from .presentation import semantic_tokens

        within = params.range
        return await ls.compute("semantic tokens", lambda: semantic_tokens(view, within))

    @server.feature(
        types.TEXT_DOCUMENT_SIGNATURE_HELP,
        types.SignatureHelpOptions(
            # A bracket or comma of a function; a space or a letter of a G65/G66 line.
            trigger_characters=["[", ",", " ", *SIGNATURE_LETTERS],
            retrigger_characters=["/", "]"],
        ),
    )
    async def on_signature_help(
        ls: FanucMacroLanguageServer, params: types.SignatureHelpParams
    ) -> types.SignatureHelp | None:
        doc = engine.document(params.text_document.uri)
        if doc is None:
            return None
        line_text = doc.line(params.position.line)
        column = engine.codec.from_client(line_text, params.position.character)
        # Like completion, it reads the newest text and does not wait for its analysis.
        result = engine.results.get(doc.key)
        view = ls.make_view(result) if result is not None and result.analysis else None
        from .presentation import signature_help

        codec = engine.codec
        return await ls.compute(
            "signature help", lambda: signature_help(line_text, column, codec, view)
        )

    @server.feature(types.TEXT_DOCUMENT_CODE_LENS, types.CodeLensOptions(resolve_provider=False))
    async def on_code_lens(
        ls: FanucMacroLanguageServer, params: types.CodeLensParams
    ) -> list[types.CodeLens] | None:
        from .presentation import code_lenses

        return await ls.answer(params.text_document.uri, "code lenses", code_lenses)

    # ---- commands --------------------------------------------------------------------------
    @server.command(TRACE)
    async def trace_command(ls: FanucMacroLanguageServer, *args: Any) -> dict[str, Any]:
        return await run_trace(engine, args)

    @server.command(TOOLPATH)
    async def toolpath_command(ls: FanucMacroLanguageServer, *args: Any) -> dict[str, Any]:
        return await run_toolpath(engine, args)

    @server.command(THREAD_MODULE)
    async def thread_module_command(ls: FanucMacroLanguageServer, *args: Any) -> dict[str, Any]:
        return await run_thread_module(args)

    @server.command(ARC_THREAD)
    async def arc_thread_command(ls: FanucMacroLanguageServer, *args: Any) -> dict[str, Any]:
        return await run_arc_thread(args)

    @server.command(DRUM_GROOVE)
    async def drum_groove_command(ls: FanucMacroLanguageServer, *args: Any) -> dict[str, Any]:
        return await run_drum_groove(args)

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
    create_server().start_io(stdin, stdout)
    return 0


__all__ = ["FanucMacroLanguageServer", "create_server", "main"]

if __name__ == "__main__":
    sys.exit(main())
