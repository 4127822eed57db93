"""Standard output, error and input as every command uses them: output that its encoding cannot
take is escaped, never a crash; ``-`` as a path reads standard input's bytes."""

from __future__ import annotations

import codecs
import contextlib
import sys
from typing import TextIO

STDIN = "-"
_UNICODE = frozenset({"utf-8", "utf-16", "utf-32", "gb18030", "utf-8-sig"})


def tolerate_unencodable(command: str | None = None) -> None:
    """Let standard output and error write what their encoding cannot hold (a Chinese comment
    quoted in a message, on a Windows console or a file redirected in cp1252) as escapes: a
    backslash escape, or in ``plot``'s SVG an XML character reference, which keeps the SVG
    valid."""
    for stream, errors in (
        (sys.stdout, "xmlcharrefreplace" if command == "plot" else "backslashreplace"),
        (sys.stderr, "backslashreplace"),
    ):
        reconfigure = getattr(stream, "reconfigure", None)  # not on a StringIO put in its place
        if reconfigure is not None:
            with contextlib.suppress(ValueError, OSError):  # closed: nothing goes to it
                reconfigure(errors=errors)


def writes_unicode(stream: TextIO) -> bool:
    """Whether ``stream`` takes every character: when not, JSON is written with ``\\u``
    escapes (``ensure_ascii``), which any JSON reader turns back into the characters."""
    encoding = getattr(stream, "encoding", None)
    if not encoding:
        return True
    try:
        return codecs.lookup(encoding).name in _UNICODE
    except LookupError:
        return False


def read_stdin() -> bytes:
    """Standard input's bytes, decoded later as a file's are (the workspace guesses GB18030 or
    Shift-JIS as for a file)."""
    if sys.stdin is None:
        return b""
    buffer = getattr(sys.stdin, "buffer", None)
    if buffer is not None:
        data: bytes = buffer.read()
        return data
    return sys.stdin.read().encode("utf-8")


__all__ = ("STDIN", "read_stdin", "tolerate_unencodable", "writes_unicode")
