"""Messages of the Debug Adapter Protocol written to a byte stream, with the sequence numbers
the protocol wants (https://microsoft.github.io/debug-adapter-protocol/overview, "Base
protocol"). They are read by :class:`fanuc_macro.framing.Reader`, shared with the language
server."""

from __future__ import annotations

import json
import threading
from typing import IO, Any


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
