"""``fanuc-macro definition`` run as a user runs it, in a subprocess: where a common variable
is set, across programs and files."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from cli_runner import run

ROOT = Path(__file__).resolve().parents[1]
SEED = ROOT / "tests" / "fixtures" / "seeds" / "o4009_external_m50x3.nc"


def definitions(cwd: Path, *args: str) -> list[tuple[str, int, int]]:
    """(path, line, column) of each place ``definition`` gives, 1-based."""
    result = run(cwd, "definition", "--format", "json", *args)
    found: list[dict[str, Any]] = json.loads(result.stdout)
    return [(Path(f["path"]).name, f["line"], f["column"]) for f in found]


def test_a_common_variable_of_a_subprogram_is_set_by_its_caller(tmp_path: Path) -> None:
    # O3331 line 30: G01 X[#100+1.] ...; O4009 sets #100=50. on line 6, before M98 P0013331.
    assert definitions(tmp_path, str(SEED), "30", "9") == [(SEED.name, 6, 1)]
    # #101 in O3331's first block: set on line 7 of O4009.
    assert definitions(tmp_path, str(SEED), "19", "8") == [(SEED.name, 7, 1)]


def test_the_caller_in_another_file(tmp_path: Path) -> None:
    lines = SEED.read_text("utf-8").splitlines(keepends=True)
    (tmp_path / "main.nc").write_text("".join(lines[:17]), "utf-8")  # % and O4009
    (tmp_path / "sub.nc").write_text("".join(lines[17:]), "utf-8")  # O3331 and %
    # O3331's G01 X[#100+1.] is line 13 of sub.nc.
    assert definitions(tmp_path, "sub.nc", "13", "9", "--with", "main.nc") == [("main.nc", 6, 1)]


def test_a_loop_brings_back_the_assignment_below(tmp_path: Path) -> None:
    (tmp_path / "loop.nc").write_text(
        "O1000\n#100=0\nWHILE[#100LT5]DO1\nG01 X#100 F0.1\n#100=#100+1\nEND1\nM30\n", "utf-8"
    )
    both = [("loop.nc", 2, 1), ("loop.nc", 5, 1)]
    assert definitions(tmp_path, "loop.nc", "4", "8") == both  # X#100
    assert definitions(tmp_path, "loop.nc", "3", "8") == both  # WHILE[#100LT5]
    assert definitions(tmp_path, "loop.nc", "5", "7") == both  # #100+1
    assert definitions(tmp_path, "loop.nc", "5", "2") == [("loop.nc", 5, 1)]  # the target


def test_a_program_nothing_calls_reads_what_any_program_sets(tmp_path: Path) -> None:
    (tmp_path / "probe.nc").write_text("O2000\nG00 X#500\nM30\n", "utf-8")
    (tmp_path / "setup.nc").write_text("O2100 (SET THE OFFSET)\n#500=12.\nM30\n", "utf-8")
    assert definitions(tmp_path, "probe.nc", "2", "6", "--with", "setup.nc") == [("setup.nc", 2, 1)]
