"""Formatting and N renumbering in the ide layer: plain edits, checked against the parser."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config, FormatSettings
from fanuc_macro.ide.data import ActionKind, Position, Range, TextEdit
from fanuc_macro.ide.formatting import (
    CannotFormat,
    FormatOptions,
    Rewrite,
    apply_edits,
    format_document,
    format_file,
    format_line,
    format_lines,
    format_text,
    line_meaning,
)
from fanuc_macro.ide.renumber import MAX_SEQUENCE_NUMBER, renumber_labels
from fanuc_macro.ide.view import View
from fanuc_macro.syntax.lines import decode_bytes, split_lines
from fanuc_macro.syntax.parser import default_parser
from fanuc_macro.syntax.tree import ParsedLine

ROOT = Path(__file__).resolve().parents[1]
SEEDS = sorted((ROOT / "tests" / "fixtures" / "seeds").glob("*.nc"))
CORPUS_DIR = ROOT.parent / "shared" / "corpus"
CORPUS = sorted(p for p in CORPUS_DIR.glob("*") if p.is_file() and p.name != "MANIFEST.tsv")

ALWAYS = FormatOptions(
    FormatSettings(space_between_words="always", spaces_around_assignment="always")
)
NEVER = FormatOptions(FormatSettings(space_between_words="never", spaces_around_assignment="never"))
OPTIONS = {"default": FormatOptions(), "always": ALWAYS, "never": NEVER}


def meanings(text: str) -> list[object]:
    parser = default_parser()
    return [line_meaning(parser.parse_line(line)) for line in split_lines(text)]


def comments(text: str) -> list[str]:
    parser = default_parser()
    return [
        line[c.span.start : c.span.end]
        for line in split_lines(text)
        for c in parser.parse_line(line).comments
    ]


# ---- one block -------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("line", "options", "expected"),
    [
        ("g01x10.z-5.  ", "default", "G01X10.Z-5."),
        ("g01x10.z-5.", "always", "G01 X10. Z-5."),
        ("G01  X10.\tZ-5.", "never", "G01X10.Z-5."),
        ("n10 g00 x1.", "never", "N10G00X1."),
        ("N10G00X1.", "always", "N10 G00 X1."),
        ("#1=#2+1.", "always", "#1 = #2+1."),
        ("#1 =  #2", "never", "#1=#2"),
        ("#1 =  #2", "default", "#1 =  #2"),
        ("if[#1eq1]then#2=3", "always", "IF[#1EQ1]THEN#2 = 3"),
        ("while[#1lt10]do1", "default", "WHILE[#1LT10]DO1"),
        ("goto 10", "default", "GOTO 10"),
        # Numbers keep their text, words their order.
        ("x10. z.5 f0.20", "never", "X10.Z.5F0.20"),
        # Comments keep their text and case, English or Chinese, and the spaces around them.
        ("g01 (Rough 粗车 x) x1.", "never", "G01 (Rough 粗车 x) X1."),
        ("g01(Rough 粗车 x)x1.", "always", "G01(Rough 粗车 x)X1."),
        ("m30 (end)   ", "default", "M30 (end)"),
        # An unclosed comment's spaces are its own.
        ("g01 x1. (open   ", "default", "G01 X1. (open   "),
        # A DPRNT format is printed as written: only its keyword is cased.
        ("dprnt[x#100[53]*y]", "default", "DPRNT[x#100[53]*y]"),
        ("O<part one>", "default", "O<part one>"),
        ("%   ", "default", "%"),
    ],
)
def test_format_line(line: str, options: str, expected: str) -> None:
    parsed = default_parser().parse_line(line)
    assert format_line(parsed, OPTIONS[options]) == expected
    assert apply_edits(line, format_lines(line, OPTIONS[options])) == expected


def test_format_settings_are_read_and_bad_values_left_at_their_defaults() -> None:
    read = FormatSettings.from_settings(
        {
            "format": {
                "upperCase": False,
                "spaceBetweenWords": "always",
                "spacesAroundAssignment": "never",
                "renumberStep": 5,
            }
        }
    )
    assert read == FormatSettings(False, "always", "never", 5)
    bad = {"upperCase": "no", "spaceBetweenWords": "some", "renumberStep": -1}
    assert FormatSettings.from_settings({"format": bad}) == FormatSettings()
    assert FormatSettings.from_settings({"format": 3}) == FormatSettings()
    assert FormatSettings.from_settings(None) == FormatSettings()


def test_keep_case_setting() -> None:
    options = FormatOptions(FormatSettings(upper_case=False))
    assert format_text("g01 x1.  \n", options) == "g01 x1.\n"


def test_a_line_with_a_syntax_error_is_left_as_it_is() -> None:
    text = "g01 x10..  \nx1.  \n"
    assert format_text(text, FormatOptions()) == "g01 x10..  \nX1.\n"


# ---- the refusal: a rewrite that changes what a block means is not applied --------------------


def _faulty(fault: str) -> Rewrite:
    def rewrite(parsed: ParsedLine, options: FormatOptions) -> str:
        good = format_line(parsed, options)
        if fault == "number":  # "10." written "10.0": a decimal point rule's meaning
            return re.sub(r"(\d+\.)(?!\d)", r"\g<1>0", good)
        if fault == "comment case":
            return good.upper()
        if fault == "space in a keyword":  # "GOTO" spaced "G O T O": no block any more
            return re.sub(r"(?<=[A-Z])(?=[A-Z])", " ", good)
        if fault == "address in a variable":  # "#100" read as "#1" and "00"...
            return good.replace("#100", "#1X00")
        raise AssertionError(fault)

    return rewrite


@pytest.mark.parametrize(
    ("fault", "line"),
    [
        ("number", "g01 x10. z5."),
        ("comment case", "g01 x1. (Rough cut)"),
        ("comment case", "dprnt[x#1[53]]"),
        ("space in a keyword", "if[#1eq1]goto10"),
        ("address in a variable", "#100=#100+1"),
    ],
)
def test_a_rewrite_that_changes_the_meaning_is_refused(fault: str, line: str) -> None:
    rewrite = _faulty(fault)
    parsed = default_parser().parse_line(line)
    assert rewrite(parsed, FormatOptions()) != format_line(parsed, FormatOptions())
    text = f"{line}\nm30  \n"
    edits = format_lines(text, FormatOptions(), rewrite=rewrite)
    # The faulty line stays as it was; the next is still formatted.
    assert [e.range.start.line for e in edits] == [1]
    assert apply_edits(text, edits) == f"{line}\nM30\n"


# ---- whole documents -------------------------------------------------------------------------


def test_crlf_is_kept_and_the_ends_of_the_document() -> None:
    text = "o1\r\ng01x1.  \r\nm30\r\n\r\n\r\n"
    assert format_text(text, FormatOptions()) == "O1\r\nG01X1.\r\nM30\r\n\r\n\r\n"
    trimmed = FormatOptions(trim_final_newlines=True)
    assert format_text(text, trimmed) == "O1\r\nG01X1.\r\nM30\r\n"
    final = FormatOptions(insert_final_newline=True)
    assert format_text("o1\r\nm30  ", final) == "O1\r\nM30\r\n"
    assert format_text("o1\r\nM30", final) == "O1\r\nM30\r\n"
    kept = FormatOptions(trim_trailing_whitespace=False)
    assert format_text("m30  \n", kept) == "M30  \n"


def test_document_edits_are_one_per_changed_line_and_small() -> None:
    edits = format_document("O1\nG01 x1.\nM30\n", FormatOptions())
    assert edits == [TextEdit(Range(Position(1, 4), Position(1, 5)), "X")]


def test_range_formatting_touches_only_its_lines() -> None:
    text = "g01x1.\ng01x2.\ng01x3.\n"
    edits = format_lines(text, FormatOptions(), 1, 1)
    assert apply_edits(text, edits) == "g01x1.\nG01X2.\ng01x3.\n"


@pytest.mark.parametrize("options", OPTIONS)
@pytest.mark.parametrize("path", SEEDS + CORPUS, ids=lambda p: p.name[-40:])
def test_programs_keep_their_meaning_and_formatting_is_idempotent(path: Path, options: str) -> None:
    text = decode_bytes(path.read_bytes()).text
    chosen = OPTIONS[options]
    once = format_text(text, chosen)
    assert format_text(once, chosen) == once
    assert meanings(once) == meanings(text)
    assert comments(once) == comments(text)
    assert [m.group() for m in re.finditer(r"\r\n|\r|\n", once)] == [
        m.group() for m in re.finditer(r"\r\n|\r|\n", text)
    ]


def test_the_corpus_is_there() -> None:
    assert len(SEEDS) >= 5
    assert len(CORPUS) >= 50, CORPUS_DIR


def test_format_file_keeps_the_encoding(tmp_path: Path) -> None:
    data = "o1 (粗车)\r\ng01x1.  \r\n".encode("gb18030")
    assert format_file(data, FormatOptions()) == "O1 (粗车)\r\nG01X1.\r\n".encode("gb18030")
    bom = "\ufeffo1\n".encode()
    assert format_file(bom, FormatOptions()) == "\ufeffO1\n".encode()
    same = b"O1\nM30\n"
    assert format_file(same, FormatOptions()) is same
    with pytest.raises(CannotFormat):
        format_file(b"\x00\x01binary", FormatOptions())


# ---- the command line ------------------------------------------------------------------------


def _cli(*args: str) -> subprocess.CompletedProcess[bytes]:
    env_path = str(ROOT / "server")
    return subprocess.run(
        [sys.executable, "-m", "fanuc_macro.cli", "format", *args],
        capture_output=True,
        env={"PYTHONPATH": env_path, "PATH": "/usr/bin:/bin"},
        check=False,
    )


def test_cli_format_check_and_write(tmp_path: Path) -> None:
    path = tmp_path / "o1.nc"
    path.write_bytes(b"o1 (Keep me)\r\ng01x1.z2.  \r\nm30\r\n")
    shown = _cli(str(path), "--space-between-words", "always")
    assert shown.returncode == 0
    assert shown.stdout == b"O1 (Keep me)\r\nG01 X1. Z2.\r\nM30\r\n"
    assert path.read_bytes() == b"o1 (Keep me)\r\ng01x1.z2.  \r\nm30\r\n"  # not written
    assert _cli(str(path), "--check").returncode == 1
    written = _cli(str(path), "--write")
    assert written.returncode == 0, written.stderr
    assert path.read_bytes() == b"O1 (Keep me)\r\nG01X1.Z2.\r\nM30\r\n"
    checked = _cli(str(path), "--check")
    assert (checked.returncode, checked.stdout) == (0, b"")
    assert _cli(str(tmp_path / "missing.nc")).returncode == 2
    assert _cli(str(path), "--check", "--write").returncode == 2


# ---- N renumbering ---------------------------------------------------------------------------


def view_of(text: str, config: Config | None = None) -> View:
    config = config or Config()
    return View("main.nc", analyse(text, "main.nc", config), config)


def renumbered(text: str, step: int = 10, config: Config | None = None) -> str:
    action = renumber_labels(view_of(text, config), 0, step)
    assert action is not None and not action.disabled, action
    assert action.kind is ActionKind.SOURCE_RENUMBER
    (edit,) = action.edits
    return apply_edits(text, list(edit.edits))


LOOP = "O1000\nN5 #1=0\nN7 IF[#1GE3]GOTO99\nn8 #1=#1+1 (count)\nGOTO7\nN99 M30\n"


def test_renumber_updates_the_jumps() -> None:
    assert renumbered(LOOP) == (
        "O1000\nN10 #1=0\nN20 IF[#1GE3]GOTO40\nn30 #1=#1+1 (count)\nGOTO20\nN40 M30\n"
    )
    assert renumbered(LOOP, step=5).splitlines()[2] == "N10 IF[#1GE3]GOTO20"


def test_renumber_updates_m99_p_and_the_lathe_profile() -> None:
    text = (
        "O2000\nG71U1.R0.5\nG71P100Q200U0.2W0.1F0.3\nN100G0X20.\nN200G1Z-10.\n"
        "G70P100Q200\nN300M99P300\n"
    )
    assert renumbered(text) == (
        "O2000\nG71U1.R0.5\nG71P10Q20U0.2W0.1F0.3\nN10G0X20.\nN20G1Z-10.\nG70P10Q20\nN30M99P30\n"
    )
    # On a mill G73 is peck drilling: its Q is a depth, not a label.
    mill = "O3000\nG73X1.Z-5.Q100R1.\nN100G80\nM30\n"
    assert renumbered(mill, config=Config(controller="0i-MF")) == (
        "O3000\nG73X1.Z-5.Q100R1.\nN10G80\nM30\n"
    )


def test_renumber_from_the_tape_mark_is_of_the_first_program() -> None:
    assert renumbered("%\nO1\nN3 GOTO3\nM30\n%\n") == "%\nO1\nN10 GOTO10\nM30\n%\n"


def test_renumber_only_the_program_at_the_line() -> None:
    text = "O1\nN1 GOTO1\nM30\nO2\nN1 GOTO1\nM99\n"
    action = renumber_labels(view_of(text), 4)
    assert action is not None and not action.disabled
    (edit,) = action.edits
    assert apply_edits(text, list(edit.edits)) == "O1\nN1 GOTO1\nM30\nO2\nN10 GOTO10\nM99\n"


@pytest.mark.parametrize(
    ("text", "reason"),
    [
        ("O1\nN1 #2=1\nGOTO#2\nM30\n", "line 3 is computed"),
        ("O1\nN1 G01 X1.\nGOTO30\nM30\n", "GOTO 30 on line 3 names no N30"),
        ("O1\nN1 G01 X1.\nN1 G01 X2.\nGOTO1\nM30\n", "N1 is on lines 2, 3"),
        ("O1\nN1 G01 X1.\nG01 X1..\nM30\n", "line 3 has a syntax error"),
        ("O1\nN1 M99 P#1\n", "the P on line 2 is computed"),
        ("O1\nN1 M98 P2\nM30\nO2\nN5 M99 P1\n", "O0002, which it calls, returns"),
    ],
)
def test_renumber_refuses_what_it_cannot_follow(text: str, reason: str) -> None:
    action = renumber_labels(view_of(text), 0)
    assert action is not None
    assert action.edits == ()
    assert reason in action.disabled
    assert reason in action.title


def test_renumber_of_a_called_program_leaves_its_m99_p() -> None:
    text = "O1\nM98 P2\nN1 M30\nO2\nN5 G01 X1.\nN6 M99 P1\n"
    action = renumber_labels(view_of(text), 4)
    assert action is not None
    assert "M99 P on line 6 returns to its caller (O0001 calls it on line 2)" in action.disabled
    # Called from nowhere, its M99 P is a jump in itself (a main program's).
    alone = "O2\nN5 G01 X1.\nN6 M99 P5\n"
    assert renumbered(alone) == "O2\nN10 G01 X1.\nN20 M99 P10\n"


def test_renumber_never_goes_past_the_largest_n_number() -> None:
    def program(labels: int) -> str:
        return "O1\n" + "".join(f"N{k} G01 X{k}.\n" for k in range(1, labels + 1)) + "M30\n"

    refused = renumber_labels(view_of(program(10)), 0, step=10_000)  # N100000 would be last
    assert refused is not None
    assert f"past N{MAX_SEQUENCE_NUMBER}" in refused.disabled
    done = renumber_labels(view_of(program(9)), 0, step=10_000)  # N90000 is
    assert done is not None and not done.disabled
    assert apply_edits(program(9), list(done.edits[0].edits)).splitlines()[-2] == "N90000 G01 X9."


def test_renumber_offers_nothing_when_there_is_nothing_to_do() -> None:
    assert renumber_labels(view_of("O1\nG01 X1.\nM30\n"), 0) is None
    assert renumber_labels(view_of("O1\nN10 G01 X1.\nN20 GOTO10\n"), 0) is None


@pytest.mark.parametrize("path", SEEDS, ids=lambda p: p.name)
def test_renumber_keeps_the_diagnostics_of_the_seeds(path: Path) -> None:
    """Each program of a seed renumbered: the same findings on the same lines (the jumps reach
    the same blocks), or a refusal that says why."""
    text = path.read_text(encoding="utf-8")
    view = view_of(text)
    before = [(d.code, d.line) for d in view.analysis.diagnostics]
    done = 0
    for program in view.index.programs:
        action = renumber_labels(view, program.first_line)
        if action is None or action.disabled:
            assert action is None or action.disabled in action.title
            continue
        after = apply_edits(text, list(action.edits[0].edits))
        assert after != text
        assert [(d.code, d.line) for d in view_of(after).analysis.diagnostics] == before
        done += 1
    if path.name == "o1_radial_layers.nc":  # N5 and its GOTO5
        assert done == 1
