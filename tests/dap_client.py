"""A Debug Adapter Protocol client over stdio, for the tests: it starts ``fanuc-macro-dap`` as a
subprocess (``python -m fanuc_macro.dap``) and speaks to it as an editor does."""

from __future__ import annotations

import contextlib
import json
import queue
import subprocess
import sys
from collections.abc import Callable
from typing import Any

from raw_stdio import StdioProcess

WAIT_S = 60.0  # a safety net for a broken adapter, not a time the tests measure


class DapClient(StdioProcess):
    def __init__(self, *args: str) -> None:
        super().__init__([sys.executable, "-m", "fanuc_macro.dap", *args], subprocess.PIPE)
        self._seq = 0
        self.events: list[dict[str, Any]] = []  # every event so far, in order
        self._pending: list[dict[str, Any]] = []

    def send(self, command: str, arguments: dict[str, Any] | None = None) -> int:
        self._seq += 1
        message: dict[str, Any] = {"seq": self._seq, "type": "request", "command": command}
        if arguments is not None:
            message["arguments"] = arguments
        body = json.dumps(message).encode()
        self.send_raw(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        return self._seq

    def _next(self, wanted: Callable[[dict[str, Any]], bool]) -> dict[str, Any]:
        for i, m in enumerate(self._pending):
            if wanted(m):
                return self._pending.pop(i)
        while True:
            m = self.messages.get(timeout=WAIT_S)
            if m is None:
                raise EOFError("the adapter closed its output")
            if m.get("type") == "event":
                self.events.append(m)
            if wanted(m):
                return m
            self._pending.append(m)

    def request(self, command: str, arguments: dict[str, Any] | None = None) -> dict[str, Any]:
        """The response, success or not."""
        seq = self.send(command, arguments)
        return self._next(lambda m: m.get("type") == "response" and m.get("request_seq") == seq)

    def ok(self, command: str, arguments: dict[str, Any] | None = None) -> dict[str, Any]:
        """The body of a successful response."""
        response = self.request(command, arguments)
        assert response["success"], response
        body: dict[str, Any] = response.get("body") or {}
        return body

    def event(self, name: str) -> dict[str, Any]:
        return self._next(lambda m: m.get("type") == "event" and m.get("event") == name)

    def stopped(self) -> dict[str, Any]:
        body: dict[str, Any] = self.event("stopped")["body"]
        return body

    def output_text(self) -> str:
        return "".join(e["body"]["output"] for e in self.events if e.get("event") == "output")

    def start(
        self,
        launch: dict[str, Any],
        breakpoints: dict[str, list[dict[str, Any]]] | None = None,
        filters: list[str] | None = None,
        locale: str | None = None,
    ) -> dict[str, Any]:
        """initialize (in the client's ``locale``), launch, the breakpoints,
        configurationDone: the initialize body."""
        initialize = {"adapterID": "fanuc-macro", "linesStartAt1": True, "columnsStartAt1": True}
        caps = self.ok("initialize", initialize | ({"locale": locale} if locale else {}))
        self.ok("launch", launch)
        self.event("initialized")
        for path, bps in (breakpoints or {}).items():
            self.ok("setBreakpoints", {"source": {"path": path}, "breakpoints": bps})
        if filters is not None:
            self.ok("setExceptionBreakpoints", {"filters": filters})
        self.ok("configurationDone")
        return caps

    def evaluate(self, expression: str, frame_id: int | None = None) -> str:
        args: dict[str, Any] = {"expression": expression, "context": "watch"}
        if frame_id is not None:
            args["frameId"] = frame_id
        result: str = self.ok("evaluate", args)["result"]
        return result

    def close(self) -> int:
        if self.proc.poll() is None:
            with contextlib.suppress(EOFError, queue.Empty, BrokenPipeError, OSError):
                self.request("disconnect", {"terminateDebuggee": True})
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        for stream in (self.proc.stdin, self.proc.stdout, self.proc.stderr):
            if stream is not None:
                stream.close()
        return self.proc.returncode
