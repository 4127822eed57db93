"""docs/rules.md is generated from the RuleDoc beside each rule and docs/rules-intro.md.

A rule's documentation is a ``RuleDoc`` constant (``MB101_DOC``) beside the function that finds
the rule; ``python3 scripts/rules_doc.py`` writes docs/rules.md from them.
These tests fail when the file is stale or a rule lacks a part; tests/test_rules.py reads the
generated file (a section per code, its severity, an example that triggers the rule).
docs/rules.zh-cn.md is the same page in Chinese, from the ``rules_doc`` catalogue; the language
server links a Chinese reader's diagnostics to it.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest
from lsprotocol import types
from pytest_lsp import LanguageClient

from fanuc_macro.analysis import RULE_DOCS, RULES
from fanuc_macro.rules_doc import PARTS, part_texts, render, rule_url, untranslated_parts
from test_lsp import client, diagnostics, open_seed, start

__all__ = ["client"]

ROOT = Path(__file__).resolve().parents[1]
INTRO = ROOT / "docs" / "rules-intro.md"
DOCS = ROOT / "docs" / "rules.md"
CHINESE = ROOT / "docs" / "rules.zh-cn.md"
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


def test_the_chinese_page_is_what_the_generator_writes() -> None:
    assert CHINESE.read_text("utf-8") == render(INTRO.read_text("utf-8"), "zh-cn"), (
        "docs/rules.zh-cn.md is stale: run `python3 scripts/rules_doc.py` and commit it"
    )


def test_the_chinese_page_has_every_rules_section_under_the_same_heading() -> None:
    text = CHINESE.read_text("utf-8")
    heads = re.findall(r"^## (MB\d{3}) (\S+)$", text, re.M)
    assert heads == [(code, RULES[code].name) for code in ALL_CODES]
    for code in ALL_CODES:
        body = text.split(f"## {code} {RULES[code].name}\n", 1)[1].split("\n## ", 1)[0]
        blocks = sum(text.count("```") for text in part_texts(RULE_DOCS[code]).values())
        assert body.count("```") == blocks, f"{code}: its code blocks are not the English page's"


# The codes whose documentation is not yet all in Chinese: empty when the catalogue is done.
# A code translated must leave this list (the test fails until it does).
NOT_YET_IN_CHINESE: list[str] = []


def test_every_rules_documentation_is_said_in_chinese() -> None:
    left = [code for code in ALL_CODES if untranslated_parts(code)]
    assert left == NOT_YET_IN_CHINESE, {code: untranslated_parts(code) for code in left}


def test_a_chinese_reader_is_linked_to_the_chinese_page() -> None:
    name = RULES["MB101"].name
    assert rule_url("MB101").endswith(f"/docs/rules.md#mb101-{name}")
    for locale in ("zh-cn", "zh-tw"):
        assert rule_url("MB101", locale).endswith(f"/docs/rules.zh-cn.md#mb101-{name}")
    assert rule_url("MB101", "ja") == rule_url("MB101")


async def test_the_server_links_a_chinese_clients_diagnostics_to_the_chinese_page(
    client: LanguageClient,
) -> None:
    await start(client, locale="zh-cn")
    uri = open_seed(client, "o2_arc_thread_roughing.nc")
    found = await diagnostics(client, uri, lambda d: any(x.code == "MB601" for x in d))
    for diag in found:
        assert diag.code_description is not None
        assert diag.code_description.href == rule_url(str(diag.code), "zh-cn"), diag
    assert "/docs/rules.zh-cn.md#mb601-" in rule_url("MB601", "zh-cn")
    # The setting overrides the client's locale: the links are the English page's again.
    client.workspace_did_change_configuration(
        types.DidChangeConfigurationParams(
            settings={"fanuc-macro": {"language": "en", "analysis": {"debounceMs": 20}}}
        )
    )
    found = await diagnostics(
        client,
        uri,
        lambda d: (
            bool(d)
            and all(x.code_description and "/rules.md#" in x.code_description.href for x in d)
        ),
    )
    assert all(x.code_description for x in found)
