"""A client of the servers over raw stdio, for the tests: messages read as framed on the wire
(a ``Content-Length`` header, a blank line, a JSON body), and bytes written as given, so a test
can send what no client library sends."""

from __future__ import annotations

import json
import queue
import subprocess
import sys
import threading
import time
from typing import IO, Any

WAIT_S = 30.0  # a safety net for a server that does not answer


def read_messages(stream: IO[bytes], messages: queue.Queue[dict[str, Any] | None]) -> None:
    """Put each message read from ``stream`` into ``messages``, then None at its end."""
    while True:
        length = None
        while True:
            line = stream.readline()
            if not line:
                messages.put(None)
                return
            if line in (b"\r\n", b"\n"):
                break
            name, _, value = line.decode().partition(":")
            if name.lower() == "content-length":
                length = int(value)
        assert length is not None
        messages.put(json.loads(stream.read(length)))


class StdioProcess:
    """A server started as a subprocess: its messages read into ``messages`` by a thread, and
    bytes written to it as given."""

    def __init__(self, argv: list[str], stderr: int = subprocess.DEVNULL) -> None:
        self.proc = subprocess.Popen(
            argv, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=stderr
        )
        self.messages: queue.Queue[dict[str, Any] | None] = queue.Queue()
        assert self.proc.stdout is not None
        threading.Thread(
            target=read_messages, args=(self.proc.stdout, self.messages), daemon=True
        ).start()

    def send_raw(self, data: bytes) -> None:
        assert self.proc.stdin is not None
        self.proc.stdin.write(data)
        self.proc.stdin.flush()


class RawLspClient(StdioProcess):
    """The language server as an editor starts it (``python -m fanuc_macro.lsp.server``)."""

    def __init__(self) -> None:
        super().__init__([sys.executable, "-m", "fanuc_macro.lsp.server"])

    def send(self, message: dict[str, Any]) -> None:
        body = json.dumps(message).encode()
        self.send_raw(b"Content-Length: %d\r\n\r\n" % len(body) + body)

    def answer(self, msg_id: object) -> dict[str, Any]:
        while True:
            message = self.messages.get(timeout=WAIT_S)
            if message is None:
                raise EOFError("the server closed its output")
            if message.get("id") == msg_id and "method" not in message:
                return message

    def answers(self, ids: set[object]) -> dict[object, dict[str, Any]]:
        """The answers to the requests ``ids``, whichever comes first."""
        found: dict[object, dict[str, Any]] = {}
        while len(found) < len(ids):
            message = self.messages.get(timeout=WAIT_S)
            if message is None:
                raise EOFError("the server closed its output")
            if message.get("id") in ids and "method" not in message:
                found[message["id"]] = message
        return found

    def initialize(self, msg_id: int = 1) -> dict[str, Any]:
        """The ``initialize`` request of a client with no capabilities, and its answer."""
        self.send(
            {
                "jsonrpc": "2.0",
                "id": msg_id,
                "method": "initialize",
                "params": {"processId": None, "rootUri": None, "capabilities": {}},
            }
        )
        return self.answer(msg_id)

    def notify(self, method: str, params: dict[str, Any]) -> None:
        self.send({"jsonrpc": "2.0", "method": method, "params": params})

    def published(self, uri: str, version: int, seconds: float = 10.0) -> None:
        """Wait for the diagnostics of ``uri`` at ``version`` or later, or ``seconds`` (the
        server publishes nothing when they did not change)."""
        end = time.monotonic() + seconds
        while (left := end - time.monotonic()) > 0:
            try:
                message = self.messages.get(timeout=left)
            except queue.Empty:
                return
            if message is None:
                raise EOFError("the server closed its output")
            params = message.get("params") or {}
            if (
                message.get("method") == "textDocument/publishDiagnostics"
                and params.get("uri") == uri
                and (params.get("version") or 0) >= version
            ):
                return

    def rss_mb(self) -> float:
        """The server's resident memory (Linux: /proc)."""
        with open(f"/proc/{self.proc.pid}/status", encoding="ascii") as status:
            for line in status:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024
        raise AssertionError("no VmRSS")

    def close(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait(timeout=10)
        for stream in (self.proc.stdin, self.proc.stdout):
            if stream is not None:
                stream.close()


__all__ = ("WAIT_S", "RawLspClient", "StdioProcess", "read_messages")
