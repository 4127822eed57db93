"""``check --fix``, ``--unsafe-fixes`` and ``--diff`` through the command line in a
subprocess: the fixes written in the file's own encoding and line ends, the file checked as
fixed, nothing written by --diff, a file whose bytes would not read back left alone."""

from __future__ import annotations

import json
from pathlib import Path

from cli_runner import run

# MB003 (a comment nested in a comment) and MB004 (a comment not closed): safe fixes; MB404
# (an argument without its decimal point) and MB201 (a DO without END): unsafe ones.
FAULTY = "O1000 (刀具 (T0101) 外圆)\r\nG00 X1. (OPEN\r\nG65 P9810 A10\r\nM30\r\n"
LOOP = "O2000\nWHILE[#1LT3]DO1\n#1=#1+1\nM30\n"


def test_fix_applies_the_safe_fixes_in_the_file_s_encoding_and_checks_it_as_fixed(
    tmp_path: Path,
) -> None:
    (tmp_path / "a.nc").write_bytes(FAULTY.encode("gb18030"))
    (tmp_path / "b.nc").write_text(LOOP, encoding="utf-8")
    result = run(tmp_path, "check", "--fix", "--format", "json", "a.nc", "b.nc")
    fixed = (tmp_path / "a.nc").read_bytes()
    assert fixed == (
        "O1000 (刀具 T0101 外圆)\r\nG00 X1. (OPEN)\r\nG65 P9810 A10\r\nM30\r\n".encode("gb18030")
    )
    assert (tmp_path / "b.nc").read_text("utf-8") == LOOP  # its fix is not safe
    found = {(f["path"], f["code"]) for f in json.loads(result.stdout)}
    assert ("a.nc", "MB003") not in found and ("a.nc", "MB004") not in found
    assert {("a.nc", "MB404"), ("b.nc", "MB201")} <= found
    assert "2 fixes applied in 1 file" in result.stderr


def test_unsafe_fixes_apply_the_others_and_a_second_fix_finds_nothing(tmp_path: Path) -> None:
    (tmp_path / "b.nc").write_text(LOOP, encoding="utf-8")
    result = run(tmp_path, "check", "--fix", "--unsafe-fixes", "--format", "json", "b.nc")
    assert (tmp_path / "b.nc").read_text("utf-8") == "O2000\nWHILE[#1LT3]DO1\n#1=#1+1\nEND1\nM30\n"
    assert "MB201" not in {f["code"] for f in json.loads(result.stdout)}
    again = run(tmp_path, "check", "--fix", "--unsafe-fixes", "b.nc")
    assert "0 fixes applied in 0 files" in again.stderr


def test_diff_shows_the_changes_and_writes_nothing(tmp_path: Path) -> None:
    (tmp_path / "a.nc").write_bytes(FAULTY.encode("gb18030"))
    result = run(tmp_path, "check", "--diff", "a.nc")
    assert result.returncode == 1
    assert "\n-G00 X1. (OPEN\n" in result.stdout and "\n+G00 X1. (OPEN)\n" in result.stdout
    assert (tmp_path / "a.nc").read_bytes() == FAULTY.encode("gb18030")
    clean = tmp_path / "c.nc"
    clean.write_text("O3000\nG00 X1.\nM30\n", encoding="utf-8")
    assert run(tmp_path, "check", "--diff", "c.nc").returncode == 0


def test_a_file_whose_bytes_would_not_read_back_is_not_rewritten(tmp_path: Path) -> None:
    # A UTF-8 line beside a GB18030 one: read line by line, written back it would differ.
    data = "O1000 (外圆\n".encode() + "G00 X1. (刀具)\nM30\n".encode("gb18030")
    (tmp_path / "m.nc").write_bytes(data)
    result = run(tmp_path, "check", "--fix", "m.nc")
    assert (tmp_path / "m.nc").read_bytes() == data
    assert "m.nc: not fixed: its bytes do not read back the same" in result.stderr


def test_fix_of_standard_input_is_a_usage_error(tmp_path: Path) -> None:
    result = run(tmp_path, "check", "--fix", "-")
    assert result.returncode == 2 and "not standard input" in result.stderr
