"""When the worker runs what: one worker thread, the debounce timers, the queue of analyses
and the cancellation of the running one.

The worker thread is the only one that touches the package's workspace, so the workspace
needs no lock and the event loop never waits for an analysis. A job runs inside the
workspace's database (:mod:`fanuc_macro.database`): a thread does not inherit the context
variable that names it.
"""

from __future__ import annotations

import asyncio
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, TypeVar

from ..cancel import CancelToken
from ..database import Database

if TYPE_CHECKING:
    from ..workspace import OtherDocument

T = TypeVar("T")

Report = Callable[[str, BaseException], None]


@dataclass
class Job:
    """The analysis the worker runs: what cancels it."""

    key: str
    seq: int  # the newest text's seq when it started: a text with a greater one is newer
    token: CancelToken
    keys: frozenset[str]  # the documents it reads
    changed: bool = False  # it put a new text of the document into the workspace
    affects: frozenset[str] = frozenset()  # the other open documents the new text may change
    # The other documents the analysis reads, computed once for it.
    others: list[OtherDocument] = field(default_factory=list)


class Scheduler:
    def __init__(self, database: Database, report: Report) -> None:
        self.database = database
        self._report = report
        self._executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="fanuc-macro")
        self._loop: asyncio.AbstractEventLoop | None = None
        self._lock = threading.Lock()  # guards _queued and _running, shared with the worker
        self._queued: set[str] = set()
        self._running: Job | None = None
        self._timers: dict[str, asyncio.TimerHandle] = {}
        self.closed = False

    # ---- the event loop --------------------------------------------------------------------
    @property
    def loop(self) -> asyncio.AbstractEventLoop:
        if self._loop is None:
            self._loop = asyncio.get_running_loop()
        return self._loop

    def bind_loop(self, loop: asyncio.AbstractEventLoop) -> None:
        self._loop = loop

    @property
    def bound_loop(self) -> asyncio.AbstractEventLoop | None:
        """The event loop, once the server runs (any thread may read it)."""
        return self._loop

    # ---- the worker ------------------------------------------------------------------------
    def _in_database(self, fn: Callable[[], T]) -> T:
        with self.database.active():
            return fn()

    def start(self, fn: Callable[[], object]) -> None:
        """Run ``fn`` in the worker, no one waiting for it."""
        self._executor.submit(self._in_database, fn)

    async def in_worker(self, fn: Callable[[], T]) -> T:
        """Run ``fn`` in the worker thread, after the work queued before it."""
        return await self.loop.run_in_executor(self._executor, self._in_database, fn)

    def submit(self, fn: Callable[[], T], then: Callable[[T], None] | None = None) -> None:
        """Run ``fn`` in the worker, then ``then`` with its result on the loop; a failure of
        either is reported, and the server goes on."""
        if self.closed:
            return
        try:
            future = self.loop.run_in_executor(self._executor, self._in_database, fn)
        except RuntimeError:  # executor shut down
            return

        def done(f: asyncio.Future[T]) -> None:
            if f.cancelled():
                return
            error = f.exception()
            if error is not None:
                self._report(f"fanuc-macro: internal error: {error!r}", error)
                return
            if then is not None:
                try:
                    then(f.result())
                except Exception as err:  # a bug on the loop side must not stop the server
                    self._report(f"fanuc-macro: internal error: {err!r}", err)

        future.add_done_callback(done)

    # ---- debounce and queue ----------------------------------------------------------------
    def later(self, key: str, delay: float, request: Callable[[str], None]) -> None:
        """``request(key)`` after ``delay`` seconds without a newer call for ``key``."""
        self.drop_timer(key)
        if delay <= 0:
            request(key)
        else:
            self._timers[key] = self.loop.call_later(delay, request, key)

    def drop_timer(self, key: str) -> None:
        timer = self._timers.pop(key, None)
        if timer is not None:
            timer.cancel()

    def waiting(self, key: str) -> bool:
        """An analysis of ``key`` is due: its timer runs or it is queued."""
        with self._lock:
            return key in self._timers or key in self._queued

    def enqueue(self, key: str) -> bool:
        """Queue an analysis of ``key``; False when one is queued (it reads the newest text)."""
        self._timers.pop(key, None)
        with self._lock:
            if key in self._queued:
                return False
            self._queued.add(key)
            return True

    def dequeue(self, key: str) -> None:
        with self._lock:
            self._queued.discard(key)

    # ---- the running job -------------------------------------------------------------------
    def running(self, job: Job | None) -> None:
        with self._lock:
            self._running = job

    def cancel_running(self, which: Callable[[Job], bool]) -> None:
        """Cancel the running analysis if ``which`` says so; any thread."""
        with self._lock:
            job = self._running
            if job is not None and which(job):
                job.token.cancel()

    def read_by(self, job: Job, keys: frozenset[str], newer: Callable[[], bool]) -> None:
        """Record the documents ``job`` reads (an edit of one cancels it from now on) and
        cancel it if ``newer()`` says one changed before."""
        with self._lock:
            job.keys = keys
        if newer():
            job.token.cancel()

    def shutdown(self) -> None:
        self.closed = True
        self.cancel_running(lambda job: True)
        for timer in self._timers.values():
            timer.cancel()
        self._timers.clear()
        self._executor.shutdown(wait=False, cancel_futures=True)


__all__ = ("Job", "Scheduler")
