"""Measures the toolpath's three consumers on two big programs.

(a) the drum-shaped spiral groove of seed 003 (``build_drum_groove``, 9 layers of 111 cuts:
999 passes of 15 NC blocks, the paper's "about 1.5 万 blocks" had it been written out, run by
its G65 macro's WHILE loops); (b) a 200,000-block posted file: a mill's CAM output, contour
passes of G01 and G02/G03 and a 3D raster of short G01 moves, only the words that change.

For each: ``fanuc-macro plot`` as a subprocess (wall time, peak RSS, the SVG's size and element
count); the Toolpath view's payload, in a process of its own (the run, ``view_data``, its JSON);
the ``fanuc-macro.toolpath`` command over stdio to a real server (after the document's first
diagnostics, the round trip). Three runs each, min and median; with ``--base PATH`` the runs
alternate with another checkout's package. Not a test: figures depend on the machine.

    python bench/bench_plot.py [--runs 3] [--blocks 200000] [--base ../main/server] [--only drum]
    python bench/bench_plot.py --view-json /tmp/posted.json  # for bench/bench_view_lod.mjs
"""

from __future__ import annotations

import argparse
import asyncio
import json
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))

# The limits raised so that the whole file is read and run, whatever the machine's speed.
LIMITS = {"maxBlocks": 1_000_000, "maxFileSize": 50_000_000, "timeLimit": 600}
CLI_LIMITS = ["--max-blocks", "1000000", "--max-file-size", "50000000", "--time-limit", "600"]


def drum_program() -> str:
    """Seed 003's groove cut by tool T1: 9 layers of 0.8 mm, 111 cuts of 0.5 mm a layer."""
    from fanuc_macro.generators.drum_groove_generator import build_drum_groove

    return build_drum_groove(None, 12.0, layers=9, cuts_per_layer=111).text


def posted_program(blocks: int) -> str:
    """A mill's posted file of about ``blocks`` blocks: a pocket's contour passes (G01 sides,
    G02 corners with R) level by level, then a 3D finishing raster of short G01 moves over a
    bump, zig-zag along Y; each block writes only the words that change, as posts do."""
    out = ["%", "O2001 (POSTED - POCKET AND 3D FINISH)", "G21 G17 G40 G49 G80 G90"]
    out += ["T1 M06", "G54 G00 X0. Y0. S8000 M03", "G43 Z25. H01 M08"]
    last: dict[str, str] = {}

    def block(code: str, **words: float) -> None:
        parts = [code] if code else []
        for k, v in words.items():
            text = f"{v:.3f}".rstrip("0")
            if last.get(k) != text or k == "R":
                parts.append(f"{k}{text}")
                last[k] = text
        if len(parts) > (1 if code else 0):
            out.append(" ".join(parts))

    contour_blocks = blocks // 5
    level = 0
    while len(out) < contour_blocks:
        level += 1
        z = -0.5 * level
        block("G00", Z=2.0)
        block("", X=5.0, Y=10.0)
        block("G01", Z=z, F=400.0)
        for k in range(20):  # loops inwards, each a rounded rectangle, G02 corners
            o = 0.6 * k
            r, x0, y0, x1, y1 = 5.0, 5.0 + o, 5.0 + o, 95.0 - o, 65.0 - o
            block("G01", X=x0, Y=y1 - r, F=1200.0)
            block("G02", X=x0 + r, Y=y1, R=r)
            block("G01", X=x1 - r)
            block("G02", X=x1, Y=y1 - r, R=r)
            block("G01", Y=y0 + r)
            block("G02", X=x1 - r, Y=y0, R=r)
            block("G01", X=x0 + r)
            block("G02", X=x0, Y=y0 + r, R=r)
    block("G00", Z=25.0)
    row = 0
    while len(out) < blocks - 4:
        x = 2.0 + 0.25 * (row % 384)
        if row % 384 == 0:
            block("G00", Z=2.0)
        ys = [float(i) for i in range(71)]  # 1 mm steps along Y
        if row % 2:
            ys.reverse()
        for i, y in enumerate(ys):
            bump = 8.0 * math.exp(-(((x - 50.0) / 25.0) ** 2) - ((y - 35.0) / 18.0) ** 2)
            z = -2.0 + bump + 0.01 * row
            block("G01" if i == 0 else "", X=x, Y=y, Z=z, F=2500.0)
            if len(out) >= blocks - 4:
                break
        row += 1
    out += ["G00 Z25. M09", "M05", "G91 G28 Z0.", "M30", "%"]
    return "\n".join(out) + "\n"


CASES: dict[str, tuple[str, Callable[[int], str]]] = {
    "drum": ("0i-TF", lambda blocks: drum_program()),
    "posted": ("0i-MF", posted_program),
}


def run_child(pythonpath: str, argv: list[str], cwd: str) -> tuple[float, float, int, bytes]:
    """Wall time, CPU time (user and system: less moved by other work on the machine), peak
    RSS (KiB, from wait4) and standard output of a Python child process."""
    env = {**os.environ, "PYTHONPATH": pythonpath}
    started = time.perf_counter()
    with (
        tempfile.TemporaryFile() as out,
        subprocess.Popen(
            [sys.executable, *argv], cwd=cwd, env=env, stdout=out, stderr=subprocess.PIPE
        ) as proc,
    ):
        assert proc.stderr is not None
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - started
        err = proc.stderr.read()
        proc.returncode = os.waitstatus_to_exitcode(status)
        if proc.returncode:
            raise RuntimeError(f"{argv}: exit {proc.returncode}: {err.decode()[-2000:]}")
        out.seek(0)
        return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss, out.read()


def plot_figures(pythonpath: str, path: Path, controller: str) -> dict[str, float]:
    svg = path.with_suffix(".svg")
    argv = ["-m", "fanuc_macro.cli", "plot", str(path), "--controller", controller, "-o", str(svg)]
    wall, cpu, rss, _ = run_child(pythonpath, [*argv, *CLI_LIMITS], str(path.parent))
    data = svg.read_bytes()
    return {
        "wall_s": wall,
        "cpu_s": cpu,
        "rss_mb": rss / 1024,
        "svg_mb": len(data) / 1e6,
        "elements": len(re.findall(rb"<[a-z]", data)),
        "linked": data.count(b" data-line="),
    }


def segment_count(data: dict[str, Any]) -> int:
    """The view payload's segments, in its packed form (``count``) or main's lists."""
    if "count" in data:
        return int(data["count"])
    return len(data["segments"]["kind"])


def view_child(path: str, controller: str, dump: str = "") -> None:
    """In the child: the run with the toolpath, ``view_data`` and its JSON, timed apart; the
    JSON written to ``dump`` when one is named (for bench_view_lod.mjs)."""
    from fanuc_macro.config import Config
    from fanuc_macro.ide.plot import run_toolpath
    from fanuc_macro.ide.toolpath_view import view_data
    from fanuc_macro.workspace import Workspace

    config = Config(
        controller=controller,
        max_blocks=LIMITS["maxBlocks"],
        max_file_size=LIMITS["maxFileSize"],
        time_limit=float(LIMITS["timeLimit"]),
    )
    workspace = Workspace(config)
    uri = str(Path(path).resolve())
    workspace.add_bytes(uri, Path(path).read_bytes())
    doc = workspace.document(uri)
    assert doc is not None
    t0 = time.perf_counter()
    toolpath = run_toolpath(uri, doc, workspace.index(uri), workspace.others(uri), config)
    t1 = time.perf_counter()
    data = view_data(toolpath, uri)
    t2 = time.perf_counter()
    text = json.dumps(data, separators=(",", ":"))
    t3 = time.perf_counter()
    if dump:
        Path(dump).write_text(text, encoding="utf-8")
    print(
        json.dumps(
            {
                "run_s": t1 - t0,
                "view_s": t2 - t1,
                "json_s": t3 - t2,
                "json_mb": len(text) / 1e6,
                "moves": len(toolpath.moves),
                "segments": segment_count(data),
            }
        )
    )


def view_figures(pythonpath: str, path: Path, controller: str) -> dict[str, float]:
    argv = [str(Path(__file__).resolve()), "--child-view", str(path), controller]
    _, _, rss, out = run_child(pythonpath, argv, str(path.parent))
    figures: dict[str, float] = json.loads(out)
    figures["rss_mb"] = rss / 1024
    return figures


async def server_figures(pythonpath: str, path: Path, controller: str) -> dict[str, float]:
    """Open the file in a real server, wait for its diagnostics, then time the command."""
    from bench_lsp import Bench, rss_kib
    from lsprotocol import types

    bench = Bench()
    client = bench.client
    env = {**os.environ, "PYTHONPATH": pythonpath}
    await client.start_io(sys.executable, "-m", "fanuc_macro.lsp.server", env=env)
    server = client._server
    assert server is not None
    await client.initialize_async(
        types.InitializeParams(
            capabilities=types.ClientCapabilities(),
            initialization_options={"controller": controller, "analysis": LIMITS},
        )
    )
    client.initialized(types.InitializedParams())
    uri = path.as_uri()
    t0 = time.perf_counter()
    client.text_document_did_open(
        types.DidOpenTextDocumentParams(
            text_document=types.TextDocumentItem(
                uri=uri, language_id="fanuc-macro", version=1, text=path.read_text("utf-8")
            )
        )
    )
    first = await bench.wait_version(uri, 1, 600.0)
    sent = time.perf_counter()
    result = await client.workspace_execute_command_async(
        types.ExecuteCommandParams(command="fanuc-macro.toolpath", arguments=[uri])
    )
    got = time.perf_counter()
    assert isinstance(result, dict) and "segments" in result, str(result)[:300]
    figures = {
        "diagnostics_s": first - t0,
        "command_s": got - sent,
        "segments": segment_count(result),
        "hwm_mb": rss_kib(server.pid).get("VmHWM", 0) / 1024,
    }
    await client.shutdown_async(None)
    client.exit(None)
    await client.stop()
    return figures


def summary(name: str, runs: list[dict[str, float]]) -> str:
    keys = list(runs[0])
    parts = []
    for k in keys:
        values = [r[k] for r in runs]
        lo, mid = min(values), statistics.median(values)
        if all(float(v).is_integer() for v in values) and lo == max(values):
            parts.append(f"{k} {int(lo):,}")
        else:
            parts.append(f"{k} {lo:.3g} / {mid:.3g}")
    return f"  {name}: " + ", ".join(parts)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--blocks", type=int, default=200_000, help="of the posted file")
    parser.add_argument("--only", choices=tuple(CASES), action="append")
    parser.add_argument("--what", choices=("plot", "view", "server"), action="append")
    parser.add_argument("--base", help="another checkout's server/ to alternate runs with")
    parser.add_argument(
        "--view-json", metavar="PATH", help="only write the posted file's view payload there"
    )
    parser.add_argument("--child-view", nargs="+", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child_view:
        view_child(*args.child_view)
        return
    if args.view_json:
        work = Path(tempfile.mkdtemp(prefix="bench-plot-"))
        path = work / "posted.nc"
        path.write_text(posted_program(args.blocks), encoding="utf-8")
        view_child(str(path), "0i-MF", str(Path(args.view_json).resolve()))
        return
    packages = {"this": str(ROOT / "server")}
    if args.base:
        packages["base"] = str(Path(args.base).resolve())
    work = Path(tempfile.mkdtemp(prefix="bench-plot-"))
    print("(figures: min / median of the runs; times in s, sizes in MB)")
    for case in args.only or list(CASES):
        controller, make = CASES[case]
        text = make(args.blocks)
        path = work / f"{case}.nc"
        path.write_text(text, encoding="utf-8")
        print(f"{case}: {len(text.splitlines()):,} lines, {len(text) / 1e6:.2f} MB, {controller}")
        measures: dict[str, Callable[[str], dict[str, float]]] = {
            "plot": lambda p: plot_figures(p, path, controller),  # noqa: B023
            "view": lambda p: view_figures(p, path, controller),  # noqa: B023
            "server": lambda p: asyncio.run(server_figures(p, path, controller)),  # noqa: B023
        }
        for what in args.what or list(measures):
            results: dict[str, list[dict[str, float]]] = {name: [] for name in packages}
            for _ in range(args.runs):
                for name, pythonpath in packages.items():  # alternated
                    results[name].append(measures[what](pythonpath))
            for name, runs in results.items():
                print(summary(f"{what} ({name})", runs))


if __name__ == "__main__":
    main()
