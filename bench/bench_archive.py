"""``fanuc-macro check`` of a shop's archive: the shared corpus copied into many job folders
(each copy keeps its O numbers, as an archive keeps the same O number in many folders), checked
in one process and in one per core; wall time and the peak memory of all the processes
together (their resident sets, polled every 20 ms; Linux).

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
    """The resident set of ``pid`` and its descendants, in KiB."""
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
        try:
            with open(f"/proc/{p}/status") as status:
                for line in status:
                    if line.startswith("VmRSS:"):
                        total += int(line.split()[1])
        except OSError:
            continue
    return total


def run_check(server: Path, archive: Path, jobs: int) -> tuple[float, float]:
    """(seconds, peak MiB) of one check of the archive."""
    env = {**os.environ, "PYTHONPATH": str(server)}
    command = [sys.executable, "-m", "fanuc_macro.cli", "check", "-q", "--format", "json"]
    if jobs:
        command += ["--jobs", str(jobs)]
    start = time.perf_counter()
    process = subprocess.Popen(
        [*command, str(archive)], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
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
    with tempfile.TemporaryDirectory() as tmp:
        archive = Path(tmp) / "archive"
        count = build_archive(archive, args.copies)
        print(f"{count} files in {args.copies} job folders, {os.cpu_count()} cores")
        for name, server in servers:
            # --jobs 1 is the one-process check; "other" may not know --jobs: 0 = leave it out
            for jobs in (1, os.cpu_count() or 1):
                if name == "other" and jobs != 1:
                    continue
                seconds, mib = run_check(server, archive, 0 if name == "other" else jobs)
                print(f"{name:5s} jobs {jobs}: {seconds:7.1f} s, peak {mib:7.0f} MiB")


if __name__ == "__main__":
    main()
