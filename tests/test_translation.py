"""The words a user reads, in every language: the texts keep their English, the catalogues are
in step with the sources, each translation keeps its message's parameters and says the
glossary's terms (docs/glossary.md)."""

from __future__ import annotations

import pickle
import re
import string
import subprocess
import sys
from pathlib import Path

import pytest

from fanuc_macro.translation import Text, joined, read_po_text, render, tr, tr_n

ROOT = Path(__file__).resolve().parents[1]
LOCALE_DIR = ROOT / "server" / "fanuc_macro" / "data" / "locale"
GLOSSARY = ROOT / "docs" / "glossary.md"


def entries(directory: str, domain: str) -> dict[str, tuple[str, ...]]:
    return read_po_text((LOCALE_DIR / directory / "LC_MESSAGES" / f"{domain}.po").read_text())[0]


def all_ids(directory: str, domain: str) -> list[str]:
    from babel.messages.pofile import read_po

    path = LOCALE_DIR / directory / "LC_MESSAGES" / f"{domain}.po"
    with path.open("rb") as f:
        return [m.id if isinstance(m.id, str) else m.id[0] for m in read_po(f) if m.id]


def fields(template: str) -> set[str]:
    return {name for _text, name, _spec, _conv in string.Formatter().parse(template) if name}


def test_a_text_is_its_english() -> None:
    depth = tr("depth {depth:.3f} mm past {where}", depth=1.23456, where="N10")
    assert depth == "depth 1.235 mm past N10" and isinstance(depth, str)
    assert tr("{{#1}} is {value}", value=2) == "{#1} is 2"
    outer = tr("in {program}: {what}", program="O1", what=depth)
    assert outer == "in O1: depth 1.235 mm past N10"
    assert tr_n("{count} pass", "{count} passes", 1) == "1 pass"
    assert tr_n("{count} pass", "{count} passes", 3) == "3 passes"
    assert joined("; ", [depth, "plain"]) == "depth 1.235 mm past N10; plain"
    assert joined(", ", ["a", "b"]) == "a, b" and not isinstance(joined(", ", ["a"]), Text)
    copied = pickle.loads(pickle.dumps(outer))
    assert copied == outer and isinstance(copied, Text) and copied.template == outer.template


def test_a_text_is_said_in_the_users_language() -> None:
    chinese = entries("zh_CN", "messages")
    template = next(t for t, forms in chinese.items() if not fields(t) and forms[0])
    assert render(tr(template), "zh-cn") == chinese[template][0]
    assert render(tr(template), "zh-tw") == chinese[template][0]  # falls back
    assert render(tr(template), "en") == template
    listed = joined(", ", [tr(template), tr(template)])
    assert render(listed, "zh-cn") == f"{chinese[template][0]}，{chinese[template][0]}"
    assert render(joined("\n", [tr(template), "x"]), "zh-cn") == f"{chinese[template][0]}\nx"
    missing = tr("a text {value} no catalogue has", value=1.5)
    assert render(missing, "zh-cn") == "a text 1.5 no catalogue has"
    assert render("a plain str", "zh-cn") == "a plain str"


def test_the_catalogues_are_in_step_with_the_sources() -> None:
    done = subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "catalogues.py"), "--check"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 0, done.stdout + done.stderr


@pytest.mark.parametrize("directory", ["zh_CN", "ja"])
def test_a_translation_keeps_every_parameter(directory: str) -> None:
    for domain in ("messages", "rules_doc"):
        path = LOCALE_DIR / directory / "LC_MESSAGES" / f"{domain}.po"
        if not path.exists():
            continue
        for message_id, forms in entries(directory, domain).items():
            if domain == "messages":
                for form in forms:
                    assert fields(form) == fields(message_id), (message_id, form)
            else:  # the documentation's code blocks are program text, never translated
                blocks = re.findall(r"```.*?```", message_id, re.S)
                assert re.findall(r"```.*?```", forms[0], re.S) == blocks, message_id


def test_every_message_is_said_in_chinese() -> None:
    ids = all_ids("zh_CN", "messages")
    chinese = entries("zh_CN", "messages")
    untranslated = [i for i in ids if i not in chinese]
    assert not untranslated, f"{len(untranslated)} messages without Chinese: {untranslated[:5]}"


def glossary() -> list[tuple[str, str, str]]:
    rows = []
    for line in GLOSSARY.read_text("utf-8").splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 3 and cells[0] not in ("English", "") and not cells[0].startswith("-"):
            rows.append((cells[0], cells[1], cells[2]))
    return sorted(rows, key=lambda row: -len(row[0]))


def glossary_terms_missing(message_id: str, translation: str, column: int) -> list[str]:
    """The glossary's terms the English has and the translation does not say (a parameter's
    name is not English the user reads)."""
    english = re.sub(r"\{[^{}]*\}", " ", message_id)
    missing = []
    for row in glossary():
        pattern = re.compile(rf"(?<![\w-]){re.escape(row[0])}s?(?![\w-])", re.I)
        if pattern.search(english):
            english = pattern.sub(" ", english)  # a longer term's words are not a shorter's
            if row[column] not in translation:
                missing.append(row[0])
    return missing


def test_the_glossary_has_the_papers_terms() -> None:
    terms = {row[0]: row[1] for row in glossary()}
    for english, chinese in (("pitch", "螺距"), ("lead", "导程"), ("thread height", "牙高")):
        assert terms[english] == chinese
    assert glossary_terms_missing("the pitch diameter", "中径", 1) == []
    assert glossary_terms_missing("the pitch", "中径", 1) == ["pitch"]
    assert glossary_terms_missing("with {tool} at {lead}", "以 {tool}", 1) == []


@pytest.mark.parametrize(("directory", "column"), [("zh_CN", 1), ("ja", 2)])
def test_the_translations_say_the_glossarys_terms(directory: str, column: int) -> None:
    wrong = []
    for message_id, forms in entries(directory, "messages").items():
        missing = glossary_terms_missing(message_id, forms[0], column)
        if missing:
            wrong.append((message_id, missing))
    assert not wrong, f"{len(wrong)} translations without the glossary's terms: {wrong[:5]}"
