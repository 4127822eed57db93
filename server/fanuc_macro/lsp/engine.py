"""The package's analysis for the language server: the analysis job, its results, and the
workspace's documents (settings, folders, files changed on disk).

One worker thread (:mod:`.scheduler`) owns the package :class:`~fanuc_macro.workspace.Workspace`:
every change to it and every analysis runs there, one at a time. The loop side keeps the open
documents' texts (:mod:`.documents`) and asks the worker to make a document fresh; the worker
always takes the newest text when it starts, so a request for an older version that is still
queued analyses the newer one instead. An edit of a document that the running analysis reads
cancels it (:mod:`fanuc_macro.cancel`): it stops at its next block boundary, publishes
nothing, and the newest text is analysed after the debounce. An edit reschedules the other
open documents whose analysis reads the edited one, before or after the edit
(:meth:`Engine._affected_by`). An analysis that goes on for more than half a second shows its
progress in the client (``window/workDoneProgress``), when the client can show it.
"""

from __future__ import annotations

import asyncio
import logging
import os
import time
import traceback
from collections.abc import Callable, Iterable, Mapping, Sequence
from contextlib import AbstractContextManager
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, TypeVar
from urllib.parse import unquote, urlparse

from lsprotocol import types

from ..cancel import Cancelled, CancelToken
from ..code_cache import save_code_cache
from ..config import Config, FormatSettings
from ..database import Database
from ..diagnostics import REPORT_INTERNAL_ERROR
from ..ide import Catalogue, catalogue
from .convert import Codec, ConvertedDiagnostics, Lines
from .documents import DocumentStore, NewestText, OpenDocument
from .documents import key_of as key_of  # where the commands read it
from .folders import Folders, path_of, read_program
from .progress import AnalysisProgress, ProgressDisplay
from .scheduler import Job, Scheduler

if TYPE_CHECKING:  # the analysis is imported by the worker, after the server has started
    from ..analysis import Analysis
    from ..ide import Indexed
    from ..workspace import OtherDocument, Workspace

log = logging.getLogger(__name__)

T = TypeVar("T")

DEFAULT_DEBOUNCE_MS = 250.0
# An analysis shows its progress once it has run this long (setting analysis.progressDelayMs);
# only at a checkpoint that counts blocks, so a document too small for one never shows any.
DEFAULT_PROGRESS_DELAY_MS = 500.0
FAULT_ENV = "FANUC_MACRO_LS_FAULT"  # tests: analysing a text that contains it raises
# Tests: every feature request fails while an open document contains it.
FEATURE_FAULT_ENV = "FANUC_MACRO_LS_FEATURE_FAULT"
NO_INDEXES: Mapping[str, Indexed] = MappingProxyType({})


@dataclass(frozen=True)
class Result:
    """One analysis of one version of a document, ready for the protocol."""

    key: str
    version: int | None
    generation: int  # of the workspace it was analysed in
    lines: Lines
    analysis: Analysis | None
    diagnostics: list[types.Diagnostic]
    seconds: float
    changed_workspace: bool  # this run put a new text of the document into the workspace
    error: str | None = None
    # The other open documents whose analysis the new text can change (their analysis reads
    # this document, before or after the change).
    affects: frozenset[str] = frozenset()


@dataclass(frozen=True)
class Stopped:
    """An analysis cancelled by a newer text: nothing of it is published."""

    key: str
    version: int | None
    where: str  # how far it got, for the log
    changed_workspace: bool  # it put a new text of the document into the workspace
    affects: frozenset[str] = frozenset()  # as in Result


@dataclass
class _Waiter:
    version: int | None
    future: asyncio.Future[Result | None] = field(repr=False)


class Engine:
    """The language server's analysis: the open documents (:class:`DocumentStore`), the
    worker that analyses them (:class:`Scheduler`), the workspace the worker owns and the
    newest result of each open document."""

    def __init__(
        self,
        publish: Callable[[OpenDocument, Result], None],
        log_message: Callable[[str, types.MessageType], None],
        codec: Codec | None = None,
        show_message: Callable[[str, types.MessageType], None] | None = None,
    ) -> None:
        self.publish = publish
        self.log_message = log_message
        self.show_message = show_message or log_message
        # The editor's settings as last sent, and the configuration file's, which win.
        self._editor_settings: dict[str, Any] | None = None
        self._file_settings: dict[str, Any] = {}
        self.config_files: tuple[Path, ...] = ()
        # The settings of documents below a configuration file other than the first folder's,
        # by that file.
        self._own_configs: dict[Path, Config] = {}
        self._nearest: dict[Path, Path | None] = {}  # a document's folder: its nearest file
        # The workspace's: every handler runs inside it (:meth:`active`), the analyses too.
        self.database = Database()
        self.codec = codec or Codec()
        self.config = Config()
        self.format_settings = FormatSettings()  # the formatter's: no analysis reads them
        self.debounce = DEFAULT_DEBOUNCE_MS / 1000.0
        self.documents = DocumentStore()
        self.scheduler = Scheduler(self.database, self.report)
        self.results: dict[str, Result] = {}  # newest analysis of each open document
        self.folders = Folders(self)
        self._waiters: dict[str, list[_Waiter]] = {}
        self.progress: ProgressDisplay | None = None  # when the client shows progress
        self.progress_delay = DEFAULT_PROGRESS_DELAY_MS / 1000.0
        self._progress_count = 0  # worker only: names the progress tokens
        # Worker-only state.
        self._workspace: Workspace | None = None  # made by the worker's first job
        self._ws_seq: dict[str, int | None] = {}  # which text of each document is in _ws
        self._analysed: dict[str, tuple[int, int]] = {}  # key -> (text seq, generation)
        # The documents each open document's last analysis read (worker thread): an edit of
        # one of them is what reschedules it.
        self._reads_of: dict[str, frozenset[str]] = {}
        # The program numbers each open document defines and calls, when its text last changed.
        # Kept with the index they were read from: an edit that keeps the index (a keystroke
        # in a line the index skips) keeps them, and costs nothing here.
        self._links: dict[str, tuple[object, frozenset[tuple[str, int | None]]]] = {}
        # The protocol's form of each open document's last diagnostics (worker thread).
        self._converted: dict[str, ConvertedDiagnostics] = {}
        self.generation = 0  # written by the worker only
        # The language of the messages: the setting `language`, else the client's locale.
        self.client_locale: str | None = None
        self.language = "auto"
        self._fault = os.environ.get(FAULT_ENV) or None
        self._feature_fault = os.environ.get(FEATURE_FAULT_ENV) or None

    # ---- helpers ---------------------------------------------------------------------------
    @property
    def indexes(self) -> Mapping[str, Indexed]:
        """Every workspace document and its index: the workspace's snapshot, which the worker
        replaces and never changes, so the event loop and feature threads may read it."""
        workspace = self._workspace
        return NO_INDEXES if workspace is None else workspace.indexes()

    @property
    def _ws(self) -> Workspace:
        """The package's workspace (worker only). The analysis modules it imports take a
        quarter of a second: the server answers ``initialize`` before, and the worker's first
        job (:meth:`preload`) loads them."""
        if self._workspace is None:
            from ..workspace import Workspace

            self._workspace = Workspace(self.config, db=self.database)
        return self._workspace

    def active(self) -> AbstractContextManager[Database]:
        """Make the workspace's database the current one (:mod:`fanuc_macro.database`): the
        handlers' table runs every handler inside it."""
        return self.database.active()

    def preload(self) -> None:
        """Load the analysis in the worker while the client sends its first documents."""

        def job() -> None:
            from . import commands, features  # noqa: F401  (imported for their own imports)

            self._ws.uris()
            save_code_cache()  # the code of the classes built so far, for the next start

        self.scheduler.start(job)

    @property
    def docs(self) -> dict[str, OpenDocument]:
        """The open documents by key (event loop)."""
        return self.documents.docs

    @property
    def loop(self) -> asyncio.AbstractEventLoop:
        return self.scheduler.loop

    def bind_loop(self, loop: asyncio.AbstractEventLoop) -> None:
        self.scheduler.bind_loop(loop)

    @property
    def bound_loop(self) -> asyncio.AbstractEventLoop | None:
        """The event loop, once the server runs (any thread may read it)."""
        return self.scheduler.bound_loop

    def client_uri(self, key: str) -> str:
        return self.documents.client_uri(key)

    def document(self, uri: str) -> OpenDocument | None:
        return self.documents.document(uri)

    def check_feature_fault(self) -> None:
        """Tests: fail as a bug in a feature would (see FEATURE_FAULT_ENV)."""
        fault = self._feature_fault
        if fault is not None and any(fault in doc.text for doc in self.docs.values()):
            raise RuntimeError("feature fault injected for testing")

    async def in_worker(self, fn: Callable[[], T]) -> T:
        """Run ``fn`` in the worker thread, after the work queued before it."""
        return await self.scheduler.in_worker(fn)

    def shutdown(self) -> None:
        self.scheduler.shutdown()

    # ---- settings --------------------------------------------------------------------------
    @property
    def catalogue(self) -> Catalogue:
        chosen = self.language if self.language != "auto" else self.client_locale
        return catalogue(chosen or "en")

    def _new_generation(self) -> None:
        """Worker: every document is published again (the messages' language changed)."""
        self.generation += 1

    def configure(self, settings: dict[str, Any] | None) -> None:
        """The editor's settings, under the configuration file's (:meth:`read_config_file`)."""
        self._editor_settings = settings
        self._own_configs = {}  # they hold the editor's settings too
        if self._file_settings:
            from ..config_file import merged

            settings = merged(settings or {}, self._file_settings)
        self._configure(settings)

    def read_config_file(self, folder: Path | None) -> None:
        """Read the configuration file nearest ``folder`` (the first workspace folder), again
        when it changed; its values win over the editor's settings. A file that cannot be
        used is told to the user, and the editor's settings are used alone."""
        from ..config_file import ConfigFileError, find_config_file, load_config_file

        found: dict[str, Any] = {}
        files: tuple[Path, ...] = ()
        try:
            path = find_config_file(folder) if folder is not None else None
            if path is not None:
                loaded = load_config_file(path)
                found, files = loaded.settings, tuple(loaded.files)
        except ConfigFileError as error:
            log.warning("%s", error)
            self.log_message(f"fanuc-macro: {error}", types.MessageType.Error)
            self.show_message(f"fanuc-macro: {error}", types.MessageType.Error)
        self.config_files = files
        had_own = bool(self._own_configs)
        self._own_configs, self._nearest = {}, {}  # read again when a document asks
        if had_own and found == self._file_settings:  # a subfolder's file changed
            self.scheduler.submit(self._new_generation, then=lambda _: self.schedule_all(0.0))
        if found != self._file_settings:
            self._file_settings = found
            self.configure(self._editor_settings)

    def config_for(self, key: str) -> Config:
        """The settings of the document ``key``: the editor's under the configuration file
        nearest it, when that is another than the first folder's (a subfolder with its own
        fanuc-macro.toml); else the workspace's. A file that cannot be used is told once, and
        the workspace's settings serve."""
        from ..config_file import ConfigFileError, find_config_file, load_config_file, merged

        path = path_of(key) if key.startswith("file:") else None
        if path is None:
            return self.config
        folder = path.parent
        if folder not in self._nearest:
            self._nearest[folder] = find_config_file(folder)
        nearest = self._nearest[folder]
        if nearest is None or nearest in self.config_files[:1]:
            return self.config
        found = self._own_configs.get(nearest)
        if found is None:
            try:
                settings = merged(self._editor_settings or {}, load_config_file(nearest).settings)
                found = Config.from_settings(settings)
            except ConfigFileError as error:
                self.show_message(f"fanuc-macro: {error}", types.MessageType.Error)
                found = self.config
            self._own_configs[nearest] = found
        return found

    def _configure(self, settings: dict[str, Any] | None) -> None:
        config = Config.from_settings(settings)
        for problem in config.setting_problems:  # the rest of the settings are used
            log.warning("%s", problem)
            self.log_message(f"fanuc-macro: {problem}", types.MessageType.Warning)
        self.format_settings = FormatSettings.from_settings(settings)
        language = (settings or {}).get("language")
        language = language if isinstance(language, str) and language else "auto"
        if language != self.language:
            before = self.catalogue
            self.language = language
            if self.catalogue != before and config == self.config:
                self.scheduler.submit(self._new_generation, then=lambda _: self.schedule_all(0.0))
        analysis = (settings or {}).get("analysis") or {}
        debounce = analysis.get("debounceMs") if isinstance(analysis, dict) else None
        if isinstance(debounce, int | float) and not isinstance(debounce, bool) and debounce >= 0:
            self.debounce = float(debounce) / 1000.0
        delay = analysis.get("progressDelayMs") if isinstance(analysis, dict) else None
        if isinstance(delay, int | float) and not isinstance(delay, bool) and delay >= 0:
            self.progress_delay = float(delay) / 1000.0
        if config == self.config:
            return
        self.config = config

        def apply() -> None:
            self._ws.set_config(config)  # the documents read with other limits are read again
            self.generation += 1

        self.scheduler.submit(apply, then=lambda _: self.schedule_all(0.0))

    # ---- documents -------------------------------------------------------------------------
    def open(self, uri: str, text: str, version: int | None, language_id: str = "") -> None:
        self.schedule(self.documents.open(uri, text, version, language_id), 0.0)

    def change(
        self, uri: str, version: int | None, changes: Sequence[types.TextDocumentContentChangeEvent]
    ) -> None:
        key = self.documents.change(uri, version, changes, self.codec)
        if key is None:
            return
        # The running analysis reads an older text of this document: its result is of no use.
        self.scheduler.cancel_running(lambda job: key in job.keys)
        self.schedule(key, self.debounce)

    def close(self, uri: str) -> None:
        key = self.documents.close(uri)
        self.results.pop(key, None)
        self._converted.pop(key, None)
        self.scheduler.drop_timer(key)
        self.scheduler.cancel_running(lambda job: job.key == key)
        for waiter in self._waiters.pop(key, []):
            if not waiter.future.done():
                waiter.future.set_result(None)
        path = path_of(key)
        keep = path is not None and self.folders.contains(path)

        def reload() -> frozenset[str]:
            # A closed file stays in the workspace as it is on disk, for the others' calls.
            data = read_program(path) if keep and path is not None else None
            self._reads_of.pop(key, None)
            changed = self.changed_files({key: data})
            release_memory()  # what the document and the caches held, back to the system
            return changed

        self.scheduler.submit(reload, then=self.schedule_each)

    # ---- scheduling ------------------------------------------------------------------------
    def schedule(self, key: str, delay: float) -> None:
        """Analyse ``key`` after ``delay`` seconds without a newer request (the debounce)."""
        if self.scheduler.closed or key not in self.docs:
            return
        self.scheduler.later(key, delay, self._request)

    def schedule_all(self, delay: float, but: str | None = None) -> None:
        for key in list(self.docs):
            if key != but:
                self.schedule(key, delay)

    def _request(self, key: str) -> None:
        if self.scheduler.closed or key not in self.docs:
            self.scheduler.drop_timer(key)
            return
        if not self.scheduler.enqueue(key):
            return  # the queued job will read the newest text when it starts
        self.scheduler.submit(lambda: self._analyse_job(key), then=lambda r: self._deliver(key, r))

    def report(self, message: str, error: BaseException | None = None) -> None:
        """Log an error and show it in the client's log; callable from any thread."""
        if error is not None:
            detail = "".join(traceback.format_exception(error))
            log.error("%s\n%s", message, detail)
            message = f"{message}\n{detail}"
        loop = self.bound_loop
        if loop is None or loop.is_closed():
            return
        # Messages go out from the event loop only: the protocol writer is not thread-safe.
        try:
            loop.call_soon_threadsafe(self.log_message, message, types.MessageType.Error)
        except RuntimeError:  # the loop closed meanwhile
            log.debug("cannot report to the client", exc_info=True)

    async def fresh(self, uri: str, timeout: float = 60.0) -> Result | None:
        """The analysis of the document's current version (waits for it, at most ``timeout``);
        the newest one there is when it does not come in time."""
        key = key_of(uri)
        doc = self.docs.get(key)
        if doc is None:
            return None
        current = self.results.get(key)
        if current is not None and current.version == doc.version:
            return current
        waiter = _Waiter(doc.version, self.loop.create_future())
        self._waiters.setdefault(key, []).append(waiter)
        self.schedule(key, 0.0)  # someone is waiting: skip the debounce
        try:
            return await asyncio.wait_for(asyncio.shield(waiter.future), timeout)
        except asyncio.TimeoutError:
            return self.results.get(key)
        finally:
            waiters = self._waiters.get(key)
            if waiters and waiter in waiters:
                waiters.remove(waiter)

    # ---- the worker side -------------------------------------------------------------------
    def _analyse_job(self, key: str) -> Result | Stopped | None:
        progress = self._progress_of(key)
        token = CancelToken(progress)
        self.scheduler.dequeue(key)
        text, seq = self.documents.newest(key)
        if text is None:
            return None  # closed meanwhile
        job = Job(key, seq, token, frozenset({key}))
        self.scheduler.running(job)
        if progress is not None:
            progress.title = f"fanuc-macro: analysing {_display_name(text.uri)}"
        ending = "done"
        try:
            result = self._run_job(job, text)
            if result is not None and result.error is not None:
                ending = "failed"
            return result
        except Cancelled as stop:
            ending = "cancelled: a document it reads changed"
            return Stopped(key, text.version, stop.where(), job.changed, job.affects)
        except BaseException:
            ending = "failed"
            raise
        finally:
            self.scheduler.running(None)
            if progress is not None:
                progress.finish(ending)

    def _run_job(self, job: Job, text: NewestText) -> Result | None:
        key = job.key
        started = time.perf_counter()
        lines = Lines(text.lines, self.codec)
        changed = False
        try:
            changed = self._ensure_text(key, text, job.token)
            job.changed = changed
            if changed:
                job.affects = self._affected_by(key)
            generation = self.generation
            if self._analysed.get(key) == (text.seq, generation):
                return None  # already fresh: a duplicate request
            self._reads(job)
            if self._fault is not None and self._fault in text.text:
                raise RuntimeError("fault injected for testing")
            analysis = self._analyse(key, job.token, job.others)
            converted = self._converted.setdefault(key, ConvertedDiagnostics())
            chosen = self.catalogue
            diagnostics = converted.convert(
                chosen.localised(analysis.diagnostics),
                key,
                text.uri,
                lines,
                self._resolve,
                chosen.locale,
            )
        except Exception as err:  # logged and shown; the server goes on with other work
            self.report(f"fanuc-macro: the analysis of {text.uri} failed: {err!r}", err)
            failure = types.Diagnostic(
                range=lines.range(0, 0, 0, len(lines.text(0))),
                message=f"fanuc-macro could not analyse this document ({err!r}): "
                f"{REPORT_INTERNAL_ERROR}",
                severity=types.DiagnosticSeverity.Error,
                code="MB000",
                source="fanuc-macro",
            )
            self._analysed[key] = (text.seq, self.generation)
            seconds = time.perf_counter() - started
            return Result(key, text.version, self.generation, lines, None, [failure], seconds,
                          changed, repr(err), job.affects)  # fmt: skip
        self._analysed[key] = (text.seq, generation)
        seconds = time.perf_counter() - started
        return Result(key, text.version, generation, lines, analysis, diagnostics, seconds,
                      changed, None, job.affects)  # fmt: skip

    def _reads(self, job: Job) -> None:
        """Worker thread: record the documents the analysis of ``job.key`` reads, so that an
        edit of any of them cancels it (one that came before it knew them too)."""
        job.others = self.documents_for(job.key)
        keys = frozenset({job.key, *(k for k, _, _ in job.others)})
        self._reads_of[job.key] = keys
        self.scheduler.read_by(job, keys, lambda: self.documents.changed_since(job.seq, keys))

    def _analyse(
        self,
        key: str,
        cancel: CancelToken | None = None,
        others: list[OtherDocument] | None = None,
    ) -> Analysis:
        """The package's analysis of ``key``, given only the documents it can reach."""
        return self._ws.analyse(key, cancel=cancel, others=others, config=self.config_for(key))

    def _progress_of(self, key: str) -> AnalysisProgress | None:
        """Worker thread: what reports the progress of an analysis, if the client shows it."""
        display, loop = self.progress, self.bound_loop
        if display is None or loop is None:
            return None
        self._progress_count += 1
        token = f"fanuc-macro/analysis/{self._progress_count}"
        return AnalysisProgress(display, loop, token, self.progress_delay)

    def documents_for(self, key: str) -> list[OtherDocument]:
        """Worker thread: the other documents an analysis or trace of ``key`` needs."""
        return self._ws.others(key)

    def _affected_by(self, *keys: str) -> frozenset[str]:
        """Worker thread, after new texts of ``keys`` went into the workspace (or they left
        it): the other open documents whose analysis they can change. Those whose last
        analysis read one of them; and, when the program numbers one of them defines or calls
        changed, those that read one of them now."""
        changed = frozenset(keys)
        affected = {k for k, reads in self._reads_of.items() if not changed.isdisjoint(reads)}
        relinked = False
        indexes = self._ws.indexes()
        for key in changed:
            entry = indexes.get(key)
            known = self._links.get(key)
            if entry is None:  # removed: who read it is known
                self._links.pop(key, None)
                continue
            if known is not None and known[0] is entry[1]:
                continue  # the same index: the same programs and calls
            links = self._ws.links(key)
            self._links[key] = (entry[1], links)
            relinked = relinked or known is None or known[1] != links
        if relinked:
            affected.update(self._ws.readers(changed, self.documents.open_keys()))
        return frozenset(affected - changed)

    def _ensure_text(self, key: str, text: NewestText, cancel: CancelToken | None = None) -> bool:
        """Put the newest text of an open document into the workspace; True if it was not.
        Cancelled, the workspace keeps the text it had."""
        if self._ws_seq.get(key) == text.seq:
            return False
        self._ws.add_text(key, text.text, cancel)
        self._ws_seq[key] = text.seq
        self.generation += 1
        return True

    def add_file(self, key: str, data: bytes) -> None:
        self._ws.add_bytes(key, data)
        self._ws_seq[key] = None
        self.generation += 1

    def remove_file(self, key: str) -> None:
        self._ws.remove(key)
        self._ws_seq.pop(key, None)
        self._analysed.pop(key, None)
        self._links.pop(key, None)
        self.generation += 1

    def _resolve(self, key: str) -> tuple[str, Lines] | None:
        doc = self._ws.document(key)
        if doc is None:
            return None
        return self.client_uri(key), Lines([b.text for b in doc.blocks], self.codec)

    # ---- back on the loop ------------------------------------------------------------------
    def _deliver(self, key: str, result: Result | Stopped | None) -> None:
        doc = self.docs.get(key)
        if doc is None:
            return
        if isinstance(result, Stopped):
            self._stopped(doc, result)
            return
        if result is None:
            # Nothing was run (a duplicate request): whoever waits gets what there is.
            current = self.results.get(key)
            if current is not None:
                self._wake(key, current)
            return
        previous = self.results.get(key)
        if previous is None or _newer_or_same(result.version, previous.version):
            self.results[key] = result
        if result.version == doc.version:
            self.publish(doc, result)
        self._wake(key, result)
        del previous  # the earlier analysis: freed now, before the memory is given back
        self.scheduler.submit(release_memory)
        # The other open documents that call a program of this one, or are called by it.
        self.schedule_each(result.affects)

    def _stopped(self, doc: OpenDocument, stopped: Stopped) -> None:
        message = (
            f"fanuc-macro: the analysis of {doc.uri} (version {stopped.version}) was cancelled "
            f"{stopped.where}: a document it reads changed"
        )
        log.info("%s", message)
        self.log_message(message, types.MessageType.Log)
        self.schedule_each(stopped.affects)
        if not self.scheduler.waiting(doc.key):
            # Cancelled by an edit of another document: this one is analysed again too.
            self.schedule(doc.key, self.debounce)

    def schedule_each(self, keys: Iterable[str]) -> None:
        for key in keys:
            self.schedule(key, self.debounce)

    def _wake(self, key: str, result: Result) -> None:
        for waiter in list(self._waiters.get(key, [])):
            if not waiter.future.done() and _newer_or_same(result.version, waiter.version):
                waiter.future.set_result(result)

    # ---- workspace folders (lsp/folders.py) ------------------------------------------------
    @property
    def scan_done(self) -> asyncio.Event:
        """Set while no folder scan is under way."""
        return self.folders.scan_done

    def add_folders(self, folders: Iterable[str]) -> None:
        self.folders.add(folders)

    def remove_folders(self, folders: Iterable[str]) -> None:
        self.folders.remove(folders)

    def files_changed(self, events: Sequence[types.FileEvent]) -> None:
        self.folders.files_changed(events)

    def changed_files(self, files: dict[str, bytes | None]) -> frozenset[str]:
        """Worker thread: read files of the workspace again (None: removed); the open documents
        whose analysis that can change."""
        for key, data in files.items():
            if data is not None:
                self.add_file(key, data)
            else:
                self.remove_file(key)
        return self._affected_by(*files)

    def has_file(self, key: str) -> bool:
        """Worker thread: ``key`` is in the workspace."""
        return key in self._ws_seq

    def file_keys(self) -> list[str]:
        """Worker thread: every document of the workspace."""
        return self._ws.uris()

    # ---- for commands ----------------------------------------------------------------------
    def trace_documents(self, key: str) -> list[OtherDocument] | None:
        """Worker thread: ``key`` first, then the documents its trace needs, with the newest
        texts of the open ones; None when ``key`` is not in the workspace."""
        texts = self.documents.newest_all()
        for k, text in texts.items():
            self._ensure_text(k, text)
        own = self._ws.indexes().get(key)
        if own is None:
            return None
        return [(key, *own), *self.documents_for(key)]

    def load(self, key: str) -> bool:
        """Worker thread: make sure ``key`` is in the workspace, reading it from disk if need be."""
        if key in self._ws.indexes():
            return True
        path = path_of(key)
        data = read_program(path) if path is not None else None
        if data is None:
            return False
        self.add_file(key, data)
        return True


def release_memory() -> bool:
    """Give the C allocator's free memory back to the system (glibc's ``malloc_trim``); False
    where there is none to call.

    An analysis of an edit builds the new version's facts, lists and texts while the previous
    version's are alive, then frees the previous ones. Python's small objects go back to its
    own arenas, but what it took from ``malloc`` (dicts and lists of a big document, its text)
    glibc keeps in its heaps when their top is still in use, and mostly in the worker thread's
    arena, which it trims seldom: the server of a 100,000-block document grew by about 35 MB
    of such free memory in 8 keystrokes. A trim takes 2-3 ms there; it runs in the worker
    after the analysis is delivered, off the keystroke's path."""
    import ctypes

    try:
        # Looked up each time (a few microseconds, once per analysis): nothing kept.
        trim = getattr(ctypes.CDLL(None), "malloc_trim", None)
    except OSError:  # no C library to load (Windows)
        return False
    if trim is None:
        return False
    trim(0)
    return True


def _display_name(uri: str) -> str:
    """The file name of a URI, for the user: ``O1234.nc``."""
    name = PurePosixPath(unquote(urlparse(uri).path)).name
    return name or uri


def _newer_or_same(version: int | None, than: int | None) -> bool:
    if version is None or than is None:
        return True
    return version >= than
