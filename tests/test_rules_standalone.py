"""A rule stands alone: what an editor shows of its diagnostics (tags, fixes) comes with the
diagnostic the rule makes, and the front ends only convert it (no rule code in ide/ or lsp/).
"""

from __future__ import annotations

from lsprotocol import types

from fanuc_macro.analysis import analyse
from fanuc_macro.diagnostics import Diagnostic, Severity, Tag
from fanuc_macro.lsp.convert import Codec, Lines, to_lsp_diagnostic

DEAD = "O1000\nGOTO 10\nG00 X1\nN10 M30\nG00 X2\n"


def test_dead_code_diagnostics_carry_the_unnecessary_tag() -> None:
    diags = analyse(DEAD).diagnostics
    tagged = {d.code for d in diags if Tag.UNNECESSARY in d.tags}
    untagged = {d.code for d in diags if not d.tags}
    assert "MB702" in tagged
    assert "MB701" not in tagged and "MB709" not in tagged
    assert untagged.isdisjoint({"MB702", "MB710"})


def test_the_language_server_maps_any_rules_tags() -> None:
    diag = Diagnostic("MB101", Severity.ERROR, "m", 0, 0, 0, 1, tags=frozenset({Tag.DEPRECATED}))
    lines = Lines(("GOTO 1",), Codec())
    converted = to_lsp_diagnostic(diag, "a.nc", "file:///a.nc", lines)
    assert converted.tags == [types.DiagnosticTag.Deprecated]
    plain = to_lsp_diagnostic(Diagnostic("MB702", Severity.HINT, "m", 0, 0, 0, 1), "a", "a", lines)
    assert plain.tags is None  # the tag is the diagnostic's, not the code's
