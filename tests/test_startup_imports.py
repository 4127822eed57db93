"""What the language server loads before it answers ``initialize``: the protocol's packages,
not the analysis (lark, numpy, the rules, the evaluator), which the first document needs and
not the start. Noted at each write to standard output, in a real server process."""

from __future__ import annotations

import gc
import io
import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

from fanuc_macro.framing import Reframed

# Loaded after initialize is answered.
ANALYSIS = (
    "lark",
    "numpy",
    "fanuc_macro.analysis",
    "fanuc_macro.workspace",
    "fanuc_macro.rules",
    "fanuc_macro.evaluator",
    "fanuc_macro.syntax.parser",
    "fanuc_macro.syntax.tree",
    "fanuc_macro.lsp.features",
)

# The server's start as `python -m fanuc_macro.lsp.server` makes it (on the C allocator, as
# after its start again), with a standard output that notes the modules loaded at each write.
START = """
import gc, json, sys
sys.orig_argv = [sys.executable, "-m", "fanuc_macro.lsp.server"]
writes = []
collecting = []

class Noting:
    def __init__(self, stream):
        self.stream = stream
    def write(self, data):
        writes.append([data.decode(), sorted(sys.modules)])
        collecting.append(gc.isenabled())
        return self.stream.write(data)
    def flush(self):
        self.stream.flush()
    def close(self):
        pass
    def fileno(self):
        return self.stream.fileno()

class Text:
    def __init__(self, stream):
        self.buffer = Noting(stream)

sys.stdout = Text(open(sys.argv[1], "wb"))
import fanuc_macro.lsp.server
status = fanuc_macro.lsp.server.main([])
with open(sys.argv[2], "w") as file:
    json.dump({"status": status, "writes": writes, "collecting": collecting}, file)
"""


def _framed(payload: dict[str, Any]) -> bytes:
    body = json.dumps(payload).encode()
    return b"Content-Length: %d\r\n\r\n" % len(body) + body


def _session(process_id: object = 4321, capabilities: dict[str, Any] | None = None) -> bytes:
    params = {"processId": process_id, "rootUri": None, "capabilities": capabilities or {}}
    return b"".join(
        _framed(m)
        for m in (
            {"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": params},
            {"jsonrpc": "2.0", "id": 2, "method": "shutdown"},
            {"jsonrpc": "2.0", "method": "exit"},
        )
    )


def _bodies(output: bytes) -> list[dict[str, Any]]:
    reader = Reframed(io.BytesIO(output))
    found = []
    while (header := reader.readline()) != b"":
        length = int(header.split(b":")[1])
        while reader.readline() not in (b"\r\n", b""):
            pass
        found.append(json.loads(reader.read(length)))
    return found


Write = tuple[str, set[str], bool]  # what was written, the modules loaded, the collector on


def _start(tmp_path: Path, session: bytes) -> tuple[list[Write], bytes, str]:
    """The writes of a server's session (each with the modules then loaded and whether the
    cyclic collector was on), all it wrote, and its log."""
    out, result = tmp_path / "out.bin", tmp_path / "result.json"
    env = {
        **os.environ,
        "FANUC_MACRO_CODE_CACHE": str(tmp_path / "cache"),
        "PYTHONMALLOC": "malloc",
    }
    done = subprocess.run(
        [sys.executable, "-c", START, str(out), str(result)],
        input=session,
        capture_output=True,
        env=env,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr.decode()
    report = json.loads(result.read_text())
    assert report["status"] == 0
    writes = [
        (data, set(modules), on)
        for (data, modules), on in zip(report["writes"], report["collecting"], strict=True)
    ]
    return writes, out.read_bytes(), done.stderr.decode()


def _loaded(modules: set[str], names: tuple[str, ...]) -> set[str]:
    return {m for m in modules for name in names if m == name or m.startswith(name + ".")}


def test_initialize_is_answered_before_the_analysis_loads(tmp_path: Path) -> None:
    writes, output, _ = _start(tmp_path, _session())
    answer, loaded, _ = writes[0]
    assert '"id": 1' in answer and '"capabilities"' in answer
    assert "pygls" in loaded and not _loaded(loaded, ANALYSIS)
    assert [m.get("id") for m in _bodies(output)] == [1, 2]


def test_the_collector_rests_until_initialize_is_answered(tmp_path: Path) -> None:
    # The start's objects all live on: the collector is paused while they are made, and back
    # once initialize is answered, for the whole session after it.
    writes, _, _ = _start(tmp_path, _session())
    assert [on for _, _, on in writes] == [False, True]


def test_the_collector_resumes_for_a_client_that_does_not_initialize(tmp_path: Path) -> None:
    session = b"".join(
        _framed(m)
        for m in (
            {"jsonrpc": "2.0", "method": "$/setTrace", "params": {"value": "off"}},
            {"jsonrpc": "2.0", "id": 2, "method": "shutdown"},
            {"jsonrpc": "2.0", "method": "exit"},
        )
    )
    writes, _, _ = _start(tmp_path, session)
    assert [on for _, _, on in writes] == [True]


def test_the_collector_runs_in_other_processes() -> None:
    # Importing the server's modules (the tests, the command line) pauses nothing.
    import fanuc_macro.lsp.server  # noqa: F401

    assert gc.isenabled()
