"""``fanuc-macro plot`` in the user's language: the drawing's texts (title, legend, axis
captions, notes, pass-map captions, tooltips) and what it says on stderr, with ``--lang`` or
``LANG``; the English drawing is the same as before."""

from __future__ import annotations

import html
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from fanuc_macro.ide.plot import text_width, wrap
from test_translation_fixtures import ENGLISH

SEEDS = Path(__file__).parent / "fixtures" / "seeds"
LOCALE_VARIABLES = ("LANGUAGE", "LC_ALL", "LC_MESSAGES", "LANG")
# What a person reads in a drawing: its texts and its tooltips.
_READ = re.compile(r"<(text|title|desc)\b[^>]*>(.*?)</\1>", re.S)


def _plot(
    tmp_path: Path, seed: str, *args: str, lang: str = "C"
) -> tuple[subprocess.CompletedProcess[str], str]:
    env = {k: v for k, v in os.environ.items() if k not in LOCALE_VARIABLES}
    env["LANG"] = lang
    env["PYTHONPATH"] = str(Path(__file__).parents[1] / "server")
    done = subprocess.run(
        [sys.executable, "-m", "fanuc_macro.cli", "plot", "-o", "-", str(SEEDS / seed), *args],
        cwd=tmp_path,
        env=env,
        encoding="utf-8",
        capture_output=True,
        timeout=300,
        check=False,
    )
    return done, done.stdout


def _read(svg: str) -> list[str]:
    return [html.unescape(m.group(2)) for m in _READ.finditer(svg)]


def _elements(svg: str) -> list[str]:
    """The drawing's elements without their texts and places: what it draws."""
    return re.findall(r'<(?:path|line|circle|rect|polyline|polygon)[^>]*data-kind="[^"]*"', svg)


@pytest.mark.parametrize("seed", ["o4009_external_m50x3.nc", "o1_radial_layers.nc"])
def test_plot_in_chinese_says_no_english_sentence(tmp_path: Path, seed: str) -> None:
    english, english_svg = _plot(tmp_path, seed)
    assert english.returncode == 0, english.stderr
    chinese, svg = _plot(tmp_path, seed, "--lang", "zh-cn")
    assert chinese.returncode == 0, chinese.stderr
    read = _read(svg)
    assert read and any("\u4e00" <= c <= "\u9fff" for text in read for c in text)
    assert [t for t in read if ENGLISH.search(t)] == []
    assert not any("…" in t for t in read)  # each caption's line fits: none is cut short
    assert [line for line in chinese.stderr.splitlines() if ENGLISH.search(line)] == []
    # The same drawing, said otherwise; LANG says the same as --lang; English as it was.
    assert _elements(svg) == _elements(english_svg)
    assert _plot(tmp_path, seed, lang="zh_CN.UTF-8")[1] == svg
    assert _plot(tmp_path, seed, "--lang", "en", lang="zh_CN.UTF-8")[1] == english_svg
    assert any(ENGLISH.search(t) for t in _read(english_svg))


def test_the_english_drawing_keeps_its_words(tmp_path: Path) -> None:
    _, svg = _plot(tmp_path, "o4009_external_m50x3.nc")
    read = _read(svg)
    assert "direction of travel" in read and "cycle time 10 min 1.3 s" in read
    assert any(t.startswith("X (mm") and "diameter" in t for t in read)
    assert "o4009_external_m50x3.nc (XZ, 1010 of 1011 moves drawn)" in read


def test_a_chinese_caption_breaks_between_characters_within_its_width() -> None:
    text = (
        "进刀：每刀在刀尖处画一个点（186 刀，位于 178 处（同一处的各刀画为一个点）），线为"
        "刀具的 60° 牙侧，阴影为基本牙槽（5H/8 = 1.624）；向下：深度（mm，半径值）"
    )
    lines = wrap(text, 300.0)
    assert len(lines) > 1 and "".join(lines).replace(" ", "") == text.replace(" ", "")
    assert all(text_width(line) <= 300.0 for line in lines)
    assert not any(line[0] in "，。；：、）" or line[-1] in "（" for line in lines)
    # English still breaks between words only.
    assert wrap("one two three four", 80.0) == ["one two", "three four"]
