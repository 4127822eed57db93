"""docs/rules.md is generated from the RuleDoc beside each rule and docs/rules-intro.md.

A rule's documentation is a ``RuleDoc`` constant (``MB101_DOC``) beside the function that finds
the rule; ``python3 scripts/rules_doc.py`` writes docs/rules.md from them.
These tests fail when the file is stale or a rule lacks a part; tests/test_rules.py reads the
generated file (a section per code, its severity, an example that triggers the rule).
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from fanuc_macro.analysis import RULE_DOCS, RULES
from fanuc_macro.rules_doc import PARTS, part_texts, render

ROOT = Path(__file__).resolve().parents[1]
INTRO = ROOT / "docs" / "rules-intro.md"
DOCS = ROOT / "docs" / "rules.md"
SCRIPT = ROOT / "scripts" / "rules_doc.py"

ALL_CODES = sorted(RULES)
LABELS = [label for _name, label in PARTS]


def test_rules_md_is_what_the_generator_writes() -> None:
    assert DOCS.read_text("utf-8") == render(INTRO.read_text("utf-8")), (
        "docs/rules.md is stale: run `python3 scripts/rules_doc.py` and commit docs/rules.md"
    )


def test_every_registered_rule_is_documented_and_only_those() -> None:
    assert sorted(RULE_DOCS) == ALL_CODES


@pytest.mark.parametrize("code", ALL_CODES)
def test_every_part_is_written(code: str) -> None:
    texts = part_texts(RULE_DOCS[code])
    empty = [label for name, label in PARTS if not texts[name].strip()]
    assert not empty, f"{code} has empty parts: {empty}"
    fence = "```text" if code == "MB000" else "```nc"  # MB000: no program makes it
    assert fence in texts["example"], f"the example of {code} has no {fence} block"


@pytest.mark.parametrize("code", ALL_CODES)
def test_parts_keep_to_their_section(code: str) -> None:
    """A part's text must not start a heading or a label of its own: the sections are split
    on them (tests/test_rules.py, the language server's anchors)."""
    for name, text in part_texts(RULE_DOCS[code]).items():
        assert not re.search(r"^#{1,6} ", text, re.M), f"{code}.{name} holds a heading"
        for label in LABELS:
            assert f"**{label}**" not in text, f"{code}.{name} holds the label {label!r}"
        assert text == text.strip(), f"{code}.{name} starts or ends with blank space"


def test_sections_are_in_code_order_after_the_intro() -> None:
    text = render(INTRO.read_text("utf-8"))
    heads = re.findall(r"^## (MB\d{3}) (\S+)$", text, re.M)
    assert heads == [(code, RULES[code].name) for code in ALL_CODES]
    assert text.index(INTRO.read_text("utf-8").strip()) < text.index("## MB000 ")


def test_check_passes_on_the_generated_file_and_fails_on_a_stale_one(tmp_path: Path) -> None:
    ok = subprocess.run(
        [sys.executable, str(SCRIPT), "--check"], capture_output=True, text=True, check=False
    )
    assert ok.returncode == 0, ok.stderr
    stale = tmp_path / "rules.md"
    stale.write_text(DOCS.read_text("utf-8").replace("**Severity:** error", "**Severity:** ", 1))
    bad = subprocess.run(
        [sys.executable, str(SCRIPT), "--check", "--output", str(stale)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert bad.returncode == 1
    assert "is stale" in bad.stderr and "python3 scripts/rules_doc.py" in bad.stderr
