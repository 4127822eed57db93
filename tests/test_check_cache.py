"""``check`` keeps each file's findings between runs: a second run with nothing changed reads
them back, and a file whose text, settings or related files changed is analysed again. The
output is always what a run without the cache prints."""

from __future__ import annotations

import os
import sqlite3
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

SUB = "%\nO2000 (SUB)\n#100=#1*{k}\nM99\n%\n"
MAIN = "%\nO1000 (MAIN)\nG65 P2000 A2.\nIF [#100 GT 3.] GOTO 99\nG00 X#100\nN99 M30\n%\n"


def _folder(tmp_path: Path) -> Path:
    jobs = tmp_path / "jobs"
    for n in range(12):
        (jobs / f"part{n:02d}").mkdir(parents=True)
        (jobs / f"part{n:02d}" / f"O{3000 + n}.nc").write_text(
            f"%\nO{3000 + n}\nG90 G00 X{n}. Y0\n#1=#2+1\nM30\n%\n"
        )
    (jobs / "main.nc").write_text(MAIN)
    (jobs / "sub.nc").write_text(SUB.format(k=1))
    return jobs


def _check(folder: Path, cache: Path | str, *options: str) -> subprocess.CompletedProcess[str]:
    env = {
        **os.environ,
        "PYTHONPATH": str(ROOT / "server"),
        "FANUC_MACRO_CHECK_CACHE": str(cache),
    }
    return subprocess.run(
        [
            sys.executable,
            "-m",
            "fanuc_macro.cli",
            "check",
            "--format",
            "json",
            *options,
            str(folder),
        ],
        capture_output=True,
        text=True,
        env=env,
        check=False,
        timeout=300,
    )


def _rows(cache: Path) -> int:
    with sqlite3.connect(cache / "check-results.sqlite3") as db:
        return int(db.execute("SELECT COUNT(*) FROM results").fetchone()[0])


def test_a_second_run_reads_the_findings_back(tmp_path: Path) -> None:
    jobs, cache = _folder(tmp_path), tmp_path / "cache"
    first = _check(jobs, cache)
    assert _rows(cache) == 14
    second = _check(jobs, cache)
    fresh = _check(jobs, cache, "--no-cache")
    assert first.stdout == second.stdout == fresh.stdout
    assert first.stderr == second.stderr == fresh.stderr
    assert first.returncode == second.returncode == fresh.returncode


def test_a_change_in_a_called_file_reaches_its_caller(tmp_path: Path) -> None:
    jobs, cache = _folder(tmp_path), tmp_path / "cache"
    before = _check(jobs, cache)
    # The subprogram now makes #100 = 4: the caller's GOTO 99 always jumps, its G00 is dead.
    (jobs / "sub.nc").write_text(SUB.format(k=2))
    after = _check(jobs, cache)
    fresh = _check(jobs, cache, "--no-cache")
    assert after.stdout == fresh.stdout
    assert after.stdout != before.stdout
    assert _rows(cache) == 16  # the caller's and the called file's findings again


def test_other_settings_are_another_run(tmp_path: Path) -> None:
    jobs, cache = _folder(tmp_path), tmp_path / "cache"
    _check(jobs, cache)
    disabled = _check(jobs, cache, "--disable", "MB901")
    assert disabled.stdout == _check(jobs, cache, "--disable", "MB901", "--no-cache").stdout
    assert _rows(cache) == 28


def test_the_cache_off_or_broken(tmp_path: Path) -> None:
    jobs, cache = _folder(tmp_path), tmp_path / "cache"
    off = _check(jobs, "0")
    assert not cache.exists()
    cache.mkdir()
    (cache / "check-results.sqlite3").write_bytes(b"not a database" * 100)
    broken = _check(jobs, cache)
    assert broken.stdout == off.stdout and broken.returncode == off.returncode
