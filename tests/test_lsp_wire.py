"""The language server over raw stdio: messages no client library can send (malformed JSON-RPC)
are answered with an error, and the server goes on."""

from __future__ import annotations

import json
import queue
import subprocess
import sys
import threading
from collections.abc import Iterator
from typing import IO, Any

import pytest

WAIT_S = 30.0  # a safety net for a server that does not answer


class RawClient:
    def __init__(self) -> None:
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "fanuc_macro.lsp.server"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
        )
        self.messages: queue.Queue[dict[str, Any] | None] = queue.Queue()
        assert self.proc.stdout is not None
        threading.Thread(target=self._read, args=(self.proc.stdout,), daemon=True).start()

    def _read(self, stream: IO[bytes]) -> None:
        while True:
            length = None
            while True:
                line = stream.readline()
                if not line:
                    self.messages.put(None)
                    return
                if line in (b"\r\n", b"\n"):
                    break
                name, _, value = line.decode().partition(":")
                if name.lower() == "content-length":
                    length = int(value)
            assert length is not None
            self.messages.put(json.loads(stream.read(length)))

    def send_raw(self, data: bytes) -> None:
        assert self.proc.stdin is not None
        self.proc.stdin.write(data)
        self.proc.stdin.flush()

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

    def close(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait(timeout=10)
        for stream in (self.proc.stdin, self.proc.stdout):
            if stream is not None:
                stream.close()


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
