"""The command line, run as a user runs it: ``python -m fanuc_macro.cli check ...`` in a
subprocess, in a temporary folder."""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys
from pathlib import Path

import pytest

from cli_runner import run

ROOT = Path(__file__).resolve().parents[1]
SEEDS = ROOT / "tests" / "fixtures" / "seeds"

TEXT_LINE = re.compile(
    r"^(?P<path>.+):(?P<line>\d+):(?P<column>\d+): (?P<code>MB\d{3}) "
    r"(?P<severity>error|warning|information|hint) (?P<message>\S.*)$"
)
JSON_KEYS = {"path", "line", "column", "end_line", "end_column", "severity", "code", "message"}

# One error: a jump to a label that is not there (MB101 error).
ERROR_PROGRAM = "%\nO1000 (MAIN)\nG00 X100. Z100.\nIF[#1GT0]GOTO99\nM30\n%\n"
ERROR_LINE = 4
ERROR_COLUMN = "IF[#1GT0]GOTO99".index("99") + 1
# Only a warning: a call of a program that is in no file given (MB403 warning).
WARNING_PROGRAM = "%\nO1000 (MAIN)\nM98 P2000\nM30\n%\n"
CLEAN_PROGRAM = "%\nO1000 (MAIN)\nG00 X100. Z100.\nM30\n%\n"


def parsed_lines(stdout: str) -> list[dict[str, str]]:
    out: list[dict[str, str]] = []
    for text in stdout.splitlines():
        m = TEXT_LINE.match(text)
        assert m is not None, f"not 'path:line:col: CODE severity message': {text!r}"
        out.append(m.groupdict())
    return out


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


# ---- output formats and exit codes -------------------------------------------------------------


def test_text_format_and_exit_1_on_an_error(tmp_path: Path) -> None:
    write(tmp_path / "prog.nc", ERROR_PROGRAM)
    result = run(tmp_path, "check", "prog.nc")
    assert result.returncode == 1, result.stderr
    rows = parsed_lines(result.stdout)
    mb101 = [r for r in rows if r["code"] == "MB101"]
    assert len(mb101) == 1
    assert mb101[0]["path"] == "prog.nc"
    assert (int(mb101[0]["line"]), int(mb101[0]["column"])) == (ERROR_LINE, ERROR_COLUMN)
    assert mb101[0]["severity"] == "error"
    assert "99" in mb101[0]["message"]


def test_json_format(tmp_path: Path) -> None:
    write(tmp_path / "prog.nc", ERROR_PROGRAM)
    result = run(tmp_path, "check", "--format", "json", "prog.nc")
    assert result.returncode == 1, result.stderr
    records = json.loads(result.stdout)
    assert isinstance(records, list) and records
    for record in records:
        assert set(record) == JSON_KEYS
        assert record["path"] == "prog.nc"
        assert record["severity"] in ("error", "warning", "information", "hint")
        assert re.fullmatch(r"MB\d{3}", record["code"])
        assert record["line"] >= 1 and record["column"] >= 1
        assert (record["end_line"], record["end_column"]) >= (record["line"], record["column"])
    (mb101,) = [r for r in records if r["code"] == "MB101"]
    assert (mb101["line"], mb101["column"]) == (ERROR_LINE, ERROR_COLUMN)
    assert (mb101["end_line"], mb101["end_column"]) == (ERROR_LINE, ERROR_COLUMN + 2)
    assert mb101["severity"] == "error"


def test_text_and_json_report_the_same(tmp_path: Path) -> None:
    write(tmp_path / "prog.nc", ERROR_PROGRAM + "O2000\nM98 P3000\nWHILE[#1LT3]DO4\nM99\n")
    text_rows = parsed_lines(run(tmp_path, "check", "prog.nc").stdout)
    records = json.loads(run(tmp_path, "check", "--format", "json", "prog.nc").stdout)
    assert [
        (r["line"], r["column"], r["code"], r["severity"], r["message"]) for r in text_rows
    ] == [
        (str(r["line"]), str(r["column"]), r["code"], r["severity"], r["message"]) for r in records
    ]


def test_exit_0_on_warnings_only(tmp_path: Path) -> None:
    write(tmp_path / "prog.nc", WARNING_PROGRAM)
    result = run(tmp_path, "check", "prog.nc")
    assert result.returncode == 0, result.stdout + result.stderr
    rows = parsed_lines(result.stdout)
    assert {r["code"] for r in rows} >= {"MB403"}
    assert not [r for r in rows if r["severity"] == "error"]


def test_exit_0_when_clean(tmp_path: Path) -> None:
    write(tmp_path / "prog.nc", CLEAN_PROGRAM)
    result = run(tmp_path, "check", "prog.nc")
    assert (result.returncode, result.stdout) == (0, ""), result.stderr
    result = run(tmp_path, "check", "--format", "json", "prog.nc")
    assert result.returncode == 0
    assert json.loads(result.stdout) == []


def test_exit_2_naming_a_missing_file(tmp_path: Path) -> None:
    write(tmp_path / "prog.nc", ERROR_PROGRAM)
    result = run(tmp_path, "check", "prog.nc", "missing.nc")
    assert result.returncode == 2
    assert {r["path"] for r in parsed_lines(result.stdout)} == {"prog.nc"}  # checked all the same
    message, summary = result.stderr.splitlines()
    assert message == "fanuc-macro: no such file or directory: missing.nc"
    assert summary.startswith("fanuc-macro: 1 file checked, ")


def test_exit_2_on_a_missing_folder(tmp_path: Path) -> None:
    result = run(tmp_path, "check", "no_such_folder")
    assert (result.returncode, result.stdout) == (2, "")
    assert result.stderr.splitlines() == [
        "fanuc-macro: no such file or directory: no_such_folder",
        "fanuc-macro: 0 files checked, 0 skipped, 0 errors, 0 warnings",
    ]


# ---- folders and file kinds ----------------------------------------------------------------------


def test_folders_are_recursed_with_the_extension_rules(tmp_path: Path) -> None:
    progs = tmp_path / "progs"
    checked = [
        "a.nc",
        "b.NC",
        "c.mac",
        "d.tap",
        "e.cnc",
        "f.eia",
        "g.txt",
        "deep/er/h.nc",
        "O1234",  # no extension, starts with O<number>
        "tape",  # no extension, starts with %
        "spaced",  # no extension, blank line then %
        "post.mc12",  # a post-processor's extension, taken for its content
    ]
    skipped = ["notes.md", "data.csv", "readme", "script.py", "Oname"]
    for name in checked + skipped:
        text = ERROR_PROGRAM
        if name == "O1234":
            text = ERROR_PROGRAM.removeprefix("%\n")
        elif name == "spaced":
            text = "\n" + ERROR_PROGRAM
        elif name == "readme":
            text = "READ ME\n" + ERROR_PROGRAM
        elif name == "Oname":
            text = "ONE PROGRAM\n" + ERROR_PROGRAM
        write(progs / name, text)
    result = run(tmp_path, "check", "progs")
    assert result.returncode == 1
    paths = {Path(r["path"]).relative_to("progs").as_posix() for r in parsed_lines(result.stdout)}
    assert paths == set(checked)


def test_a_file_named_on_the_command_line_is_checked_whatever_its_extension(
    tmp_path: Path,
) -> None:
    write(tmp_path / "post.mc12", ERROR_PROGRAM)
    result = run(tmp_path, "check", "post.mc12")
    assert result.returncode == 1
    assert {r["path"] for r in parsed_lines(result.stdout)} == {"post.mc12"}


def test_a_file_in_a_shops_encoding_is_read_without_a_note(tmp_path: Path) -> None:
    chinese = "O1000 (外螺纹 主程序)\nG00 X100. Z100. (退刀)\nM30\n"
    (tmp_path / "gb.nc").write_bytes(chinese.encode("gb18030"))
    (tmp_path / "sjis.nc").write_bytes("O2000 (ねじ切り)\nM30\n".encode("shift_jis"))
    western = "O3000 (Fräser Ø20, Fase 45°)\nG00 X100. (Planfläche)\nM30\n"
    (tmp_path / "w.nc").write_bytes(western.encode("cp1252"))
    for name in ("gb.nc", "sjis.nc", "w.nc"):
        result = run(tmp_path, "check", "--format", "json", name)
        assert (result.returncode, json.loads(result.stdout)) == (0, []), result.stderr
    # The comments are read as written: hover shows the Western program's comment.
    hover = run(tmp_path, "hover", "w.nc", "1", "2")
    assert "Fräser Ø20, Fase 45°" in hover.stdout, hover.stdout + hover.stderr


def test_a_file_of_two_encodings_is_reported_with_its_lines(tmp_path: Path) -> None:
    head = "O1000 (外螺纹 主程序)\n".encode("gb18030")
    pasted = "(螺纹 精车)\n".encode()  # a line copied from a UTF-8 file
    tail = "G00 X100. Z100. (退刀)\nM30\n".encode("gb18030")
    (tmp_path / "mixed.nc").write_bytes(head + pasted + tail)
    result = run(tmp_path, "check", "--format", "json", "mixed.nc")
    assert result.returncode == 0, result.stdout + result.stderr
    [record] = json.loads(result.stdout)
    assert (record["code"], record["line"], record["severity"]) == ("MB007", 1, "information")
    assert record["message"].startswith(
        "file mixes encodings: line 2 in UTF-8, 2 lines (the first: line 1) in GB18030"
    )


def test_exit_2_when_no_programs_are_found(tmp_path: Path) -> None:
    (tmp_path / "empty").mkdir()
    write(tmp_path / "notes" / "readme.md", ERROR_PROGRAM)  # not a program file's extension
    write(tmp_path / "notes" / "todo.txt", "Order inserts.\nCall the service about X.\n")
    for folder, skipped in (
        ("empty", "0 skipped"),
        ("notes", f"1 skipped (not programs: {Path('notes') / 'todo.txt'})"),
    ):
        for form, shown in (("text", ""), ("json", "[]\n")):
            result = run(tmp_path, "check", "--format", form, folder)
            assert (result.returncode, result.stdout) == (2, shown), result.stderr
            assert result.stderr == (
                f"fanuc-macro: no programs found in {folder}\n"
                f"fanuc-macro: 0 files checked, {skipped}, 0 errors, 0 warnings\n"
            )


def test_a_folder_without_programs_beside_programs_is_told_and_the_rest_checked(
    tmp_path: Path,
) -> None:
    (tmp_path / "empty").mkdir()
    write(tmp_path / "progs" / "prog.nc", ERROR_PROGRAM)
    result = run(tmp_path, "check", "empty", "progs")
    assert result.returncode == 2  # a usage problem, told once the rest is checked
    assert result.stderr.splitlines()[0] == "fanuc-macro: no programs found in empty"
    assert "MB101" in {r["code"] for r in parsed_lines(result.stdout)}


# The start of an ELF executable (NUL bytes from the fifth), then text that would be 1,000
# diagnostics if it were read as a program.
BINARY = b"\x7fELF\x02\x01\x01\x00" + b"\x00" * 8 + b"IF[#1GT0]GOTO99\n" * 1000


def test_a_binary_file_is_reported_once(tmp_path: Path) -> None:
    (tmp_path / "progs").mkdir()
    (tmp_path / "progs" / "a.out.nc").write_bytes(BINARY)
    write(tmp_path / "progs" / "prog.nc", WARNING_PROGRAM)
    result = run(tmp_path, "check", "progs")
    assert result.returncode == 0, result.stdout + result.stderr
    rows = [r for r in parsed_lines(result.stdout) if r["path"].endswith("a.out.nc")]
    assert [(r["line"], r["column"], r["code"], r["severity"]) for r in rows] == [
        ("1", "1", "MB007", "information")
    ]
    assert rows[0]["message"] == (
        "not a program text: it holds NUL bytes (the first at byte 8): a binary file, or text "
        "saved as UTF-16; the file is not analysed"
    )
    as_json = json.loads(run(tmp_path, "check", "--format", "json", "progs/a.out.nc").stdout)
    assert [(r["code"], r["line"], r["message"]) for r in as_json] == [
        ("MB007", 1, rows[0]["message"])
    ]
    # Control codes without a NUL (compressed data, say) are not text either.
    noisy = bytes(b for b in range(256) if b) * 4
    (tmp_path / "noise.nc").write_bytes(noisy)
    [row] = parsed_lines(run(tmp_path, "check", "noise.nc").stdout)
    assert row["code"] == "MB007" and "are control codes: a binary file" in row["message"]


def test_a_punched_tapes_leader_and_trailer_of_nuls_are_blank(tmp_path: Path) -> None:
    """NUL bytes (blank tape, feed holes only) before the first '%' and after the last are a
    tape's leader and trailer, which the control does not read: neither a syntax error nor a
    sign of a binary file, also when the leader is punched over several lines."""
    program = CLEAN_PROGRAM.encode()
    leaders = {
        "one.nc": b"\0" * 40 + program + b"\0" * 40,
        "lines.nc": b"\0" * 20 + b"\r\n" + b"\0" * 20 + b"\r\n" + program + b"\0" * 8,
        "same-line.nc": b"\0" * 20 + program,  # the leader runs into the '%'
    }
    for name, data in leaders.items():
        (tmp_path / name).write_bytes(data)
        result = run(tmp_path, "check", "--format", "json", name)
        assert (result.returncode, json.loads(result.stdout)) == (0, []), (name, result.stdout)
        formatted = run(tmp_path, "format", "--check", name)
        assert formatted.returncode == 0, (name, formatted.stdout + formatted.stderr)
    # A NUL among the program's blocks is still not text.
    (tmp_path / "inside.nc").write_bytes(program[:10] + b"\0" + program[10:])
    [row] = parsed_lines(run(tmp_path, "check", "inside.nc").stdout)
    assert row["code"] == "MB007" and "it holds NUL bytes (the first at byte 11)" in row["message"]


def test_a_utf16_file_is_named_as_such(tmp_path: Path) -> None:
    (tmp_path / "u16.nc").write_bytes(ERROR_PROGRAM.encode("utf-16"))  # with its byte order mark
    result = run(tmp_path, "check", "u16.nc")
    [row] = parsed_lines(result.stdout)
    assert row["code"] == "MB007"
    assert "it is UTF-16 text (save it as UTF-8 or ASCII)" in row["message"]


# A blank before a comment: the ASCII space and tab/form feed the grammar skips, the
# Unicode spaces it rejects (MB001). A line's verdict is its own, whatever line of the same
# code but another blank was read before it.
BLANKS = {"nbsp": "\u00a0", "em": "\u2003", "ideographic": "\u3000", "tab": "\t", "ff": "\f"}


def test_a_blank_before_a_comment_gives_the_same_verdict_alone_and_after_its_twin(
    tmp_path: Path,
) -> None:
    def program(number: int, blank: str) -> str:
        return f"%\nO{number}\n#3000=91{blank}(D INPUT MISSING)\nM30\n%\n"

    def verdicts(*names: str) -> dict[str, list[tuple[int, int, str]]]:
        result = run(tmp_path, "check", "--format", "json", *names)
        out: dict[str, list[tuple[int, int, str]]] = {name: [] for name in names}
        for r in json.loads(result.stdout):
            out[r["path"]].append((r["line"], r["column"], r["code"]))
        return out

    write(tmp_path / "space.nc", program(1000, " "))
    for i, (name, blank) in enumerate(BLANKS.items(), 1):
        write(tmp_path / f"{name}.nc", program(1000 + i, blank))
    together = verdicts("space.nc", *(f"{name}.nc" for name in BLANKS))
    assert together["space.nc"] == [(3, 1, "MB503")]
    for name, blank in BLANKS.items():
        alone = verdicts(f"{name}.nc")[f"{name}.nc"]
        assert together[f"{name}.nc"] == alone, name
        assert alone == ([(3, 1, "MB503")] if blank in "\t\f" else [(3, 9, "MB001")]), name


# ---- --disable ---------------------------------------------------------------------------------


def test_disable(tmp_path: Path) -> None:
    write(tmp_path / "prog.nc", ERROR_PROGRAM)
    result = run(tmp_path, "check", "--disable", "MB101", "prog.nc")
    assert result.returncode == 0, result.stdout
    assert "MB101" not in {r["code"] for r in parsed_lines(result.stdout)}


def test_disable_several_codes_in_any_case(tmp_path: Path) -> None:
    write(tmp_path / "prog.nc", ERROR_PROGRAM + "O2000\nM98 P3000\nM99\n")
    before = {r["code"] for r in parsed_lines(run(tmp_path, "check", "prog.nc").stdout)}
    assert {"MB101", "MB403"} <= before
    result = run(tmp_path, "check", "--disable", "mb101, MB403", "prog.nc")
    after = {r["code"] for r in parsed_lines(result.stdout)}
    assert not after & {"MB101", "MB403"}
    assert after == before - {"MB101", "MB403"}


def test_an_unknown_code_to_disable_is_a_usage_error_naming_the_nearest(tmp_path: Path) -> None:
    write(tmp_path / "prog.nc", ERROR_PROGRAM)
    cases = {  # a typed O for 0, a misspelt name, a known code beside two unknown ones
        "MB1O1": "unknown rule code 'MB1O1': the nearest known one is MB101 goto-missing-label",
        "lowercse": "unknown rule code 'LOWERCSE': the nearest known one is MB006 lowercase",
        "mb101,MB9O4,NO-SUCH-VAR": "unknown rule codes 'MB9O4' (nearest: MB904 "
        "arguments-assumed), 'NO-SUCH-VAR' (nearest: MB302 no-such-variable)",
    }
    for given, told in cases.items():
        result = run(tmp_path, "check", "--disable", given, "prog.nc")
        assert (result.returncode, result.stdout) == (2, ""), result.stdout
        assert result.stderr.startswith("usage: fanuc-macro check")
        last = result.stderr.splitlines()[-1]
        assert last == f"fanuc-macro check: error: argument --ignore/--disable: {told}"
    for command in (["trace", "prog.nc"], ["hover", "prog.nc", "1", "1"]):
        result = run(tmp_path, *command, "--disable", "NOPE")
        assert result.returncode == 2 and "unknown rule code 'NOPE'" in result.stderr


# ---- the machine's limits and options ------------------------------------------------------------

FAST = "%\nO6002 (SURFACE SPEED)\n#19=FIX[1000.*300./[3.1416*20.]]\nS#19 M03\nM30\n%\n"


def test_spindle_speed_is_checked_only_against_a_limit_given(tmp_path: Path) -> None:
    write(tmp_path / "prog.nc", FAST)
    quiet = parsed_lines(run(tmp_path, "check", "prog.nc").stdout)
    assert "MB602" not in {r["code"] for r in quiet}
    result = run(tmp_path, "check", "--max-spindle-speed", "4000", "prog.nc")
    [row] = [r for r in parsed_lines(result.stdout) if r["code"] == "MB602"]
    assert "S gets 4774. rpm, above the machine's maximum 4000. rpm" in row["message"]
    assert int(row["line"]) == 4
    assert run(tmp_path, "check", "--max-spindle-speed", "5000", "prog.nc").stdout == ""


def test_threading_feed_is_checked_only_against_a_limit_given(tmp_path: Path) -> None:
    thread = "%\nO1007\nG97 S3500 M03\nG00 X66. Z12.\nG92 X63.4 Z-40. F6.\nM30\n%\n"
    write(tmp_path / "prog.nc", thread)
    assert "MB807" not in run(tmp_path, "check", "prog.nc").stdout
    result = run(tmp_path, "check", "--max-threading-feed", "10000", "prog.nc")
    assert "MB807" in {r["code"] for r in parsed_lines(result.stdout)}


def test_extended_commons_option(tmp_path: Path) -> None:
    write(tmp_path / "prog.nc", "%\nO9040\n#200=#5061\n#201=#5062\nM99\n%\n")
    [row] = [r for r in parsed_lines(run(tmp_path, "check", "prog.nc").stdout)]
    assert (row["code"], row["line"]) == ("MB303", "3")
    assert "first of 2 uses" in row["message"]
    assert run(tmp_path, "check", "--extended-commons", "prog.nc").stdout == ""


def test_a_limit_must_be_a_positive_number(tmp_path: Path) -> None:
    write(tmp_path / "prog.nc", FAST)
    for bad in ("0", "-5", "fast", "inf"):
        result = run(tmp_path, "check", "--max-spindle-speed", bad, "prog.nc")
        assert result.returncode == 2 and "positive number" in result.stderr, bad


# ---- calls between files -------------------------------------------------------------------------

MAIN = "%\nO1000 (MAIN)\nM98 P2000\nG65 P7123 X10. Z-20. D12.\nM30\n%\n"
SUB = "%\nO2000 (SUB)\nG00 X100.\nM99\n%\n"
MACRO = "%\nO7123 (BORE)\nG00 X#24 Z#26\nM99\n%\n"


def test_calls_unresolved_with_the_caller_alone(tmp_path: Path) -> None:
    write(tmp_path / "main.nc", MAIN)
    rows = parsed_lines(run(tmp_path, "check", "main.nc").stdout)
    assert sorted(int(r["line"]) for r in rows if r["code"] == "MB403") == [3, 4]


def test_calls_resolved_through_a_folder(tmp_path: Path) -> None:
    write(tmp_path / "job" / "main.nc", MAIN)
    write(tmp_path / "job" / "subs" / "o2000.nc", SUB)
    write(tmp_path / "job" / "subs" / "O7123", MACRO)  # no extension, starts with %
    result = run(tmp_path, "check", "job")
    assert result.returncode == 0, result.stdout
    assert "MB403" not in {r["code"] for r in parsed_lines(result.stdout)}


def test_calls_resolved_through_files_given_together(tmp_path: Path) -> None:
    write(tmp_path / "main.nc", MAIN)
    write(tmp_path / "lib" / "o2000.nc", SUB)
    write(tmp_path / "lib" / "o7123.nc", MACRO)
    result = run(tmp_path, "check", "main.nc", "lib")
    assert result.returncode == 0, result.stdout
    assert "MB403" not in {r["code"] for r in parsed_lines(result.stdout)}
    partial = parsed_lines(run(tmp_path, "check", "main.nc", "lib/o2000.nc").stdout)
    assert [int(r["line"]) for r in partial if r["code"] == "MB403"] == [4]


def test_files_without_o_line_are_known_by_their_names(tmp_path: Path) -> None:
    write(tmp_path / "main.nc", "%\nO1000 (MAIN)\nM98 P8501\nG65 P9010 A1.\nM98 P8502\nM30\n%\n")
    write(tmp_path / "O8501.NC", "%\n(ROUGHING)\nG00 X100.\nM99\n%\n")
    write(tmp_path / "O09010", "G00 X#1 Z2.\nM99\n")  # a memory card's name, no extension
    write(tmp_path / "O8502 FINISH.nc", "G00 X50.\nZ2.\n")  # no M99 either
    rows = parsed_lines(run(tmp_path, "check", ".").stdout)
    assert not [r for r in rows if r["code"] in ("MB403", "MB410", "MB901")]
    hints = {(Path(r["path"]).name, r["line"]): r for r in rows if r["code"] == "MB010"}
    assert set(hints) == {("O8501.NC", "3"), ("O09010", "1"), ("O8502 FINISH.nc", "1")}
    assert all(r["severity"] == "hint" for r in hints.values())
    assert hints[("O8501.NC", "3")]["message"].startswith(
        "program number 8501 taken from the file name 'O8501.NC'"
    )
    # A program named by its file is checked as one: O8502 runs off its end.
    [unended] = [r for r in rows if r["code"] == "MB407"]
    assert (Path(unended["path"]).name, unended["line"]) == ("O8502 FINISH.nc", "2")
    assert "called with M98 from O1000" not in unended["message"]  # another file calls it
    # Given together on the command line, the files know each other too; alone, they do not.
    together = run(tmp_path, "check", "main.nc", "O8501.NC", "O09010", "O8502 FINISH.nc")
    assert "MB403" not in together.stdout and "MB410" not in together.stdout
    alone = parsed_lines(run(tmp_path, "check", "main.nc").stdout)
    # O8000-O9999 are the control's resident programs' ranges: hints, not warnings (MB410)
    assert {r["message"].split(",")[0] for r in alone if r["code"] == "MB410"} == {
        "M98 calls O8501",
        "G65 calls O9010",
        "M98 calls O8502",
    }


def test_names_that_are_not_program_numbers_number_nothing(tmp_path: Path) -> None:
    write(tmp_path / "main.nc", "%\nO1000 (MAIN)\nM98 P4\nM30\n%\n")
    write(tmp_path / "04_variables.nc", "G00 X1.\nM99\n")
    rows = parsed_lines(run(tmp_path, "check", ".").stdout)
    assert [r["code"] for r in rows if r["path"].endswith("main.nc")] == ["MB403"]
    [note] = [r for r in rows if r["path"].endswith("04_variables.nc")]
    assert (note["code"], note["severity"]) == ("MB010", "information")


# ---- the seed programs ----------------------------------------------------------------------

# o2_arc_thread_roughing.nc copies the paper's typo 'M#1' for 'M#13' (spindle direction) in
# its O3 and O4: #1 is 93.82, so 'M#1' is no M code. The checker is right to say so (MB601);
# no other error is allowed.
SEED_TYPOS = {
    ("o2_arc_thread_roughing.nc", 30, "MB601"),
    ("o2_arc_thread_roughing.nc", 64, "MB601"),
}


@pytest.mark.parametrize("fmt", ["text", "json"])
def test_seed_programs_check_without_error(tmp_path: Path, fmt: str) -> None:
    result = run(tmp_path, "check", "--format", fmt, str(SEEDS))
    assert result.returncode in (0, 1), result.stderr
    if fmt == "json":
        records = json.loads(result.stdout)
    else:
        records = [dict(r, line=int(r["line"])) for r in parsed_lines(result.stdout)]
    errors = {
        (Path(str(r["path"])).name, int(r["line"]), str(r["code"]))
        for r in records
        if r["severity"] == "error"
    }
    assert errors <= SEED_TYPOS, sorted(errors - SEED_TYPOS)
    checked = {Path(str(r["path"])).name for r in records}
    assert checked <= {p.name for p in SEEDS.glob("*.nc")}
    for name, line, _ in errors:
        assert "M#1 " in (SEEDS / name).read_text("utf-8").splitlines()[line - 1]


# ---- fanuc-macro trace -----------------------------------------------------------------------


def test_trace_json_gives_every_executed_cut(tmp_path: Path) -> None:
    done = run(tmp_path, "trace", str(SEEDS / "o4009_external_m50x3.nc"), "--format", "json")
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)
    motions = result["motions"]
    assert set(motions[0]) == {"program", "line", "code", "words", "start", "end", "clock"}
    cuts = [m for m in motions if m["code"] == "G92"]
    assert len(cuts) == 186  # 2 x 88 rough passes + 2 finishing + 8 spring passes
    assert set(cuts[0].pop("values")) == {"#100", "#9", "#2", "#102", "#1", "#101"}
    assert cuts[0] == {
        "program": "O3331",
        "line": 32,
        "code": "G92",
        "words": {"X": 49.816, "W": -60.0, "R": 0.0, "F": 3.0},
        "speed": 400.0,  # G97 S400: the spindle speed in force
        # The cycle time when it begins (tests/test_cycle_time.py): T0101's 2 s, G01 X51.
        # W7. at F0.5 x S400 (sqrt(53) mm at 200 mm/min), G01 W-1.036 at 200 mm/min.
        "clock": 4.495,
        "start": {"X": 51.0, "Z": 5.964},
        "end": {"X": 51.0, "Z": 5.964},
        "moves": [
            {"kind": "rapid", "start": {"X": 51.0, "Z": 5.964}, "end": {"X": 49.816, "Z": 5.964}},
            {
                "kind": "thread",
                "start": {"X": 49.816, "Z": 5.964},
                "end": {"X": 49.816, "Z": -54.036},
            },
            {
                "kind": "rapid",
                "start": {"X": 49.816, "Z": -54.036},
                "end": {"X": 51.0, "Z": -54.036},
            },
            {"kind": "rapid", "start": {"X": 51.0, "Z": -54.036}, "end": {"X": 51.0, "Z": 5.964}},
        ],
    }
    lost = result["toolpath"]["lost"]
    assert lost[0]["line"] == 4 and lost[0]["axes"] == ["X", "Z"]
    # The modal repeat "X[#100-2.*#4]" is a G92 record of its own, with the modal F.
    assert any(m["line"] == 43 and set(m["words"]) == {"X", "F"} for m in cuts)
    assert result["summary"]["by_code"]["G92"] == 186
    assert result["summary"]["stopped"] is None


def test_trace_json_gives_the_values_each_block_read(tmp_path: Path) -> None:
    """Each motion's ``values``: what the variables its block reads held at that execution,
    worked out here from the seed's own formulas (O3331, lines 19-27, and O3, lines 9-29)."""
    done = run(tmp_path, "trace", str(SEEDS / "o4009_external_m50x3.nc"), "--format", "json")
    assert done.returncode == 0, done.stderr
    motions = json.loads(done.stdout)["motions"]
    assert "values" not in motions[0]  # G00 X55. Z0. reads no variable
    pitch, length, es, td2 = 3.0, 50.0, 0.048, 0.170
    nose = pitch / (8 * math.sin(math.radians(60)))
    height = 7 / 8 * math.sin(math.radians(60)) * pitch - nose + es / 2 + td2 / 4
    first_depth = 0.2 / 3 * math.sqrt(height)  # #9 = #5 * SQRT[#7], #7 = 1 on the first pass
    lead_in = 2 * pitch + pitch + math.floor(length / pitch) * pitch - length
    cuts = [m for m in motions if m["code"] == "G92"]
    # G92 X[#100-2.*#9] W[-#2-#102-#1] R0 F#101: the variables in the order the block names them.
    assert list(cuts[0]["values"]) == ["#100", "#9", "#2", "#102", "#1", "#101"]
    assert cuts[0]["values"]["#9"] == pytest.approx(first_depth, abs=1e-9)
    assert cuts[0]["values"]["#2"] == pytest.approx(lead_in)
    assert cuts[0]["values"]["#100"] == 50.0 and cuts[0]["values"]["#101"] == pitch
    assert cuts[0]["words"]["X"] == round(50.0 - 2 * first_depth, 3)
    # The second pass read the #9 of the loop's second round: the values are per execution.
    assert cuts[2]["values"]["#9"] == pytest.approx(first_depth * math.sqrt(2), abs=1e-9)

    arc = run(tmp_path, "trace", str(SEEDS / "o2_arc_thread_roughing.nc"), "--format", "json")
    assert arc.returncode == 0, arc.stderr
    rapids = [m for m in json.loads(arc.stdout)["motions"] if m["line"] == 33]
    # N25 G00 Z[#6 + [#4 - #18] * COS[#16]], #16 the angle of the pass (N16-N21, N29).
    asin = [math.degrees(math.asin(x)) for x in ((108 - 93.82) / 2 / 10, 1.2 / (10 - 1.2))]
    step = (180 - 2 * asin[0] + asin[1]) / 7
    angles = [r["values"]["#16"] for r in rapids]
    assert angles[:2] == pytest.approx([asin[0] - asin[1] + step, asin[0] - asin[1] + 2 * step])
    assert rapids[0]["values"] == {"#6": 50.0, "#4": 10.0, "#18": 1.2, "#16": angles[0]}


def test_trace_text_and_entry(tmp_path: Path) -> None:
    seed = SEEDS / "o5_arc_thread_finishing.nc"
    done = run(tmp_path, "trace", str(seed))
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert sum(1 for ln in lines if ln.startswith("O") and " G32 " in ln) == 19
    assert lines[-2].startswith("78 motions (G00 59, G32 19)")
    assert lines[-1].startswith("cycle time ")
    first_cut = next(ln for ln in lines if " G32 " in ln)
    assert "[X94.561 Z58.369 -> X94.561 Z-113.]" in first_cut
    sub = run(tmp_path, "trace", str(SEEDS / "o4009_external_m50x3.nc"), "--entry", "O3331")
    assert sub.returncode == 0, sub.stderr
    assert "O4009" not in sub.stdout  # only the sub-program, with unknown #100-#104
    missing = run(tmp_path, "trace", "no-such-file.nc")
    assert missing.returncode == 2 and "no-such-file.nc" in missing.stderr
    bad_entry = run(tmp_path, "trace", str(seed), "--entry", "O9999")
    assert bad_entry.returncode == 2 and "O9999" in bad_entry.stderr


def test_check_reports_evaluator_findings_with_values(tmp_path: Path) -> None:
    program = write(
        tmp_path / "asin.nc",
        "%\nO3 (ARC)\n#1=93.82\n#4=10\n#5=125\n#10=ASIN[[[#5-#1]/2]/#4]\nM30\n%\n",
    )
    done = run(tmp_path, "check", str(program), "--format", "json")
    assert done.returncode == 1
    found = [d for d in json.loads(done.stdout) if d["code"] == "MB501"]
    assert found and found[0]["line"] == 6 and "1.559" in found[0]["message"]


VARIANTS = ROOT / "tests" / "fixtures" / "thread_variants"


def test_threading_verdicts_through_the_command_line(tmp_path: Path) -> None:
    names = ["o3331_height_typo.nc", "g92_fix_step.nc", "o4009_clean.nc"]
    result = run(tmp_path, "check", "--format", "json", *(str(VARIANTS / n) for n in names))
    assert result.returncode == 1, result.stderr
    found = {(Path(d["path"]).name, d["line"], d["code"]) for d in json.loads(result.stdout)}
    assert found == {
        ("o3331_height_typo.nc", 22, "MB808"),
        ("o3331_height_typo.nc", 42, "MB801"),
        ("g92_fix_step.nc", 9, "MB814"),
        ("g92_fix_step.nc", 11, "MB817"),
    }


def test_trace_lists_every_pass_of_a_g76(tmp_path: Path) -> None:
    result = run(tmp_path, "trace", "--format", "json", str(VARIANTS / "g76_clean.nc"))
    assert result.returncode == 0, result.stderr
    motions = json.loads(result.stdout)["motions"]
    passes = [m for m in motions if m["code"] == "G76"]
    assert len(passes) == 11 and all(m["line"] == 7 for m in passes)
    assert [m["words"]["X"] for m in passes][:3] == [29.2, 28.869, 28.614]


def test_trace_plot_hover_and_definition_of_a_folder(tmp_path: Path) -> None:
    write(tmp_path / "progs" / "prog.nc", CLEAN_PROGRAM)
    for command in (["trace"], ["plot"], ["hover"], ["definition"]):
        place = ["1", "1"] if command[0] in ("hover", "definition") else []
        result = run(tmp_path, *command, "progs", *place)
        assert (result.returncode, result.stdout) == (2, ""), result.stderr
        assert result.stderr == (
            f"fanuc-macro: {command[0]} takes one program file; progs is a folder\n"
        )
    assert not list(tmp_path.glob("*.svg"))


def test_trace_of_a_binary_file_stops_with_the_reason(tmp_path: Path) -> None:
    (tmp_path / "a.out").write_bytes(BINARY)
    for command in (["trace", "a.out"], ["plot", "a.out"], ["hover", "a.out", "1", "1"]):
        result = run(tmp_path, *command)
        assert (result.returncode, result.stdout) == (2, ""), result.stderr
        assert result.stderr.startswith("fanuc-macro: a.out: not a program text: it holds NUL")


# ---- the analyser's own failures: one line for the user, the traceback on request -------------


def _broken_rule(ctx: object) -> list[object]:
    raise RuntimeError("rule bug")


@pytest.fixture
def broken_rule(monkeypatch: pytest.MonkeyPatch) -> None:
    import fanuc_macro.analysis

    monkeypatch.setattr(
        fanuc_macro.analysis, "ALL_CHECKS", (*fanuc_macro.analysis.ALL_CHECKS, _broken_rule)
    )


def test_internal_error_names_the_rule_without_a_traceback(
    tmp_path: Path, broken_rule: None, capsys: pytest.CaptureFixture[str]
) -> None:
    from fanuc_macro.cli import main

    path = write(tmp_path / "p.nc", CLEAN_PROGRAM)
    assert main(["check", str(path)]) == 3
    out, err = capsys.readouterr()
    internal = [d for d in parsed_lines(out) if d["code"] == "MB000"]
    assert len(internal) == 1
    message = internal[0]["message"]
    assert "test_cli._broken_rule" in message and "RuntimeError('rule bug')" in message
    assert "please report it" in message and "--verbose" in message
    assert "Traceback" not in err and "Traceback" not in out


def test_verbose_and_log_file_give_the_traceback(
    tmp_path: Path, broken_rule: None, capsys: pytest.CaptureFixture[str]
) -> None:
    from fanuc_macro.cli import main

    path = write(tmp_path / "p.nc", CLEAN_PROGRAM)
    assert main(["check", "--verbose", str(path)]) == 3
    assert "Traceback" in capsys.readouterr().err
    log = tmp_path / "analysis.log"
    assert main(["check", "--log-file", str(log), str(path)]) == 3
    assert "Traceback" not in capsys.readouterr().err
    assert "RuntimeError: rule bug" in log.read_text("utf-8")
    assert main(["check", str(path)]) == 3  # the handlers of the runs before are gone
    assert "Traceback" not in capsys.readouterr().err


def test_a_failing_rule_prints_no_traceback_in_a_process_of_its_own(tmp_path: Path) -> None:
    """Outside pytest (whose log capture takes every record), a process without --verbose
    or --log-file imports logging only when a rule fails: its traceback must not reach the
    terminal through logging's last resort."""
    path = write(tmp_path / "p.nc", CLEAN_PROGRAM)
    script = (
        "import sys\n"
        "import fanuc_macro.analysis as analysis\n"
        "from fanuc_macro.cli import main\n"
        "def broken(ctx):\n"
        "    raise RuntimeError('rule bug')\n"
        "analysis.ALL_CHECKS = (*analysis.ALL_CHECKS, broken)\n"
        "assert 'logging' not in sys.modules\n"
        "status = main(['check', sys.argv[1]])\n"
        "assert 'logging' in sys.modules\n"  # the failure was logged
        "sys.exit(status)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script, str(path)], capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 3, done.stderr  # the analyser's failure: an internal error
    assert "MB000" in done.stdout and "rule bug" in done.stdout
    assert "Traceback" not in done.stderr and "failed" not in done.stderr, done.stderr


def test_trace_failing_inside_answers_json_and_exit_3(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    import fanuc_macro.cli

    def broken(*args: object, **kwargs: object) -> dict[str, object]:
        raise RuntimeError("evaluator bug")

    monkeypatch.setattr(fanuc_macro.cli, "trace", broken)
    path = write(tmp_path / "p.nc", CLEAN_PROGRAM)
    assert fanuc_macro.cli.main(["trace", "--format", "json", str(path)]) == 3
    out, err = capsys.readouterr()
    assert "evaluator bug" in json.loads(out)["error"]
    assert "Traceback" not in err and "please report it" in err


def test_the_read_limits_and_the_budget_are_options(tmp_path: Path) -> None:
    rows = "".join(f"G01 X{i}. Z-{i % 7}. F0.2\n" for i in range(40))
    write(tmp_path / "cam.nc", f"%\nO1234 (CAM)\n{rows}M30\n%\n")
    plain = run(tmp_path, "check", "--format", "json", "cam.nc")
    assert plain.returncode == 0, plain.stderr
    assert not [r for r in json.loads(plain.stdout) if r["code"] == "MB013"]
    cut = run(tmp_path, "check", "--format", "json", "--max-blocks", "20", "cam.nc")
    assert cut.returncode == 0, cut.stderr
    codes = [r["code"] for r in json.loads(cut.stdout)]
    assert codes == ["MB013"]  # and nothing the unread part may settle (its M30)
    (record,) = json.loads(cut.stdout)
    assert record["line"] == 21 and "--max-blocks" in record["message"]
    sized = run(tmp_path, "check", "--format", "json", "--max-file-size", "200", "cam.nc")
    assert [r["code"] for r in json.loads(sized.stdout)] == ["MB013"]
    endless = write(tmp_path / "loop.nc", "%\nO1\n#1=0\nWHILE[#1LT10]DO1\n#2=#2+1\nEND1\nM30\n%\n")
    looped = run(tmp_path, "check", "--format", "json", "--step-budget", "500", endless.name)
    (mb703,) = [r for r in json.loads(looped.stdout) if r["code"] == "MB703"]
    assert "(500 blocks)" in mb703["message"]
    refused = run(tmp_path, "check", "--max-blocks", "0", "cam.nc")
    assert refused.returncode == 2 and "not a positive whole number" in refused.stderr


def test_a_cam_file_without_f_gets_one_feed_warning(tmp_path: Path) -> None:
    rows = "".join(f"G01 X{i}. Y{i % 5}. Z-1.\n" for i in range(50))
    write(tmp_path / "cam.nc", f"%\nO1234 (CAM)\nG00 X0 Y0\n{rows}M30\n%\n")
    result = run(tmp_path, "check", "--format", "json", "cam.nc")
    (warning,) = [r for r in json.loads(result.stdout) if r["code"] == "MB603"]
    assert warning["line"] == 4
    assert (
        "49 more cuts run without F after it (lines 5, 6, 7, 8, 9, 10, 11, 12, ...)"
        in (warning["message"])
    )


# ---- hover and definition: the editor's answers on the command line ---------------------------

CALLER = (
    "%\nO1000 (MAIN)\n#1=2.5 (直径)\nG01 (进给) X#1 F0.2\nM98 P2000\nIF[#1GT0]GOTO20\nN20 M30\n%\n"
)
CALLED = "%\nO2000 (SUB)\nG00 X0\nM99\n%\n"


def test_hover_prints_the_editors_hover_text(tmp_path: Path) -> None:
    from fanuc_macro.analysis import analyse
    from fanuc_macro.config import Config
    from fanuc_macro.ide.hover import hover
    from fanuc_macro.ide.view import View

    write(tmp_path / "main.nc", CALLER)
    column = CALLER.splitlines()[3].index("#1") + 1  # in characters, after the Chinese comment
    result = run(tmp_path, "hover", "main.nc", "4", str(column))
    assert result.returncode == 0, result.stderr
    config = Config()
    expected = hover(View("main.nc", analyse(CALLER, "main.nc", config), config), 3, column - 1)
    assert expected is not None
    assert result.stdout == expected.markdown + "\n"
    assert "**#1**" in result.stdout and "**#1** here: **2.5**" in result.stdout
    shown = run(tmp_path, "hover", "main.nc", "4", str(column), "--format", "json")
    assert shown.returncode == 0, shown.stderr
    record = json.loads(shown.stdout)
    assert record["markdown"] == expected.markdown
    assert (record["path"], record["line"], record["column"]) == ("main.nc", 4, column)
    assert record["end_column"] == column + 2


def test_hover_of_nothing_exits_1(tmp_path: Path) -> None:
    write(tmp_path / "main.nc", CALLER)
    empty = run(tmp_path, "hover", "main.nc", "1", "1")  # the "%"
    assert empty.returncode == 1 and empty.stdout == ""
    assert "nothing there: main.nc:1:1" in empty.stderr
    as_json = run(tmp_path, "hover", "main.nc", "1", "1", "--format", "json")
    assert as_json.returncode == 1 and json.loads(as_json.stdout) is None
    missing = run(tmp_path, "hover", "nope.nc", "1", "1")
    assert missing.returncode == 2 and "no such file" in missing.stderr
    zero = run(tmp_path, "hover", "main.nc", "0", "1")
    assert zero.returncode == 2 and "not a positive whole number" in zero.stderr


def test_definition_prints_path_line_column(tmp_path: Path) -> None:
    write(tmp_path / "main.nc", CALLER)
    write(tmp_path / "lib" / "sub.nc", CALLED)
    call = CALLER.splitlines()[4].index("P2000") + 2
    found = run(tmp_path, "definition", "main.nc", "5", str(call), "--with", "lib")
    assert found.returncode == 0, found.stderr
    assert found.stdout == f"{Path('lib') / 'sub.nc'}:2:1\n"
    alone = run(tmp_path, "definition", "main.nc", "5", str(call))  # O2000 is in no file given
    assert alone.returncode == 1 and alone.stdout == ""
    jump = CALLER.splitlines()[5].index("GOTO") + 1
    label = run(tmp_path, "definition", "main.nc", "6", str(jump), "--format", "json")
    assert label.returncode == 0, label.stderr
    assert json.loads(label.stdout) == [
        {"path": "main.nc", "line": 7, "column": 1, "end_line": 7, "end_column": 4}
    ]
    variable = CALLER.splitlines()[3].index("#1") + 1
    assigned = run(tmp_path, "definition", "main.nc", "4", str(variable))
    assert assigned.stdout == "main.nc:3:1\n"


# ---- help ----------------------------------------------------------------------------------------


def test_every_option_and_argument_of_every_command_has_a_help_text(tmp_path: Path) -> None:
    import argparse

    from fanuc_macro.cli import build_parser

    parser = build_parser()
    [commands] = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    assert set(commands.choices) == {
        "check", "trace", "plot", "hover", "definition", "thread", "arc-thread", "drum-groove",
        "format", "config", "rule"
    }  # fmt: skip
    for name, command in commands.choices.items():
        for action in command._actions:
            shown = "/".join(action.option_strings) or action.metavar or action.dest
            assert action.help and action.help != argparse.SUPPRESS, f"{name} {shown}"
        result = run(tmp_path, name, "--help")
        assert result.returncode == 0, result.stderr
        for action in command._actions:
            for option in action.option_strings:
                assert option in result.stdout, f"{name} --help does not show {option}"
