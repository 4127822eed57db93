"""The command line as ruff and ESLint users expect it, run as a user runs it (a subprocess in
a temporary folder): which files a folder walk takes, the summary line, output a stream cannot
encode, the exit status, and the options ``--with``, ``--disable``, ``--controller``,
``--exclude``, ``-`` with ``--stdin-filename``, and ``format`` of several files."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SEEDS = ROOT / "tests" / "fixtures" / "seeds"
CHINESE_SEED = SEEDS / "o2_arc_thread_roughing.nc"  # its messages quote Chinese comments

# One error: a jump to a label that is not there (MB101).
ERROR_PROGRAM = "%\nO1000 (MAIN)\nG00 X100. Z100.\nIF[#1GT0]GOTO99\nM30\n%\n"
# Only a warning: a call of a program that is in no file given (MB403).
WARNING_PROGRAM = "%\nO1000 (MAIN)\nM98 P2000\nM30\n%\n"
CLEAN_PROGRAM = "%\nO1000 (MAIN)\nG00 X100. Z100.\nM30\n%\n"
CALLED = "%\nO2000 (SUB)\nG00 X0\nM99\n%\n"
NOTES = "Call Bob about the fixture on Monday.\nOrder more inserts (CNMG 120408).\n"
SUMMARY = re.compile(
    r"^fanuc-macro: (?P<checked>\d+) files? checked, (?P<skipped>\d+) skipped"
    r"(?: \(not programs: (?P<names>.*)\))?, (?P<errors>\d+) errors?, (?P<warnings>\d+) "
    r"warnings?(?:, \d+ information)?(?:, \d+ hints?)?$"
)


def run(
    cwd: Path, *args: str, stdin: bytes | None = None, encoding: str = "utf-8"
) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT / "server")
    env["PYTHONIOENCODING"] = encoding
    done = subprocess.run(
        [sys.executable, "-m", "fanuc_macro.cli", *args],
        cwd=cwd,
        env=env,
        input=stdin if stdin is not None else b"",
        capture_output=True,
        timeout=120,
    )
    # What a terminal of that encoding shows (format writes the file's own bytes).
    return subprocess.CompletedProcess(
        done.args,
        done.returncode,
        done.stdout.decode(encoding, errors="replace"),
        done.stderr.decode(encoding, errors="replace"),
    )


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


def reported(stdout: str) -> set[str]:
    """The paths the text output has findings for, with / between folders."""
    return {Path(line.split(":", 1)[0]).as_posix() for line in stdout.splitlines()}


def summary(stderr: str) -> dict[str, str]:
    last = stderr.splitlines()[-1]
    match = SUMMARY.match(last)
    assert match is not None, f"not the summary line: {last!r}"
    return {k: v or "" for k, v in match.groupdict().items()}


# ---- which files a folder walk takes ---------------------------------------------------------


def test_programs_are_found_by_the_extensions_of_controls_and_posts_in_any_case(
    tmp_path: Path,
) -> None:
    names = [
        "a.nc", "b.NC", "c.ngc", "d.ncd", "e.SPF", "f.mpf", "g.MIN", "h.tap", "i.cnc",
        "j.eia", "k.mac", "deep/er/l.Nc",
    ]  # fmt: skip
    for name in names:
        write(tmp_path / "progs" / name, ERROR_PROGRAM)
    result = run(tmp_path, "check", "progs")
    assert result.returncode == 1, result.stderr
    assert reported(result.stdout) == {f"progs/{name}" for name in names}
    assert summary(result.stderr)["checked"] == str(len(names))


# Files whose extension other files share (.txt, .prg, .iso, ...) or that have none: taken for
# what they hold.
PROGRAM_TEXTS = {
    "tape.txt": ERROR_PROGRAM,
    "ALL-PROG.TXT": "O1000\n" + ERROR_PROGRAM.split("\n", 2)[2],
    "iso_number.prg": ":1000\nIF[#1GT0]GOTO99\nM30\n",
    "named.iso": "O<MAIN>\nIF[#1GT0]GOTO99\nM30\n",
    "blocks_only.txt": "G00 X100. Z100.\nIF[#1GT0]GOTO99\nM30\n",
    "commented.sub": "(OP 10)\n\n(ROUGH)\nN10 G00 X1.\n#1=2\nIF[#1GT0]GOTO99\nM30\n",
    "lower case.txt": "g00 x100. z100.\nif[#1gt0]goto99\nm30\n",
    "O1234": "IF[#1GT0]GOTO99\nM30\n",  # no extension, named as a program number
    "no_extension": "%\nIF[#1GT0]GOTO99\nM30\n%\n",
    "utf8_bom.txt": "\ufeff%\nO1000\nIF[#1GT0]GOTO99\nM30\n%\n",
    "post.mc12": "\nN160G0G17G40G49G80G90M9\nT160M6\nIF[#1GT0]GOTO99\nM30\n",
}
NOT_PROGRAM_TEXTS = {
    "notes.txt": NOTES,
    "LICENSE.txt": "MIT License\n\nCopyright (c) 2024 Someone\n\nPermission is hereby granted",
    "requirements.txt": "numpy>=1.24\nlark==1.1.9\n",
    "README": "# fanuc macros\n\nG-code programs for the lathe.\n",
    "Makefile": "all:\n\tpython3 -m pytest\n",
    "shell_comments.txt": "# settings\n#1 is the first\nX=1\n",
    "first_line_prose.txt": "READ ME FIRST\nG00 X1.\nG01 Z-1. F0.2\nM30\n",
    "mostly_prose.txt": "G00 X1.\nthen the operator checks\nthe part and writes it\nin the log\n",
    "percent_prose.txt": "% of parts scrapped last week\nG00 X1.\n",
    "empty.txt": "",
    "only_comments.txt": "(a note)\n(another)\n",
}


def test_text_files_are_programs_only_when_their_content_is_one(tmp_path: Path) -> None:
    for name, text in {**PROGRAM_TEXTS, **NOT_PROGRAM_TEXTS}.items():
        write(tmp_path / "shop" / name, text)
    (tmp_path / "shop" / "image.iso").write_bytes(b"\0" * 40000 + b"CD001" + b"\0" * 100)
    (tmp_path / "shop" / "u16.txt").write_bytes(ERROR_PROGRAM.encode("utf-16"))  # with its BOM
    result = run(tmp_path, "check", "--format", "json", "shop")
    paths = {Path(r["path"]).name for r in json.loads(result.stdout)}
    assert paths == {*PROGRAM_TEXTS, "u16.txt"}  # the UTF-16 one is told to be saved as UTF-8
    counts = summary(result.stderr)
    assert counts["checked"] == str(len(PROGRAM_TEXTS) + 1)
    assert counts["skipped"] == str(len(NOT_PROGRAM_TEXTS) + 1)  # and the disk image


def test_a_shop_folders_notes_are_skipped_and_named_in_the_summary(tmp_path: Path) -> None:
    write(tmp_path / "shop" / "o1000.nc", CLEAN_PROGRAM)
    write(tmp_path / "shop" / "notes.txt", NOTES)
    result = run(tmp_path, "check", "shop")
    assert (result.returncode, result.stdout) == (0, ""), result.stderr
    notes = Path("shop") / "notes.txt"
    assert result.stderr == (
        f"fanuc-macro: 1 file checked, 1 skipped (not programs: {notes}), 0 errors, 0 warnings\n"
    )
    # Named on the command line, a file is checked whatever it holds.
    named = run(tmp_path, "check", str(notes))
    assert named.returncode == 1 and "MB001" in named.stdout


def test_hidden_and_tool_folders_are_not_walked_unless_named(tmp_path: Path) -> None:
    repo = tmp_path / "repo"
    write(repo / "progs" / "o1000.nc", ERROR_PROGRAM)
    skipped = [
        ".git/hooks/o1.nc", ".hidden/o2.nc", ".venv/lib/o3.nc", "node_modules/pkg/LICENSE.txt",
        "node_modules/pkg/o4.nc", "build/o5.nc", "dist/o6.nc", "__pycache__/o7.nc",
        "venv/o8.nc", "pkg.egg-info/PKG-INFO", "env/lib/o9.nc", "cache/o10.nc",
        "progs/.o11.nc",
    ]  # fmt: skip
    for name in skipped:
        write(repo / name, ERROR_PROGRAM if name.endswith(".nc") else "MIT License\n")
    write(repo / "env" / "pyvenv.cfg", "home = /usr/bin\n")  # a virtualenv of any name
    write(repo / "cache" / "CACHEDIR.TAG", "Signature: 8a477f597d28d172789f06886806bc55\n")
    result = run(tmp_path, "check", "repo")
    assert result.returncode == 1, result.stderr
    assert reported(result.stdout) == {"repo/progs/o1000.nc"}
    assert summary(result.stderr)["skipped"] == "0"  # not looked into, so not counted
    # A folder or file the user names is taken, as ruff takes it.
    named = run(tmp_path, "check", "repo/build", "repo/.git/hooks/o1.nc")
    assert reported(named.stdout) == {"repo/build/o5.nc", "repo/.git/hooks/o1.nc"}


def test_exclude_matches_names_anywhere_and_paths_from_the_folder_walked(tmp_path: Path) -> None:
    for name in ("keep.nc", "old/a.nc", "sub/old/b.nc", "sub/c.nc", "sub/d.bak.nc", "e.nc"):
        write(tmp_path / "progs" / name, ERROR_PROGRAM)
    everything = run(tmp_path, "check", "progs")
    assert len(reported(everything.stdout)) == 6
    result = run(
        tmp_path,
        "check",
        "progs",
        "--exclude",
        "old",  # a folder's name, anywhere
        "--exclude",
        "*.bak.nc",  # a file's name
        "--exclude",
        "sub/c.nc",  # a path from the folder walked
        "--exclude",
        "progs/e.nc",  # the path as shown
    )
    assert reported(result.stdout) == {"progs/keep.nc"}
    # A file named on the command line is checked even when a pattern matches it.
    named = run(tmp_path, "check", "progs/old/a.nc", "--exclude", "old")
    assert reported(named.stdout) == {"progs/old/a.nc"}


# ---- the summary line -------------------------------------------------------------------------


def test_the_summary_is_one_line_on_standard_error_and_stdout_stays_the_findings(
    tmp_path: Path,
) -> None:
    write(tmp_path / "err.nc", ERROR_PROGRAM)
    write(tmp_path / "warn.nc", WARNING_PROGRAM)
    for index in range(5):
        write(tmp_path / f"note{index}.txt", NOTES)
    text = run(tmp_path, "check", ".")
    assert text.stderr.count("\n") == 1
    assert text.stderr == (
        "fanuc-macro: 2 files checked, 5 skipped (not programs: note0.txt, note1.txt, "
        "note2.txt, +2 more), 1 error, 1 warning, 1 hint\n"
    )
    assert all(
        re.match(r"^(err|warn)\.nc:\d+:\d+: MB\d{3} ", line) for line in text.stdout.splitlines()
    )
    as_json = run(tmp_path, "check", "--format", "json", ".")
    assert len(json.loads(as_json.stdout)) == len(text.stdout.splitlines())
    assert as_json.stderr == text.stderr
    quiet = run(tmp_path, "check", "-q", ".")
    assert (quiet.stdout, quiet.stderr) == (text.stdout, "")


# ---- output a stream cannot encode -------------------------------------------------------------


def test_output_a_stream_cannot_encode_is_escaped_not_a_crash(tmp_path: Path) -> None:
    seed = str(CHINESE_SEED)
    shown = run(tmp_path, "check", seed, encoding="cp1252")
    assert shown.returncode == 1, shown.stderr  # its two errors, not an internal error
    assert "internal error" not in shown.stderr
    assert "(#1 \\u4e3a\\u87ba\\u7eb9\\u5916\\u5f84)" in shown.stdout
    records = json.loads(run(tmp_path, "check", "--format", "json", seed, encoding="cp1252").stdout)
    assert "(#1 为螺纹外径)" in records[0]["message"]  # escaped in JSON, read back as written
    traced = run(tmp_path, "trace", "--format", "json", seed, encoding="cp1252")
    assert traced.returncode == 0 and json.loads(traced.stdout)["motions"], traced.stderr
    plotted = run(tmp_path, "plot", "-o", "-", seed, encoding="cp1252")
    assert plotted.returncode == 0, plotted.stderr
    ET.fromstring(plotted.stdout)  # still an SVG
    for command in (["hover", seed, "9", "5"], ["format", seed], ["trace", seed]):
        done = run(tmp_path, *command, encoding="cp1252")
        assert done.returncode == 0 and done.stdout, (command, done.stderr)


# ---- exit status -----------------------------------------------------------------------------


def test_exit_status_by_the_least_severe_finding_that_fails(tmp_path: Path) -> None:
    write(tmp_path / "warn.nc", WARNING_PROGRAM)
    write(tmp_path / "clean.nc", CLEAN_PROGRAM)
    (tmp_path / "binary.nc").write_bytes(b"O1\x00\x01")  # MB007 information: not a text
    assert run(tmp_path, "check", "warn.nc").returncode == 0  # an error fails by default
    assert run(tmp_path, "check", "--fail-on", "error", "warn.nc").returncode == 0
    assert run(tmp_path, "check", "--fail-on", "warning", "warn.nc").returncode == 1
    assert run(tmp_path, "check", "--fail-on", "warning", "clean.nc").returncode == 0
    assert run(tmp_path, "check", "--fail-on", "warning", "binary.nc").returncode == 0
    assert run(tmp_path, "check", "--fail-on", "information", "binary.nc").returncode == 1
    assert run(tmp_path, "check", "--fail-on", "hint", "binary.nc").returncode == 1
    refused = run(tmp_path, "check", "--fail-on", "fatal", "warn.nc")
    assert refused.returncode == 2 and "invalid choice" in refused.stderr


def test_max_warnings_fails_when_there_are_more(tmp_path: Path) -> None:
    write(tmp_path / "warn.nc", WARNING_PROGRAM)
    write(tmp_path / "clean.nc", CLEAN_PROGRAM)
    assert run(tmp_path, "check", "--max-warnings", "0", "warn.nc").returncode == 1
    assert run(tmp_path, "check", "--max-warnings", "1", "warn.nc").returncode == 0
    assert run(tmp_path, "check", "--max-warnings", "0", "clean.nc").returncode == 0
    refused = run(tmp_path, "check", "--max-warnings", "-1", "warn.nc")
    assert refused.returncode == 2 and "not a whole number from 0" in refused.stderr


def test_every_path_is_checked_when_one_is_missing_or_empty(tmp_path: Path) -> None:
    write(tmp_path / "good.nc", ERROR_PROGRAM)
    (tmp_path / "empty").mkdir()
    missing = run(tmp_path, "check", "missing.nc", "good.nc")
    assert missing.returncode == 2
    assert reported(missing.stdout) == {"good.nc"}
    assert missing.stderr.splitlines()[0] == "fanuc-macro: no such file or directory: missing.nc"
    empty = run(tmp_path, "check", "empty", "good.nc")
    assert empty.returncode == 2
    assert reported(empty.stdout) == {"good.nc"}
    assert empty.stderr.splitlines()[0] == "fanuc-macro: no programs found in empty"
    as_json = run(tmp_path, "check", "--format", "json", "missing.nc", "good.nc")
    assert {r["path"] for r in json.loads(as_json.stdout)} == {"good.nc"}
    clean = write(tmp_path / "clean.nc", CLEAN_PROGRAM)
    assert run(tmp_path, "check", "missing.nc", clean.name).returncode == 2  # not 0


INTERNAL_ERROR_SCRIPT = """
import sys
import fanuc_macro.analysis as analysis
import fanuc_macro.cli as cli
def broken(*args, **kwargs):
    raise RuntimeError("a bug")
if sys.argv[1] == "check":
    analysis.ALL_CHECKS = (*analysis.ALL_CHECKS, broken)
else:
    cli.trace = broken
sys.exit(cli.main(sys.argv[1:]))
"""


@pytest.mark.parametrize("command", ["check", "trace"])
def test_an_internal_error_exits_3(tmp_path: Path, command: str) -> None:
    path = write(tmp_path / "p.nc", CLEAN_PROGRAM)
    env = dict(os.environ, PYTHONPATH=str(ROOT / "server"))
    done = subprocess.run(
        [sys.executable, "-c", INTERNAL_ERROR_SCRIPT, command, str(path)],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )
    assert done.returncode == 3, done.stdout + done.stderr
    assert "a bug" in done.stdout + done.stderr


def test_the_help_says_the_exit_codes(tmp_path: Path) -> None:
    for command in ([], ["check"], ["format"]):
        shown = run(tmp_path, *command, "--help").stdout
        codes = re.findall(r"^  ([0-3])  ", shown, re.M)
        assert codes == ["0", "1", "2", "3"], (command, shown)
    check_help = run(tmp_path, "check", "--help").stdout
    for said in (".ngc", ".spf", ".min", ".txt", "node_modules", "pyvenv.cfg", "--fail-on"):
        assert said in check_help


# ---- options -----------------------------------------------------------------------------------


CALLER = "%\nO1000 (MAIN)\nM98 P2000\nM30\n%\n"
CALL_COLUMN = "M98 P2000".index("P2000") + 2


@pytest.mark.parametrize(
    "arguments",
    [
        ["--with", "lib", "main.nc", "3", str(CALL_COLUMN)],
        ["main.nc", "3", str(CALL_COLUMN), "--with", "lib"],
        ["main.nc", "--with", "lib", "3", str(CALL_COLUMN)],
        ["--with", "other", "--with", "lib", "main.nc", "3", str(CALL_COLUMN)],
        ["--with", "other", "lib", "main.nc", "3", str(CALL_COLUMN)],
        ["main.nc", "3", str(CALL_COLUMN), "--with", "other", "lib"],
        ["--with=lib", "main.nc", "3", str(CALL_COLUMN)],
        ["--with", "lib", "--format", "text", "main.nc", "3", str(CALL_COLUMN)],
    ],
    ids=[
        "before",
        "after",
        "between",
        "repeated",
        "two-before",
        "two-after",
        "equals",
        "then-an-option",
    ],
)
def test_with_takes_its_paths_anywhere(tmp_path: Path, arguments: list[str]) -> None:
    write(tmp_path / "main.nc", CALLER)
    write(tmp_path / "lib" / "o2000.nc", CALLED)
    write(tmp_path / "other" / "o3000.nc", "%\nO3000\nM99\n%\n")
    found = run(tmp_path, "definition", *arguments)
    assert (found.returncode, found.stdout) == (0, f"{Path('lib') / 'o2000.nc'}:2:1\n"), (
        found.stderr
    )


def test_with_before_the_file_of_trace(tmp_path: Path) -> None:
    write(tmp_path / "main.nc", CALLER)
    write(tmp_path / "lib" / "o2000.nc", CALLED)
    traced = run(tmp_path, "trace", "--with", "lib", "main.nc", "--format", "json")
    assert traced.returncode == 0, traced.stderr
    assert [m["program"].split()[0] for m in json.loads(traced.stdout)["motions"]] == ["O2000"]
    bare = run(tmp_path, "trace", "--with", "main.nc")  # no path left for --with
    assert bare.returncode == 2 and "--with: expected one argument" in bare.stderr


def test_disable_takes_rule_names_in_any_case(tmp_path: Path) -> None:
    write(tmp_path / "p.nc", "%\nO1000\nG00 X1.\nM30%\n%\n")  # '%' fused to a block: MB009
    assert "MB009" in run(tmp_path, "check", "p.nc").stdout
    for spelling in ("tape-mark-not-alone", "Tape-Mark-Not-Alone", "TAPE_MARK_NOT_ALONE", "mb009"):
        result = run(tmp_path, "check", "--disable", spelling, "p.nc")
        assert result.returncode != 2 and "MB009" not in result.stdout, (spelling, result.stderr)
    both = run(tmp_path, "check", "--disable", "MB403", "--disable", "tape-mark-not-alone", "p.nc")
    assert "MB009" not in both.stdout
    unknown = run(tmp_path, "check", "--disable", "tape-mark-alone", "p.nc")
    assert unknown.returncode == 2
    assert "unknown rule code 'TAPE-MARK-ALONE'" in unknown.stderr
    assert "MB009 tape-mark-not-alone" in unknown.stderr  # the nearest


def test_controller_in_any_case(tmp_path: Path) -> None:
    write(tmp_path / "p.nc", ERROR_PROGRAM)
    canonical = run(tmp_path, "check", "--format", "json", "--controller", "0i-MF", "p.nc")
    for spelling in ("0i-mf", "0I-MF", " 0i-Mf"):
        other = run(tmp_path, "check", "--format", "json", "--controller", spelling, "p.nc")
        assert (other.returncode, other.stdout) == (canonical.returncode, canonical.stdout)
    assert run(tmp_path, "trace", "--controller", "30I", "p.nc").returncode == 0
    refused = run(tmp_path, "check", "--controller", "31i", "p.nc")
    assert refused.returncode == 2 and "0i-TF, 0i-MF" in refused.stderr


def test_standard_input_is_checked_under_the_name_given(tmp_path: Path) -> None:
    data = ERROR_PROGRAM.encode()
    plain = run(tmp_path, "check", "-", stdin=data)
    assert plain.returncode == 1 and reported(plain.stdout) == {"-"}
    named = run(tmp_path, "check", "-", "--stdin-filename", "progs/o1000.nc", stdin=data)
    assert reported(named.stdout) == {"progs/o1000.nc"}
    # Decoded as a file is: GB18030 comments read as written.
    gb = "%\nO1000 (外螺纹)\nG00 X1. (退刀)\nM30\n%\n".encode("gb18030")
    assert run(tmp_path, "check", "--format", "json", "-", stdin=gb).stdout == "[]\n"
    # The name gives the program number of a file without an O line, and the text on standard
    # input stands for the file of that name on disk.
    write(tmp_path / "lib" / "O2000.nc", "G00 X0 (ON DISK)\nM99\n")
    write(tmp_path / "main.nc", CALLER)
    sub = b"G00 X0 (EDITED)\nM99\n"
    calls = run(
        tmp_path, "check", "main.nc", "lib", "-", "--stdin-filename", "lib/O2000.nc", stdin=sub
    )
    assert calls.returncode == 0, calls.stderr
    [hint] = calls.stdout.splitlines()  # O2000 is found: no MB403, only the name's note
    assert hint.startswith("lib/O2000.nc:1:1: MB010 hint program number 2000 taken from")
    assert summary(calls.stderr)["checked"] == "2"
    refused = run(tmp_path, "check", "main.nc", "--stdin-filename", "x.nc")
    assert refused.returncode == 2 and "give - among the paths" in refused.stderr


def test_standard_input_for_trace_plot_hover_and_format(tmp_path: Path) -> None:
    data = b"%\nO1000\nG00 X10. Z5.\nG01 Z-5. F0.2\nM30\n%\n"
    traced = run(tmp_path, "trace", "-", "--format", "json", stdin=data)
    assert len(json.loads(traced.stdout)["motions"]) == 2, traced.stderr
    plotted = run(tmp_path, "plot", "-", "-o", "-", stdin=data)
    assert plotted.returncode == 0 and "<svg" in plotted.stdout, plotted.stderr
    nowhere = run(tmp_path, "plot", "-", stdin=data)
    assert nowhere.returncode == 2 and "-o" in nowhere.stderr
    hovered = run(tmp_path, "hover", "-", "3", "1", "--stdin-filename", "o1000.nc", stdin=data)
    assert hovered.returncode == 0 and "G00" in hovered.stdout, hovered.stderr
    formatted = run(tmp_path, "format", "-", stdin=b"o1\ng01x1.\n")
    assert (formatted.returncode, formatted.stdout) == (0, "O1\nG01X1.\n")
    checked = run(tmp_path, "format", "--check", "-", "--stdin-filename", "a.nc", stdin=b"g0\n")
    assert checked.returncode == 1 and "a.nc: would be reformatted" in checked.stderr
    written = run(tmp_path, "format", "--write", "-", stdin=b"g0\n")
    assert written.returncode == 2 and "cannot be written back" in written.stderr


def test_format_checks_and_writes_several_files_and_folders(tmp_path: Path) -> None:
    write(tmp_path / "a.nc", "o1\ng01x1.\nm30\n")
    write(tmp_path / "progs" / "b.nc", "O2\nG01X1.\nM30\n")  # formatted already
    write(tmp_path / "progs" / "sub" / "c.ngc", "o3\nm30\n")
    write(tmp_path / "progs" / "notes.txt", NOTES)  # not a program: not formatted
    write(tmp_path / "progs" / "node_modules" / "d.nc", "o4\n")  # a tool's folder
    checked = run(tmp_path, "format", "--check", "a.nc", "progs")
    assert checked.returncode == 1
    assert sorted(checked.stderr.splitlines()) == sorted(
        [
            "a.nc: would be reformatted",
            f"{Path('progs') / 'sub' / 'c.ngc'}: would be reformatted",
            "fanuc-macro: 2 files would be reformatted, 1 already formatted",
        ]
    )
    written = run(tmp_path, "format", "--write", "a.nc", "progs")
    assert written.returncode == 0, written.stderr
    assert (tmp_path / "a.nc").read_text() == "O1\nG01X1.\nM30\n"
    assert (tmp_path / "progs" / "sub" / "c.ngc").read_text() == "O3\nM30\n"
    assert (tmp_path / "progs" / "notes.txt").read_text() == NOTES
    assert (tmp_path / "progs" / "node_modules" / "d.nc").read_text() == "o4\n"
    again = run(tmp_path, "format", "--check", "a.nc", "progs")
    assert again.returncode == 0, again.stderr
    missing = run(tmp_path, "format", "--check", "missing.nc", "a.nc")
    assert missing.returncode == 2 and "missing.nc" in missing.stderr


def test_format_prints_one_file_and_refuses_several_without_check_or_write(
    tmp_path: Path,
) -> None:
    write(tmp_path / "a.nc", "o1\n")
    write(tmp_path / "progs" / "b.nc", "o2\n")
    for paths in (["a.nc", "progs/b.nc"], ["progs"]):
        refused = run(tmp_path, "format", *paths)
        assert (refused.returncode, refused.stdout) == (2, ""), paths
        assert "give --check or --write" in refused.stderr
    assert run(tmp_path, "format", "a.nc").stdout == "O1\n"
