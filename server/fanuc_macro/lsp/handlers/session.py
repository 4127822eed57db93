"""The session: initialize, shutdown, the open documents' texts, settings, workspace folders
and files changed on disk."""

from __future__ import annotations

import asyncio
import logging
from typing import TYPE_CHECKING, Any, cast

from lsprotocol import types

from ...code_cache import save_code_cache
from ..client import CompletionSupport
from ..convert import Codec
from ..folders import path_of
from ..progress import ClientProgress
from ..protocol import AnsweringProtocol
from . import Route

if TYPE_CHECKING:
    from ..server import FanucMacroLanguageServer

log = logging.getLogger(__name__)

SETTINGS_SECTION = "fanuc-macro"
PROGRAM_GLOB = "**/*.{nc,NC,mac,MAC,tap,TAP,cnc,CNC,eia,EIA}"
CONFIG_GLOB = "**/{fanuc-macro.toml,pyproject.toml}"
CONFIG_NAMES = ("fanuc-macro.toml", "pyproject.toml")


def _contributes_snippets(options: Any) -> bool:
    """The client's initialization option ``contributesSnippets``: the editor has the package's
    snippets already (the VS Code extension contributes them), so completion leaves them out."""
    return isinstance(options, dict) and options.get("contributesSnippets") is True


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


def initialize(ls: FanucMacroLanguageServer, params: types.InitializeParams) -> None:
    loop = asyncio.get_running_loop()
    # Once the answer is written: pygls writes it first.
    loop.call_soon(cast(AnsweringProtocol, ls.protocol).resume_collector)
    engine = ls.engine
    engine.bind_loop(loop)
    engine.codec = Codec(ls.workspace.position_encoding)
    engine.client_locale = params.locale
    caps = params.capabilities
    ls.completion_support = CompletionSupport(
        snippets=bool(
            _capability(caps, "text_document.completion.completion_item.snippet_support")
        ),
        markdown=types.MarkupKind.Markdown
        in (
            _capability(caps, "text_document.completion.completion_item.documentation_format") or []
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
    ls.pull_configuration = settings is None and bool(_capability(caps, "workspace.configuration"))
    engine.configure(settings)


async def initialized(ls: FanucMacroLanguageServer, params: types.InitializedParams) -> None:
    engine = ls.engine
    engine.preload()  # the analysis, loaded while the client opens its first documents
    folders = [f.uri for f in ls.workspace.folders.values()]
    if not folders and ls.workspace.root_uri:
        folders = [ls.workspace.root_uri]
    engine.add_folders(folders)
    engine.read_config_file(path_of(folders[0]) if folders else None)
    if ls.watch_files:
        registration = types.Registration(
            id="fanuc-macro-watch",
            method=types.WORKSPACE_DID_CHANGE_WATCHED_FILES,
            register_options=types.DidChangeWatchedFilesRegistrationOptions(
                watchers=[
                    types.FileSystemWatcher(glob_pattern=PROGRAM_GLOB),
                    types.FileSystemWatcher(glob_pattern=CONFIG_GLOB),
                ]
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
        ls.engine.configure(_settings_of(values[0]))


def shutdown(ls: FanucMacroLanguageServer, params: None) -> None:
    ls.engine.shutdown()
    save_code_cache()  # with the converter hooks the messages since the start needed


# ---- documents -------------------------------------------------------------------------------
def did_open(ls: FanucMacroLanguageServer, params: types.DidOpenTextDocumentParams) -> None:
    doc = params.text_document
    ls.engine.open(doc.uri, doc.text, doc.version, doc.language_id)


def did_change(ls: FanucMacroLanguageServer, params: types.DidChangeTextDocumentParams) -> None:
    document = params.text_document
    ls.engine.change(document.uri, document.version, params.content_changes)


def did_close(ls: FanucMacroLanguageServer, params: types.DidCloseTextDocumentParams) -> None:
    ls.engine.close(params.text_document.uri)
    ls.text_document_publish_diagnostics(
        types.PublishDiagnosticsParams(uri=params.text_document.uri, diagnostics=[])
    )


# ---- settings, folders, files ----------------------------------------------------------------
async def did_change_configuration(
    ls: FanucMacroLanguageServer, params: types.DidChangeConfigurationParams
) -> None:
    settings = _settings_of(params.settings)
    if settings is None or not settings:
        if _capability(ls.client_capabilities, "workspace.configuration"):
            await pull_configuration(ls)
        return
    ls.engine.configure(settings)


def did_change_workspace_folders(
    ls: FanucMacroLanguageServer, params: types.DidChangeWorkspaceFoldersParams
) -> None:
    ls.engine.remove_folders(f.uri for f in params.event.removed)
    ls.engine.add_folders(f.uri for f in params.event.added)


def did_change_watched_files(
    ls: FanucMacroLanguageServer, params: types.DidChangeWatchedFilesParams
) -> None:
    if any(c.uri.endswith(CONFIG_NAMES) for c in params.changes):
        folders = [f.uri for f in ls.workspace.folders.values()] or [ls.workspace.root_uri or ""]
        ls.engine.read_config_file(path_of(folders[0]) if folders[0] else None)
    ls.engine.files_changed([c for c in params.changes if not c.uri.endswith(CONFIG_NAMES)])


ROUTES = (
    Route(types.INITIALIZE, initialize),
    Route(types.INITIALIZED, initialized),
    Route(types.SHUTDOWN, shutdown),
    Route(types.TEXT_DOCUMENT_DID_OPEN, did_open),
    Route(types.TEXT_DOCUMENT_DID_CHANGE, did_change),
    Route(types.TEXT_DOCUMENT_DID_CLOSE, did_close),
    Route(types.WORKSPACE_DID_CHANGE_CONFIGURATION, did_change_configuration),
    Route(types.WORKSPACE_DID_CHANGE_WORKSPACE_FOLDERS, did_change_workspace_folders),
    Route(types.WORKSPACE_DID_CHANGE_WATCHED_FILES, did_change_watched_files),
)
