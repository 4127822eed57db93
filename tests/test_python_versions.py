"""What the package does differently on the Python versions it declares (3.10 and later): where
it uses what came with 3.11, it has a way that works on 3.10 too, and the two agree. CI runs
this file, the CLI's, the language server's and the debug adapter's on the oldest and newest
interpreter it has (.ci/run)."""

from __future__ import annotations

import importlib
import pkgutil
import re
import sys
import weakref
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import fanuc_macro
from fanuc_macro.lazy_regex import LazyPattern
from fanuc_macro.line_maps import line_diff
from fanuc_macro.syntax.lines import cut_comments, decode_bytes, split_lines
from fanuc_macro.syntax.parser import (
    PLAIN_BLOCK_PATTERN,
    parse_text,
    without_possessive_repeats,
)
from fanuc_macro.syntax.tree import Document

ROOT = Path(__file__).resolve().parents[1]
CORPUS = ROOT.parent / "shared" / "corpus"
PROGRAMS = [
    *sorted((ROOT / "tests" / "fixtures" / "seeds").glob("*.nc")),
    *sorted((ROOT / "samples").glob("*.nc")),
    *(sorted(p for p in CORPUS.iterdir() if p.is_file()) if CORPUS.is_dir() else []),
]

GREEDY = re.compile(without_possessive_repeats(PLAIN_BLOCK_PATTERN))
needs_possessive = pytest.mark.skipif(
    sys.version_info < (3, 11), reason="Python 3.10's re has no possessive repeats to compare"
)


def _possessive() -> re.Pattern[str]:
    return re.compile(PLAIN_BLOCK_PATTERN)


def _lazy_patterns(value: object, found: list[LazyPattern], depth: int = 0) -> None:
    """The LazyPatterns a module's global holds, in containers and class attributes."""
    if isinstance(value, LazyPattern):
        found.append(value)
    elif depth < 4 and isinstance(value, (tuple, list, set, frozenset)):
        for item in value:
            _lazy_patterns(item, found, depth + 1)
    elif depth < 4 and isinstance(value, dict):
        for item in value.values():
            _lazy_patterns(item, found, depth + 1)
    elif depth == 0 and isinstance(value, type):
        for item in vars(value).values():
            _lazy_patterns(item, found, depth + 1)


def test_every_module_imports_and_every_regex_compiles() -> None:
    # A module's regexes compile when it is imported; the lazy ones, only on the texts that need
    # them (Python 3.10's re has no possessive repeats or atomic groups).
    names = [m.name for m in pkgutil.walk_packages(fanuc_macro.__path__, "fanuc_macro.")]
    lazy: list[LazyPattern] = []
    for name in names:
        if not name.endswith("__main__"):
            for value in vars(importlib.import_module(name)).values():
                _lazy_patterns(value, lazy)
    assert len(names) > 50 and len(lazy) > 30
    for pattern in lazy:
        assert pattern.compiled.pattern == pattern.pattern


def test_the_greedy_plain_block_pattern_has_no_possessive_repeat_left() -> None:
    assert PLAIN_BLOCK_PATTERN.count("+") > GREEDY.pattern.count("+")
    assert not re.search(r"[*+?}]\+", GREEDY.pattern.replace("[-+]", ""))
    assert GREEDY.fullmatch("G01X10.Z-2.5F.2 ")  # compiles on 3.10, and reads a block


@needs_possessive
def test_the_plain_block_patterns_agree_on_every_line_of_the_programs() -> None:
    possessive = _possessive()
    read = 0
    for path in PROGRAMS:
        for text in split_lines(decode_bytes(path.read_bytes()).text):
            code = cut_comments(text).code
            expected = possessive.fullmatch(code) is not None
            assert (GREEDY.fullmatch(code) is not None) == expected, (path.name, code)
            read += expected
    assert read > 100  # plain blocks among them


@needs_possessive
def test_the_plain_block_patterns_agree_on_edge_cases() -> None:
    possessive = _possessive()
    for code in [
        "G01X123456789012",
        "G01X1234567890123",
        "X1.2.3",
        "X.",
        "X.5",
        "X5.",
        "X-.5 Z+1",
        "X1 \t",
        "X1  Y",
        "X--1",
        "O1000",
        "N10G01",
        "G01X1#2",
        "",
    ]:
        assert (GREEDY.fullmatch(code) is None) == (possessive.fullmatch(code) is None), code


@needs_possessive
@settings(max_examples=400, deadline=None)
@given(st.text(alphabet="GXZFNO0123456789.-+ \t#", max_size=30))
def test_the_plain_block_patterns_agree_on_any_text(code: str) -> None:
    assert (GREEDY.fullmatch(code) is None) == (_possessive().fullmatch(code) is None)


def test_a_document_is_weakly_referable_and_keeps_its_slots() -> None:
    old = parse_text("G00X1.\nG01Z-2.F.2\n", "file:///o1.nc")
    new = parse_text("G00X1.\nG01Z-3.F.2\n", "file:///o1.nc")
    assert not hasattr(old, "__dict__") and isinstance(old, Document)
    assert len(old.blocks) == len(new.blocks) == 2
    ref = weakref.ref(new)
    assert ref() is new
    # The cache of line diffs holds the versions by weak reference: the same pair, the same diff.
    assert line_diff(old, new) is line_diff(old, new)
    del new
    assert ref() is None
