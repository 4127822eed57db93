"""Progress the client shows (``window/workDoneProgress``) for long analyses: what an analysis
reports from its checkpoints in the worker (:class:`AnalysisProgress`), and how the client is
told on the event loop (:class:`ClientProgress`)."""

from __future__ import annotations

import asyncio
import logging
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol

from lsprotocol import types
from pygls.lsp.server import LanguageServer

from ..cancel import RUNNING, Stage

log = logging.getLogger(__name__)

PROGRESS_EVERY = 0.2  # seconds between two progress reports of an analysis


class ProgressDisplay(Protocol):
    """Shows the progress of long analyses in the client; called on the event loop only."""

    def begin(self, token: str, title: str, message: str, percentage: int) -> None: ...

    def report(self, token: str, message: str, percentage: int) -> None: ...

    def end(self, token: str, message: str) -> None: ...


class AnalysisProgress:
    """The progress of one analysis, told by its checkpoints in the worker thread and shown by
    the display on the event loop: begun at the first checkpoint that counts blocks once the
    analysis has run ``delay`` seconds, reported at most every PROGRESS_EVERY seconds."""

    def __init__(
        self,
        display: ProgressDisplay,
        loop: asyncio.AbstractEventLoop,
        token: str,
        delay: float,
    ) -> None:
        self.display = display
        self.loop = loop
        self.token = token
        self.title = "fanuc-macro: analysing"
        self.delay = delay
        self.started = time.monotonic()
        self.shown = False
        self.last = 0.0
        self.percentage = 0

    def __call__(self, stage: Stage, done: int, total: int) -> None:
        now = time.monotonic()
        if self.shown:
            if now - self.last < PROGRESS_EVERY:
                return
        elif not stage.counts_blocks or now - self.started < self.delay:
            return
        self.last = now
        share = min(done / total, 1.0) if total > 0 else 0.0
        # Steadily rising, as the protocol asks: a run of another entry starts from 0 again.
        percentage = int(100 * (stage.start + (stage.end - stage.start) * share))
        self.percentage = max(self.percentage, min(percentage, 100))
        if stage is RUNNING:
            message = f"{stage.name}: {done:,} blocks run (budget {total:,})"
        else:
            message = f"{stage.name}: {done:,} of {total:,}"
        if self.shown:
            self._post(self.display.report, self.token, message, self.percentage)
        else:
            self.shown = True
            self._post(self.display.begin, self.token, self.title, message, self.percentage)

    def finish(self, message: str) -> None:
        if self.shown:
            self._post(self.display.end, self.token, message)

    def _post(self, fn: Callable[..., None], *args: Any) -> None:
        # The protocol writer is not thread-safe: the display runs on the event loop.
        if self.loop.is_closed():
            return
        try:
            self.loop.call_soon_threadsafe(fn, *args)
        except RuntimeError:  # the loop closed meanwhile
            log.debug("cannot show progress", exc_info=True)


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


__all__ = ("AnalysisProgress", "ClientProgress", "ProgressDisplay")
