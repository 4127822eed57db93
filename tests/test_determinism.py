"""The same files and settings give byte-identical diagnostics on any machine and under any
load: the evaluator's budgets count executed blocks, never seconds (docs/rules.md, "How the
evaluator runs a program"). Each check runs in a process of its own, with another hash seed,
so that an order taken from a set of strings would show too."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FIXTURES = ROOT / "tests" / "fixtures"
CORPUS = ROOT.parent / "shared" / "corpus"
NOT_PROGRAMS = {"README.md", "MANIFEST.tsv"}


def program_files() -> list[Path]:
    files = sorted(p for p in FIXTURES.rglob("*") if p.is_file())
    if CORPUS.is_dir():  # the real programs, when the shared corpus is beside the repository
        files += sorted(p for p in CORPUS.iterdir() if p.is_file() and p.name not in NOT_PROGRAMS)
    return files


def check_output(files: list[Path], hash_seed: str) -> bytes:
    env = {
        **os.environ,
        "PYTHONPATH": os.pathsep.join(
            filter(None, [str(ROOT / "server"), os.environ.get("PYTHONPATH")])
        ),
        "PYTHONHASHSEED": hash_seed,
    }
    check = [sys.executable, "-m", "fanuc_macro.cli", "check", "--quiet", "--format", "json"]
    done = subprocess.run(
        [*check, *map(str, files)],
        capture_output=True,
        env=env,
        timeout=120,
        check=False,
    )
    assert done.returncode in (0, 1), done.stderr.decode(errors="replace")
    assert not done.stderr, done.stderr.decode(errors="replace")  # no safety-net stop either
    return done.stdout


def test_same_output_when_the_machine_is_busy() -> None:
    files = program_files()
    quiet = check_output(files, "1")
    # Every core busy with other work, as on a loaded build machine or a laptop compiling.
    busy = [
        subprocess.Popen([sys.executable, "-c", "while True: pass"])
        for _ in range(max(2, os.cpu_count() or 2))
    ]
    try:
        loaded = check_output(files, "2")
    finally:
        for process in busy:
            process.kill()
            process.wait()
    codes = {d["code"] for d in json.loads(quiet)}
    # The verdicts that need a run to its budget's end are among what is compared.
    assert {"MB703", "MB707", "MB708"} <= codes
    assert loaded == quiet
