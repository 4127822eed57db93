"""A shop's archive: many files, the same O number in many job folders, checked in several
processes. The calls between files are followed through one program graph per state of the
workspace (not by reading every file for each), and ``check --jobs N`` prints what one
process prints."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from fanuc_macro import cli
from fanuc_macro.cli import check_command
from fanuc_macro.config import Config
from fanuc_macro.workspace import Workspace, program_graph, related_documents

ROOT = Path(__file__).resolve().parent.parent
RULE_FIXTURES = ROOT / "tests" / "fixtures" / "rules"

SUB = "%\nO1000 (SUB)\n#1=#1+1\nM99\n%\n"
MAIN = "%\nO{n}\nM98 P1000\nM30\n%\n"


def _archive(copies: int, mains: int) -> Workspace:
    workspace = Workspace(Config())
    for k in range(copies):
        workspace.add_text(f"job{k:03d}/O1000.nc", SUB)
    for k in range(mains):
        workspace.add_text(f"main{k}/O{2000 + k}.nc", MAIN.format(n=2000 + k))
    return workspace


def test_copies_of_one_number() -> None:
    workspace = _archive(copies=50, mains=3)
    indexes = workspace.indexes()
    # A copy is run by the mains that call its number, and a main runs the first copy.
    assert related_documents("job007/O1000.nc", indexes) == [
        f"main{k}/O{2000 + k}.nc" for k in range(3)
    ]
    assert related_documents("main1/O2001.nc", indexes) == ["job000/O1000.nc"]
    assert workspace.others("main1/O2001.nc")[0][0] == "job000/O1000.nc"


def test_the_graph_is_built_once_per_state_of_the_workspace() -> None:
    workspace = _archive(copies=5, mains=1)
    graph = workspace.graph()
    assert workspace.graph() is graph
    assert graph.definers[1000] == [f"job{k:03d}/O1000.nc" for k in range(5)]
    workspace.add_text("main9/O2009.nc", MAIN.format(n=2009))
    again = workspace.graph()
    assert again is not graph
    assert "main9/O2009.nc" in again.callers[1000]
    assert again.definers == program_graph(workspace.indexes()).definers


def test_a_computed_call_needs_every_document() -> None:
    workspace = _archive(copies=2, mains=0)
    workspace.add_text("dyn.nc", "%\nO3000\n#1=1000\nM98 P#1\nM30\n%\n")
    assert related_documents("dyn.nc", workspace.indexes()) is None


def _check(jobs: int) -> subprocess.CompletedProcess[bytes]:
    env = {**os.environ, "PYTHONPATH": str(ROOT / "server")}
    command = [sys.executable, "-m", "fanuc_macro.cli", "check", "--format", "json"]
    return subprocess.run(
        [*command, "--jobs", str(jobs), str(RULE_FIXTURES)],
        capture_output=True,
        env=env,
        check=False,
        timeout=600,
    )


def test_check_in_processes_prints_what_one_process_prints() -> None:
    one, two = _check(1), _check(2)
    assert one.returncode == two.returncode == 1
    assert one.stdout == two.stdout
    assert one.stderr == two.stderr
    assert len(one.stdout) > 100_000  # the rule fixtures' findings, each file's in order


def test_files_dropped_between_files_leave_each_check_as_it_was(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A process of a parallel check keeps few files read, the ones each file needs loaded
    again: with room for 3, the findings are those of one workspace holding every file."""
    for k in range(3):  # the same O numbers in three job folders, the calls between them
        folder = tmp_path / f"job{k}"
        folder.mkdir()
        for fixture in sorted(RULE_FIXTURES.glob("MB4*.nc")):
            (folder / fixture.name).write_bytes(fixture.read_bytes())
        # O1000 sets the divisor of the main programs: 0 in the first folder, which the
        # archive's order makes the one called (a division by zero), 2 in the others.
        (folder / "O1000.nc").write_text(f"%\nO1000 (SUB)\n#100={2 * k}\nM99\n%\n")
        main = f"%\nO{3000 + k}\nM98 P1000\n#1=1/#100\nG00 X#1\nM30\n%\n"
        (folder / f"O{3000 + k}.nc").write_text(main)
    whole = cli.main(["check", "--format", "json", "--no-cache", "--jobs", "1", str(tmp_path)])
    held = capsys.readouterr()
    monkeypatch.setattr(check_command, "FILES_KEPT", 3)
    monkeypatch.setenv("FANUC_MACRO_CHECK_CACHE", str(tmp_path / "cache"))
    few = cli.main(["check", "--format", "json", "--jobs", "1", str(tmp_path)])
    dropped = capsys.readouterr()
    assert whole == few == 1
    assert held.out == dropped.out and held.err == dropped.err
    assert held.out.count('"code"') > 50
    assert held.out.count("O3000.nc") == held.out.count("O3001.nc") > 0  # O1000 was read
