"""With the editor in Chinese, every rule's fixture is said in Chinese: each diagnostic's
message, its related places' messages and its fixes' titles have a translation, and so has
every text they are made of; what fills them is numbers and program text, not English.

``ENGLISH`` finds an English sentence: three words of letters in a row. A parameter that holds
program text (a block, a comment as the program writes it) is named so (``block``,
``comment``, ``program_text``, ``..._text``) and is not looked at.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path

import pytest

from fanuc_macro.diagnostics import Diagnostic
from fanuc_macro.translation import Text, has_translation
from test_rules import FIXTURE_FILES, fixture_analysis

ENGLISH = re.compile(r"[A-Za-z]{2,}(?:[ ,;:'-]+[A-Za-z]{2,}){2,}")
PROGRAM_TEXT = re.compile(r"block|comment|program_text|.*_text")


def english_in(text: str, locale: str = "zh-cn") -> Iterator[str]:
    """The English a user would read in ``text`` said in ``locale``."""
    if not isinstance(text, Text):
        if ENGLISH.search(text):
            yield text
        return
    if not has_translation(text, locale) and ENGLISH.search(text.template):
        yield text.template
    for name, value in text.params.items():
        if isinstance(value, str) and not PROGRAM_TEXT.fullmatch(name):
            yield from english_in(value, locale)


def english_of(diagnostic: Diagnostic) -> list[str]:
    texts = [diagnostic.message, *(r.message for r in diagnostic.related)]
    texts += [f.title for f in diagnostic.fixes]
    return [found for text in texts for found in english_in(text)]


def test_english_is_found() -> None:
    from fanuc_macro.translation import tr

    assert list(english_in("GOTO 10 jumps out of the loop")) == ["GOTO 10 jumps out of the loop"]
    assert list(english_in("G92 X20.0 Z-30.0 F2.0")) == []
    made = tr(
        "no label {label} in the program {program}: {why}",
        label=10,
        program="O1",
        why="it was deleted",
    )
    assert list(english_in(made)) == [made.template, "it was deleted"]
    assert list(english_in(tr("{block}", block="(ROUGH THE THREAD)"))) == []


@pytest.mark.parametrize("path", FIXTURE_FILES, ids=lambda p: p.name)
def test_a_fixture_is_said_in_chinese(path: Path) -> None:
    analysis, _expected = fixture_analysis(path)
    english = {d.code: english_of(d) for d in analysis.diagnostics if english_of(d)}
    assert not english, f"English left in zh-cn: {english}"
