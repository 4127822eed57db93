"""Measures fanuc-macro-ls as an editor sees it: a real server process over stdio.

Prints: the first analysis of a 20,000-block program, keystroke -> diagnostics latency (total
and after the debounce), how many analyses a burst of typing publishes, hover latency while the
analysis is fresh, and the server's resident memory; then, in a server of its own, a keystroke
during the analysis of a 200,000-block CAM file -> the newer version's diagnostics (the running
analysis is cancelled). Not a test: figures depend on the machine.

    python bench/bench_lsp.py [--blocks 20000] [--debounce 250] [--read-whole] [--no-cancel]
    python bench/bench_lsp.py --only-cancel [--server-pythonpath ../main/server]
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import os
import statistics
import sys
import time
from pathlib import Path
from typing import Any

from lsprotocol import types
from pygls.lsp.client import LanguageClient

ROOT = Path(__file__).resolve().parents[1]
SEEDS = ROOT / "tests" / "fixtures" / "seeds"


def program(blocks: int, distinct: bool = False) -> str:
    """A main program of about ``blocks`` blocks in the style of the seeds: thread passes
    computed by macro statements, with comments in Chinese, a loop and a subprogram call.

    The passes' code repeats every few thousand blocks, as a program's passes do, and only the
    comments number them; ``distinct`` numbers the code too, so that no two blocks are alike:
    the case where the parser and the compiler share nothing between lines."""
    lines = [
        "%",
        "O1000 (性能测试 主程序)",
        "T0101 (外螺纹车刀)",
        "G97 S400 M03 M8",
        "#100=50. (公称直径)",
        "#101=3. (螺距)",
        "#102=50. (长度)",
    ]
    i = 0
    while len(lines) < blocks - 12:
        i += 1
        if distinct:
            lines += [
                f"#{1 + i % 30}=#101*{i}.+SQRT[{i % 11 + 1}.] (计算 {i})",
                f"G00 X[#100+{i % 5 + 1}.] Z{i % 9 + 2}.{i}",
                f"G92 X[#100-0.{i % 9 + 1}] W-[#102+#101+0.{i}] F#101 (螺纹加工 {i})",
                f"G01 W[{i}.*0.0001] (偏移)",
            ]
            continue
        lines += [
            f"#{1 + i % 30}=#101*{i % 7 + 1}.+SQRT[{i % 11 + 1}.] (计算 {i})",
            f"G00 X[#100+{i % 5 + 1}.] Z{i % 9 + 2}.",
            f"G92 X[#100-0.{i % 9 + 1}] W-[#102+#101] F#101 (螺纹加工 {i})",
            f"G01 W[{i % 3}.*0.1] (偏移)",
        ]
    lines += [
        "#20=0",
        "WHILE[#20LT25]DO1",
        "#20=#20+1 (计数)",
        "G01 U-0.1 W0.1",
        "END1",
        "M98 P0013331 (调用子程序)",
        "G00 X100. Z100.",
        "M5",
        "M9",
        "M30",
        "%",
    ]
    return "\n".join(lines) + "\n"


def cam_program(blocks: int) -> str:
    """CAM output: a macro header, then plain G01 X Y Z blocks, no two alike."""
    rows = [
        f"G01 X{i / 1000:.3f} Y{(i * 7919) % 100_003 / 1000:.3f} Z-{i % 977 / 100:.2f}"
        for i in range(blocks)
    ]
    head = ["%", "O1234 (CAM)", "#100=2.", "#101=#100*3.", "G90 G54 G00 X0 Y0", "S3000 M03"]
    return "\n".join([*head, *rows, "M30", "%"]) + "\n"


class Bench:
    def __init__(self) -> None:
        self.client = LanguageClient("fanuc-macro-bench", "0.1")
        self.published: list[tuple[float, str, int | None, int]] = []
        self.event = asyncio.Event()

        @self.client.feature(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
        def on_diagnostics(params: types.PublishDiagnosticsParams) -> None:
            self.published.append(
                (time.perf_counter(), params.uri, params.version, len(params.diagnostics))
            )
            self.event.set()

        @self.client.feature(types.WINDOW_LOG_MESSAGE)
        def on_log(params: types.LogMessageParams) -> None:
            print(f"  server log: {params.message[:200]}", file=sys.stderr)

    async def wait_version(self, uri: str, version: int, timeout: float = 120.0) -> float:
        deadline = time.perf_counter() + timeout
        while True:
            for at, p_uri, p_version, _ in self.published:
                if p_uri == uri and p_version is not None and p_version >= version:
                    return at
            self.event.clear()
            remaining = deadline - time.perf_counter()
            if remaining <= 0:
                raise TimeoutError(f"no diagnostics for version {version}")
            with contextlib.suppress(asyncio.TimeoutError):
                await asyncio.wait_for(self.event.wait(), remaining)


def rss_kib(pid: int) -> dict[str, int]:
    out: dict[str, int] = {}
    try:
        for line in Path(f"/proc/{pid}/status").read_text().splitlines():
            if line.startswith(("VmRSS:", "VmHWM:")):
                out[line.split(":")[0]] = int(line.split()[1])
    except OSError:
        pass
    return out


def ms(seconds: float) -> str:
    return f"{seconds * 1000:.0f} ms"


def change_digit(uri: str, version: int, line: int, column: int, digit: str) -> Any:
    return types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=version),
        content_changes=[
            types.TextDocumentContentChangePartial(
                range=types.Range(
                    start=types.Position(line=line, character=column),
                    end=types.Position(line=line, character=column + 1),
                ),
                text=digit,
            )
        ],
    )


async def cancellation(pythonpath: str, blocks: int, debounce_ms: int, after: float) -> None:
    """A keystroke ``after`` seconds into the analysis of a big CAM file, cold (just opened) and
    warm (just edited): the time until the newer version's diagnostics."""
    bench = Bench()
    client = bench.client
    server = os.environ.get("FANUC_MACRO_BENCH_SERVER", "-m fanuc_macro.lsp.server").split()
    await client.start_io(sys.executable, *server, env={**os.environ, "PYTHONPATH": pythonpath})
    limits = {"maxBlocks": 10 * blocks, "maxFileSize": 100 * blocks}
    await client.initialize_async(
        types.InitializeParams(
            capabilities=types.ClientCapabilities(),
            initialization_options={"analysis": {"debounceMs": debounce_ms, **limits}},
        )
    )
    client.initialized(types.InitializedParams())
    text = cam_program(blocks)
    lines = text.split("\n")
    uri = "untitled:cam.nc"
    line = len(lines) // 2
    column = lines[line].index("X") + 1
    t0 = time.perf_counter()
    client.text_document_did_open(
        types.DidOpenTextDocumentParams(
            text_document=types.TextDocumentItem(
                uri=uri, language_id="fanuc-macro", version=1, text=text
            )
        )
    )
    await asyncio.sleep(after)
    sent = time.perf_counter()
    client.text_document_did_change(change_digit(uri, 2, line, column, "7"))
    got = await bench.wait_version(uri, 2, 600.0)
    print(
        f"cancellation, {len(lines) - 1} lines of CAM output: keystroke {ms(sent - t0)} after "
        f"open -> diagnostics of the newer version: {ms(got - sent)} (open -> them: {ms(got - t0)})"
    )
    client.text_document_did_change(change_digit(uri, 3, line, column, "8"))
    await asyncio.sleep(after)
    sent = time.perf_counter()
    client.text_document_did_change(change_digit(uri, 4, line, column, "9"))
    got = await bench.wait_version(uri, 4, 600.0)
    print(
        f"cancellation: a keystroke {ms(after)} into the analysis of an edit -> diagnostics of "
        f"the newer version: {ms(got - sent)}"
    )
    stale = [p for p in bench.published if p[2] in (1, 3)]
    print(f"versions 1 and 3 published: {len(stale)}")
    await client.shutdown_async(None)
    client.exit(None)
    await client.stop()


async def main(
    blocks: int,
    debounce_ms: int,
    keystrokes: int,
    hovers: int,
    read_whole: bool = False,
    pythonpath: str = str(ROOT / "server"),
    distinct: bool = False,
) -> None:
    bench = Bench()
    client = bench.client
    # Read whole: the limits raised, so that a document past maxBlocks is analysed entire.
    limits = {"maxBlocks": 10 * blocks, "maxFileSize": 100 * blocks} if read_whole else {}
    env = {**os.environ, "PYTHONPATH": pythonpath}
    server = os.environ.get("FANUC_MACRO_BENCH_SERVER", "-m fanuc_macro.lsp.server").split()
    await client.start_io(sys.executable, *server, env=env)
    server = client._server
    assert server is not None
    started = time.perf_counter()
    await client.initialize_async(
        types.InitializeParams(
            capabilities=types.ClientCapabilities(),
            root_uri=SEEDS.as_uri(),
            workspace_folders=[types.WorkspaceFolder(uri=SEEDS.as_uri(), name="seeds")],
            initialization_options={"analysis": {"debounceMs": debounce_ms, **limits}},
        )
    )
    client.initialized(types.InitializedParams())
    print(f"initialize: {ms(time.perf_counter() - started)}")
    print(f"server RSS after start: {rss_kib(server.pid)}")

    text = program(blocks, distinct)
    lines = text.split("\n")
    uri = "untitled:bench.nc"
    version = 1
    t0 = time.perf_counter()
    client.text_document_did_open(
        types.DidOpenTextDocumentParams(
            text_document=types.TextDocumentItem(
                uri=uri, language_id="fanuc-macro", version=version, text=text
            )
        )
    )
    first = await bench.wait_version(uri, version)
    print(f"document: {len(lines) - 1} lines; open -> first diagnostics: {ms(first - t0)}")
    await asyncio.sleep(1.0)  # idle, as between keystrokes: the server has tidied up
    print(f"server RSS after open (1 s idle): {rss_kib(server.pid)}")

    async def keystrokes_at(line: int, column: int, replace: bool) -> list[float]:
        """Type digits at one place, one at a time, waiting for each analysis."""
        nonlocal version
        latencies: list[float] = []
        for k in range(keystrokes):
            version += 1
            at = column if replace else column + k
            sent = time.perf_counter()
            client.text_document_did_change(
                types.DidChangeTextDocumentParams(
                    text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=version),
                    content_changes=[
                        types.TextDocumentContentChangePartial(
                            range=types.Range(
                                start=types.Position(line=line, character=at),
                                end=types.Position(line=line, character=at + int(replace)),
                            ),
                            text=str(k % 9 + 1),
                        )
                    ],
                )
            )
            latencies.append(await bench.wait_version(uri, version) - sent)
        return latencies

    def report(what: str, latencies: list[float]) -> None:
        median = statistics.median(latencies)
        print(
            f"keystroke -> diagnostics, {what} ({keystrokes} edits, debounce {debounce_ms} ms): "
            f"median {ms(median)}, max {ms(max(latencies))}; after the debounce: median "
            f"{ms(median - debounce_ms / 1000)}"
        )

    # In a comment: the program runs the same, the evaluator's facts are kept.
    target_line = len(lines) // 2
    column = lines[target_line].index("(") + 1
    report("typing in a comment", await keystrokes_at(target_line, column, False))
    # In the code: a digit of a computed address changes, the whole program runs again.
    code_line = next(i for i in range(target_line, len(lines)) if "X[#100+" in lines[i])
    digit = lines[code_line].index("X[#100+") + len("X[#100+")
    report("changing a number in the code", await keystrokes_at(code_line, digit, True))
    print(f"server RSS after {2 * keystrokes} keystrokes, at once: {rss_kib(server.pid)}")
    await asyncio.sleep(1.0)
    print(f"server RSS after {2 * keystrokes} keystrokes, 1 s idle: {rss_kib(server.pid)}")

    # A burst of typing faster than the debounce: only the last version should be analysed.
    before = len(bench.published)
    burst = 20
    for _ in range(burst):
        version += 1
        client.text_document_did_change(
            types.DidChangeTextDocumentParams(
                text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=version),
                content_changes=[
                    types.TextDocumentContentChangePartial(
                        range=types.Range(
                            start=types.Position(line=target_line, character=column),
                            end=types.Position(line=target_line, character=column),
                        ),
                        text="x",
                    )
                ],
            )
        )
        await asyncio.sleep(debounce_ms / 1000 / 4)
    await bench.wait_version(uri, version)
    publishes = len(bench.published) - before
    print(f"burst of {burst} edits every {debounce_ms // 4} ms: {publishes} publish(es)")

    # Hover on a variable read in a G92 block, with the analysis fresh.
    hover_line = next(i for i, line in enumerate(lines) if line.startswith("G92"))
    hover_col = lines[hover_line].index("#100") + 1
    times: list[float] = []
    for _ in range(hovers):
        t = time.perf_counter()
        result = await client.text_document_hover_async(
            types.HoverParams(
                text_document=types.TextDocumentIdentifier(uri=uri),
                position=types.Position(line=hover_line, character=hover_col),
            )
        )
        times.append(time.perf_counter() - t)
        assert result is not None
    times.sort()
    print(
        f"hover ({hovers} requests): median {ms(statistics.median(times))}, "
        f"p95 {ms(times[int(len(times) * 0.95) - 1])}"
    )

    seed = (SEEDS / "o4009_external_m50x3.nc").as_uri()
    client.text_document_did_open(
        types.DidOpenTextDocumentParams(
            text_document=types.TextDocumentItem(
                uri=seed,
                language_id="fanuc-macro",
                version=1,
                text=(SEEDS / "o4009_external_m50x3.nc").read_text("utf-8"),
            )
        )
    )
    t = time.perf_counter()
    await client.text_document_hover_async(
        types.HoverParams(
            text_document=types.TextDocumentIdentifier(uri=seed),
            position=types.Position(line=21, character=1),
        )
    )
    print(f"open seed o4009 + hover (includes its analysis): {ms(time.perf_counter() - t)}")
    print(f"server RSS at the end: {rss_kib(server.pid)}")
    await client.shutdown_async(None)
    client.exit(None)
    await client.stop()


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--blocks", type=int, default=20_000)
    parser.add_argument(
        "--read-whole", action="store_true", help="raise maxBlocks and maxFileSize to the document"
    )
    parser.add_argument(
        "--distinct-code",
        action="store_true",
        help="no two blocks of the program alike (its passes numbered in the code too)",
    )
    parser.add_argument("--debounce", type=int, default=250, help="analysis.debounceMs")
    parser.add_argument("--keystrokes", type=int, default=10)
    parser.add_argument("--hovers", type=int, default=50)
    parser.add_argument("--cancel-blocks", type=int, default=200_000)
    parser.add_argument("--cancel-after", type=float, default=1.0, help="seconds into the analysis")
    parser.add_argument("--only-cancel", action="store_true", help="only the cancellation case")
    parser.add_argument("--no-cancel", action="store_true", help="not the cancellation case")
    parser.add_argument(
        "--server-pythonpath",
        default=str(ROOT / "server"),
        help="the package the servers run (another checkout, to compare)",
    )
    args = parser.parse_args()
    if not args.only_cancel:
        asyncio.run(
            main(
                args.blocks,
                args.debounce,
                args.keystrokes,
                args.hovers,
                args.read_whole,
                args.server_pythonpath,
                args.distinct_code,
            )
        )
    if not args.no_cancel:
        asyncio.run(
            cancellation(
                args.server_pythonpath, args.cancel_blocks, args.debounce, args.cancel_after
            )
        )
