"""The language server over raw stdio: messages no client library can send (malformed JSON-RPC)
are answered with an error, and the server goes on."""

from __future__ import annotations

import json
from collections.abc import Iterator
from typing import Any

import pytest

from raw_stdio import RawLspClient as RawClient


@pytest.fixture
def lsp() -> Iterator[RawClient]:
    client = RawClient()
    yield client
    client.close()


INITIALIZE = {
    "jsonrpc": "2.0",
    "id": 100,
    "method": "initialize",
    "params": {"processId": None, "rootUri": None, "capabilities": {}},
}


@pytest.mark.parametrize(
    ("message", "said"),
    [
        ({"jsonrpc": "2.0", "id": 7}, "no method"),
        ({"jsonrpc": "2.0", "id": "seven", "params": {}}, "no method"),
        ({"id": 7, "method": "initialize", "params": {}}, '"jsonrpc" must be "2.0"'),
        ({"jsonrpc": "1.0", "id": 7, "method": "shutdown"}, '"jsonrpc" must be "2.0"'),
        ({"jsonrpc": "2.0", "id": 7, "method": 12}, "not a string"),
    ],
)
def test_an_invalid_request_gets_invalid_request(
    lsp: RawClient, message: dict[str, Any], said: str
) -> None:
    lsp.send(message)
    answer = lsp.answer(message["id"])
    assert answer["error"]["code"] == -32600, answer
    assert said in answer["error"]["message"], answer
    lsp.send(INITIALIZE)
    assert "capabilities" in lsp.answer(100)["result"]


def test_a_cancel_request_is_taken_as_one_and_no_error_is_shown(lsp: RawClient) -> None:
    # Its params {"id": 7} look like a request without "jsonrpc" once read on their own.
    lsp.send(INITIALIZE)
    assert "capabilities" in lsp.answer(100)["result"]
    lsp.send({"jsonrpc": "2.0", "method": "initialized", "params": {}})
    lsp.send({"jsonrpc": "2.0", "method": "$/cancelRequest", "params": {"id": 7}})
    lsp.send({"jsonrpc": "2.0", "id": 8, "method": "workspace/symbol", "params": {"query": "O"}})
    seen: list[dict[str, Any]] = []
    while True:
        message = lsp.messages.get(timeout=30)
        assert message is not None
        seen.append(message)
        if message.get("id") == 8 and "method" not in message:
            break
    assert "result" in seen[-1], seen[-1]
    shown = [m for m in seen if m.get("method") == "window/showMessage"]
    assert shown == [], shown
    assert not [m for m in seen if m.get("id") == 7], seen


@pytest.mark.parametrize(
    "bad",
    [
        # A length larger than its body: pygls would read the next messages as its body.
        b'Content-Length: 9999\r\n\r\n{"jsonrpc": "2.0", "id": 1, "method": "shutdown"',
        b"Content-Length: 9999\r\n\r\n{}",
        # A length that is no number, with no line end: glued in front of the next header.
        b"Content-Length: abc",
        b"\x00\xff garbage Content-Length: 12",
        # A header line pygls does not take (another spacing) before a valid message.
        b"content-length:3\r\n\r\n{}}",
    ],
)
def test_the_server_finds_the_next_message_after_a_bad_one(lsp: RawClient, bad: bytes) -> None:
    lsp.send(INITIALIZE)
    assert "capabilities" in lsp.answer(100)["result"]
    lsp.send({"jsonrpc": "2.0", "method": "initialized", "params": {}})
    lsp.send_raw(bad)
    ids = list(range(200, 220))
    for msg_id in ids:
        lsp.send(
            {
                "jsonrpc": "2.0",
                "id": msg_id,
                "method": "workspace/symbol",
                "params": {"query": "O1"},
            }
        )
    answers = lsp.answers(set(ids))  # in any order: requests run side by side
    assert all("result" in answers[msg_id] for msg_id in ids), answers


def test_a_length_that_swallows_the_next_message_costs_that_message_only(
    lsp: RawClient,
) -> None:
    lsp.send(INITIALIZE)
    lsp.answer(100)
    following = json.dumps({"jsonrpc": "2.0", "id": 300, "method": "shutdown"}).encode()
    short = b'{"jsonrpc": "2.0", "method": "initialized", "params": {}}'
    lsp.send_raw(
        b"Content-Length: %d\r\n\r\n" % (len(short) + 30)
        + short
        + b"Content-Length: %d\r\n\r\n" % len(following)
        + following
    )
    assert lsp.answer(300)["result"] is None
