"""``fanuc-macro check`` of a shop's archive: the shared corpus copied into many job folders
(each copy keeps its O numbers, as an archive keeps the same O number in many folders), checked
in one process, in one per core, and with the findings kept between runs (a first run and a
second with nothing changed); wall time and the peak memory of all the processes together
(their proportional sets, which count a page the processes share once; polled every 20 ms;
Linux).

    PYTHONPATH=server python3 bench/bench_archive.py [--copies 20] [--other ROOT]

``--other`` checks the same archive with another checkout's server too (its ``server/``), the
runs alternated, so that two versions are compared on one machine in one run. Quote the
figures with the machine they ran on (docs/benchmarks.md).
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT.parent / "shared" / "corpus"


def build_archive(target: Path, copies: int) -> int:
    files = sorted(p for p in CORPUS.iterdir() if p.is_file() and p.name != "MANIFEST.tsv")
    for k in range(copies):
        folder = target / f"job{k:04d}"
        folder.mkdir(parents=True)
        for f in files:
            shutil.copyfile(f, folder / f.name)
    return copies * len(files)


def _tree_rss(pid: int) -> int:
    """The memory of ``pid`` and its descendants, in KiB (:func:`_pss`)."""
    total = 0
    children: dict[int, list[int]] = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as stat:
                parent = int(stat.read().rsplit(")", 1)[1].split()[1])
        except OSError:
            continue
        children.setdefault(parent, []).append(int(entry))
    todo = [pid]
    while todo:
        p = todo.pop()
        todo.extend(children.get(p, []))
        total += _pss(p)
    return total


def _pss(pid: int) -> int:
    """A process's proportional set (KiB): the pages it shares with the processes forked from
    it counted once among them, not once in each; its resident set where the kernel does not
    say."""
    for name, field in ((f"/proc/{pid}/smaps_rollup", "Pss:"), (f"/proc/{pid}/status", "VmRSS:")):
        try:
            with open(name) as status:
                for line in status:
                    if line.startswith(field):
                        return int(line.split()[1])
        except OSError:
            continue
    return 0


def run_check(
    server: Path, archive: Path, options: list[str], cache: Path | None = None
) -> tuple[float, float]:
    """(seconds, peak MiB) of one check of the archive; ``cache``: the folder of the findings
    kept between runs (None: no cache)."""
    env = {**os.environ, "PYTHONPATH": str(server)}
    env["FANUC_MACRO_CHECK_CACHE"] = str(cache) if cache is not None else "0"
    command = [sys.executable, "-m", "fanuc_macro.cli", "check", "-q", "--format", "json"]
    start = time.perf_counter()
    process = subprocess.Popen(
        [*command, *options, str(archive)],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    peak = 0
    while process.poll() is None:
        peak = max(peak, _tree_rss(process.pid))
        time.sleep(0.02)
    return time.perf_counter() - start, peak / 1024.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--copies", type=int, default=20)
    parser.add_argument("--other", type=Path, help="another checkout to compare with")
    args = parser.parse_args()
    servers = [("this", ROOT / "server")]
    if args.other is not None:
        servers.append(("other", args.other.resolve() / "server"))
    cores = os.cpu_count() or 1
    with tempfile.TemporaryDirectory() as tmp:
        archive = Path(tmp) / "archive"
        count = build_archive(archive, args.copies)
        print(f"{count} files in {args.copies} job folders, {cores} cores")
        runs: list[tuple[str, Path, list[str], Path | None]] = [
            ("one process", ROOT / "server", ["--jobs", "1"], None),
            (f"{cores} processes", ROOT / "server", ["--jobs", str(cores)], None),
            (f"{cores} processes, cache empty", ROOT / "server", [], Path(tmp) / "cache"),
            (f"{cores} processes, cache kept", ROOT / "server", [], Path(tmp) / "cache"),
        ]
        if args.other is not None:  # before --jobs and the cache: one process
            runs.insert(1, ("other checkout", args.other.resolve() / "server", [], None))
        for name, server, options, cache in runs:
            seconds, mib = run_check(server, archive, options, cache)
            print(f"{name:30s} {seconds:7.1f} s, peak {mib:6.0f} MiB (all processes)")


if __name__ == "__main__":
    main()
