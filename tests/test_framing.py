"""The reader of the language server's and the debugger's input: each message's body whole,
whatever headers come before its Content-Length (the base protocol allows Content-Type)."""

from __future__ import annotations

import io

import pytest

from fanuc_macro.framing import Reader, WireError


def _bodies(stream: bytes) -> list[bytes]:
    reader = Reader(io.BytesIO(stream))
    found: list[bytes] = []
    while (body := reader.read_body()) is not None:
        found.append(body)
    return found


@pytest.mark.parametrize(
    "headers",
    [
        b"Content-Length: 13\r\n\r\n",
        b"Content-Type: application/vscode-jsonrpc; charset=utf-8\r\nContent-Length: 13\r\n\r\n",
        b"Content-Length: 13\r\nContent-Type: application/vscode-jsonrpc\r\n\r\n",
    ],
    ids=["alone", "a header before", "a header after"],
)
def test_each_body_is_read_whole_whatever_the_other_headers(headers: bytes) -> None:
    assert _bodies(headers + b'{"id": 12345}' + headers + b'{"id": 67890}') == [
        b'{"id": 12345}',
        b'{"id": 67890}',
    ]


def test_bytes_that_are_no_message_are_skipped_with_a_wire_error() -> None:
    reader = Reader(io.BytesIO(b"garbage\r\nContent-Length: 2\r\n\r\n{}"))
    with pytest.raises(WireError, match="skipped"):
        reader.read_body()
    assert reader.read_body() == b"{}"
