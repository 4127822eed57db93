"""Dead blocks, restart points and blocks after the end (MB702, MB709, MB710)."""

from __future__ import annotations

from fanuc_macro.analysis import analyse


def found(text: str, *codes: str, run_evaluator: bool = True) -> list[tuple[int, str]]:
    """(1-based line, code) of the diagnostics with the given codes."""
    diags = analyse(text, "flow.nc", run_evaluator=run_evaluator).diagnostics
    return sorted((d.line + 1, d.code) for d in diags if d.code in codes)


FLOW = ("MB702", "MB709", "MB710")


def test_restart_point_after_a_bare_n_line_and_dead_blocks_before_it() -> None:
    text = "O1\nG00 X1.\nM30\nG00 X2.\nN5\nG00 X3.\nG00 X4.\nM99\nG00 X5.\n"
    # Line 4 after M30 has no N: dead. 'N5' alone starts what a search runs, up to M99.
    assert found(text, *FLOW) == [(4, "MB702"), (6, "MB709"), (9, "MB702")]
    message = next(d.message for d in analyse(text, "flow.nc").diagnostics if d.code == "MB709")
    assert "(lines 6-8, from N5)" in message and "past the M30 of line 3" in message


def test_a_haas_local_subroutine_is_neither_dead_nor_a_restart_point() -> None:
    text = "O1\nM97 P5\nG00 X1.\nM30\nN5 G00 X2.\nG00 X3.\nM99\n"
    assert found(text, *FLOW) == []


def test_a_jump_in_a_block_that_does_not_parse_leaves_reachability_unknown() -> None:
    text = "O1\nIF[#1 == 2]GOTO5\nGOTO9\nN5 G00 X1.\nG00 X2.\nN9 M30\n"
    assert found(text, "MB702", "MB709") == []


def test_after_the_end_is_mb702_when_the_run_is_whole_and_mb710_when_it_is_not() -> None:
    pasted = "M30\nG00 X50. Z2.\nG01 X0. F0.2\nM30\n"
    decided = "O1\n#1=1\nIF[#1EQ1]GOTO20\nG01 X9. F0.2\nN20 G00 X100.\n" + pasted
    # IF always true (MB701): the run is decided, so MB702 names every block it did not run.
    assert found(decided, *FLOW) == [(4, "MB702"), (7, "MB702")]
    undecided = decided.replace("#1=1\n", "#1=#500\n")
    assert found(undecided, *FLOW) == [(7, "MB710")]
    # The text alone is enough for MB710.
    assert found(undecided, *FLOW, run_evaluator=False) == [(7, "MB710")]


def test_block_skip_makes_an_end_optional() -> None:
    text = "O1\n#1=#500\nIF[#1EQ1]GOTO9\n/M30\nG00 X1.\nN9 M30\nG00 X2.\n"
    assert found(text, "MB710") == [(7, "MB710")]


def test_another_controls_program_gets_no_reachability_verdict() -> None:
    # Syntec: IF (...) THEN does not parse, and its GOTO does.
    text = "O1\nIF(#1=1)THEN\nGOTO5;\nEND_IF;\nG00 X1.\nN5 G00 X2.\nM30\nG00 X3.\n"
    assert found(text, *FLOW) == []
