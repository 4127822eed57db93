"""Messages of the Debug Adapter Protocol on a byte stream: a ``Content-Length`` header, a blank
line, a JSON body (https://microsoft.github.io/debug-adapter-protocol/overview, "Base
protocol")."""

from __future__ import annotations

import json
import threading
from typing import IO, Any

# A body larger than this is not a request any client sends: it is read and dropped.
MAX_BODY = 64 * 1024 * 1024


class WireError(Exception):
    """A message that cannot be read (a bad header or body); the stream goes on after it."""


class Reader:
    def __init__(self, stream: IO[bytes]) -> None:
        self.stream = stream

    def read(self) -> dict[str, Any] | None:
        """The next message; None at the end of the stream."""
        length: int | None = None
        while True:
            line = self.stream.readline(65536)
            if not line:
                return None
            text = line.decode("ascii", "replace").strip()
            if not text:
                if length is None:
                    continue  # blank lines between messages
                break
            name, _, value = text.partition(":")
            if name.strip().lower() == "content-length":
                try:
                    length = int(value.strip())
                except ValueError:
                    raise WireError(f"bad Content-Length header: {text!r}") from None
        if length < 0:
            raise WireError(f"bad Content-Length: {length}")
        body = b""
        remaining = length
        while remaining > 0:
            chunk = self.stream.read(min(remaining, 1 << 20))
            if not chunk:
                return None
            if len(body) < MAX_BODY:
                body += chunk
            remaining -= len(chunk)
        if length > MAX_BODY:
            raise WireError(f"a message of {length:,} bytes is too large")
        try:
            message = json.loads(body.decode("utf-8"))
        except (UnicodeDecodeError, json.JSONDecodeError) as err:
            raise WireError(f"a message that is not JSON: {err}") from None
        if not isinstance(message, dict):
            raise WireError("a message that is not a JSON object")
        return message


class Writer:
    """Writes messages whole, from any thread, with the sequence numbers the protocol wants."""

    def __init__(self, stream: IO[bytes]) -> None:
        self.stream = stream
        self._lock = threading.Lock()
        self._seq = 0

    def send(self, message: dict[str, Any]) -> None:
        with self._lock:
            self._seq += 1
            body = json.dumps({"seq": self._seq, **message}, ensure_ascii=False).encode("utf-8")
            self.stream.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
            self.stream.flush()
