"""Messages framed as the Language Server and the Debug Adapter Protocols frame them: a
``Content-Length`` header, a blank line, a JSON body (the LSP specification, "Base Protocol";
https://microsoft.github.io/debug-adapter-protocol/overview, "Base protocol").

The reader finds the next valid header after garbage, a wrong length or a cut message, so one
bad message costs that message, not the session. The debug adapter reads its messages with
:class:`Reader`; the language server gives pygls a :class:`Reframed` standard input, since
pygls takes every length on trust and wants each header line exactly as it writes them.
"""

from __future__ import annotations

import json
import logging
import re
from collections.abc import Callable
from typing import IO, Any

log = logging.getLogger(__name__)

# A body larger than this is not a request any client sends: it is read and dropped.
MAX_BODY = 64 * 1024 * 1024


# A header block: Content-Length, maybe other headers, a blank line. No valid JSON body can hold
# one (a JSON string cannot hold a raw line break), so one seen inside a body means the body is
# cut short or its length is wrong: reading starts again at it.
_HEADER = re.compile(
    rb"Content-Length[ \t]*:[ \t]*(\d{1,19})[ \t]*\r?\n"
    rb"(?:[A-Za-z][A-Za-z0-9-]*[ \t]*:[^\r\n]*\r?\n)*\r?\n",
    re.IGNORECASE,
)
# Header lines before Content-Length (Content-Type) are no garbage.
_OTHER_HEADERS = re.compile(rb"\s*(?:[A-Za-z][A-Za-z0-9-]*[ \t]*:[^\r\n]*\r?\n\s*)*")
_KEEP = 256  # the tail kept while no header is found: a header may be split across reads


class WireError(Exception):
    """A message that cannot be read (a bad header or body); the stream goes on after it."""


class Reader:
    def __init__(self, stream: IO[bytes]) -> None:
        self.stream = stream
        self._buf = bytearray()
        self._eof = False
        read1 = getattr(stream, "read1", None)
        self._read_some: Callable[[], bytes] = (
            (lambda: read1(1 << 16)) if callable(read1) else (lambda: stream.readline(1 << 16))
        )

    def _fill(self) -> bool:
        """More bytes into the buffer; False at the end of the stream."""
        if self._eof:
            return False
        chunk = self._read_some()
        if not chunk:
            self._eof = True
            return False
        self._buf += chunk
        return True

    def read(self) -> dict[str, Any] | None:
        """The next message; None at the end of the stream. A WireError says what was skipped;
        the next call reads on from the next header."""
        body = self.read_body()
        if body is None:
            return None
        try:
            message = json.loads(body.decode("utf-8"))
        except (UnicodeDecodeError, json.JSONDecodeError) as err:
            raise WireError(f"a message that is not JSON: {err}") from None
        except RecursionError:
            raise WireError("a message nested too deep to read") from None
        if not isinstance(message, dict):
            raise WireError("a message that is not a JSON object")
        return message

    def read_body(self) -> bytes | None:
        """The next message's body, unparsed; None at the end of the stream. A WireError says
        what was skipped; the next call reads on from the next header."""
        skipped = 0
        searched = 0
        while True:
            header = _HEADER.search(self._buf, searched)
            if header is not None:
                break
            junk = len(self._buf) - _KEEP
            if junk > 0:
                skipped += len(self._buf[:junk].strip())
                del self._buf[:junk]
            searched = max(0, len(self._buf) - _KEEP)
            if not self._fill():
                self._buf.clear()
                return None
        # Read from the match before the buffer moves: its groups are slices of the buffer.
        length = int(header.group(1))
        start = header.end() - header.start()
        before = bytes(self._buf[: header.start()])
        del self._buf[: header.start()]
        if skipped or not _OTHER_HEADERS.fullmatch(before):
            raise WireError(f"skipped {skipped + len(before.strip()):,} bytes that are no message")
        if length > MAX_BODY:
            self._drop(start, length)
            return None  # the end of the stream inside it
        searched = start
        while len(self._buf) - start < length:
            following = _HEADER.search(self._buf, searched)
            if following is not None:
                del self._buf[: following.start()]
                raise WireError(
                    f"a message shorter than its Content-Length of {length:,}: "
                    "read on from the next header"
                )
            searched = max(start, len(self._buf) - _KEEP)
            if not self._fill():
                self._buf.clear()
                return None
        body = bytes(self._buf[start : start + length])
        del self._buf[: start + length]
        following = _HEADER.search(body)
        if following is not None:  # a length that swallowed the next message: no JSON holds one
            self._buf[:0] = body[following.start() :]
            raise WireError(
                f"a message whose Content-Length of {length:,} runs into the next message"
            )
        return body

    def _drop(self, start: int, length: int) -> None:
        """Skips a body too large to hold (or up to a header inside it), then says so."""
        del self._buf[:start]
        remaining = length
        while True:
            following = _HEADER.search(self._buf)
            if following is not None:
                del self._buf[: following.start()]
                break
            if len(self._buf) >= remaining:
                del self._buf[:remaining]
                break
            cut = max(0, len(self._buf) - _KEEP)
            del self._buf[:cut]
            remaining -= cut
            if not self._fill():
                self._buf.clear()
                return None
        raise WireError(f"a message of {length:,} bytes is too large")


class Reframed:
    """A binary input stream of well-framed messages, read from ``stream`` by :class:`Reader`:
    what pygls' reader reads (``readline`` for headers, ``read`` for a body). A message that
    cannot be framed is logged and skipped."""

    def __init__(self, stream: IO[bytes]) -> None:
        self._reader = Reader(stream)
        self._pending = bytearray()

    def _next(self) -> bool:
        """The next message, framed, onto the pending bytes; False at the end of the stream."""
        while True:
            try:
                body = self._reader.read_body()
            except WireError as err:
                log.warning("a message could not be read: %s", err)
                continue
            if body is None:
                return False
            self._pending += b"Content-Length: %d\r\n\r\n" % len(body) + body
            return True

    def readline(self, limit: int = -1) -> bytes:
        while b"\n" not in self._pending and self._next():
            pass
        end = self._pending.find(b"\n") + 1 or len(self._pending)
        if limit >= 0:
            end = min(end, limit)
        line = bytes(self._pending[:end])
        del self._pending[:end]
        return line

    def read(self, size: int = -1) -> bytes:
        while (size < 0 or len(self._pending) < size) and self._next():
            pass
        end = len(self._pending) if size < 0 else min(size, len(self._pending))
        data = bytes(self._pending[:end])
        del self._pending[:end]
        return data


__all__ = ("MAX_BODY", "Reader", "Reframed", "WireError")
