"""What a start imports, not how long it takes: each command loads only the modules it uses
(the figures are in docs/benchmarks.md, from bench/bench_startup.py)."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from fanuc_macro.lazy_regex import LazyPattern

SMALL_PROGRAM = "%\nO1000\n#1=10.\nWHILE[#1GT0]DO1\n#1=#1-1.\nEND1\nG0 X#1\nM30\n%\n"
# The same with blocks the grammar rejects (a character no word takes, a missing bracket): the
# parser's own error types tell them, without Lark.
BAD_PROGRAM = SMALL_PROGRAM.replace("G0 X#1", "G0 X#1 ?\n#2=[#1+1\nIF[#1 GT 0 GOTO5")

# Heavy or unrelated to checking a file: the thread generator, the language server's protocol
# packages, numpy, Lark (the parser runs the grammar's shipped tables with its own driver), the
# `regex` package Lark would load for an option the grammar does not use, logging (imported
# when something fails or a log is asked for) and hashlib (OpenSSL; the grammar's check is a
# CRC).
NOT_FOR_CHECK = (
    "numpy",
    "lark",
    "logging",
    "hashlib",
    "lsprotocol",
    "pygls",
    "cattrs",
    "regex",
    "fanuc_macro.lsp",
    "fanuc_macro.generators.thread_generator",
    "fanuc_macro.generators.arc_thread_generator",
    "fanuc_macro.generators.drum_groove_generator",
    "fanuc_macro.generators.thread_snippet",
)


def loaded_after(code: str, *args: str) -> set[str]:
    """The modules a new interpreter has loaded after running ``code``."""
    script = code + "\nimport json, sys\nprint(json.dumps(sorted(sys.modules)))\n"
    done = subprocess.run(
        [sys.executable, "-c", script, *args], capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr
    return set(json.loads(done.stdout.splitlines()[-1]))


@pytest.mark.parametrize(
    ("text", "status"), [(SMALL_PROGRAM, 0), (BAD_PROGRAM, 1)], ids=["clean", "rejected blocks"]
)
def test_check_of_a_small_file_loads_no_generator_server_lark_or_numpy(
    tmp_path: Path, text: str, status: int
) -> None:
    program = tmp_path / "o1000.nc"
    program.write_text(text)
    loaded = loaded_after(
        "import contextlib, io, sys\n"
        "from fanuc_macro.cli import main\n"
        "out = io.StringIO()\n"
        "with contextlib.redirect_stdout(out):\n"
        "    status = main(['check', sys.argv[1]])\n"
        f"assert status == {status}, status\n"
        f"assert ('MB001' in out.getvalue()) == {status == 1}, out.getvalue()\n",
        str(program),
    )
    assert "fanuc_macro.analysis" in loaded  # the check ran
    unexpected = {m for m in loaded if m in NOT_FOR_CHECK or m.split(".")[0] in NOT_FOR_CHECK}
    unexpected |= {m for m in loaded if m.startswith(("fanuc_macro.lsp.", "lsprotocol."))}
    assert not unexpected


def test_the_thread_command_still_loads_its_generator(tmp_path: Path) -> None:
    loaded = loaded_after(
        "import contextlib, io\n"
        "from fanuc_macro.cli import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    status = main(['thread', 'M50x3-5g6g', '--length', '30'])\n"
        "assert status == 0, status\n"
    )
    assert "fanuc_macro.generators.thread_generator" in loaded


def test_the_language_server_starts_without_the_thread_generator() -> None:
    loaded = loaded_after("import fanuc_macro.lsp.server\n")
    assert "pygls" in loaded and "fanuc_macro.lsp.engine" in loaded
    assert "fanuc_macro.generators.thread_generator" not in loaded
    assert "fanuc_macro.generators.thread_snippet" not in loaded
    # The arc-thread and drum-groove commands load their requests and generators when run.
    assert "fanuc_macro.generators.generator_requests" not in loaded
    assert "fanuc_macro.generators.arc_thread_generator" not in loaded
    assert "fanuc_macro.generators.drum_groove_generator" not in loaded
    assert "regex" not in loaded


def test_the_language_server_answers_initialize_before_loading_the_analysis() -> None:
    """The server's module and its `initialize` need the protocol, not the analysis: the
    syntax tree, the parser, the evaluator, the rules and the features are loaded by the worker
    afterwards (the settings need only the read limits)."""
    loaded = loaded_after(
        "from lsprotocol import types\n"
        "from fanuc_macro.lsp.server import create_server\n"
        "server = create_server()\n"
        "server.engine.configure({'analysis': {'debounceMs': 10}})\n"
    )
    later = {
        "fanuc_macro.analysis",
        "fanuc_macro.syntax.tree",
        "fanuc_macro.syntax.lines",
        "fanuc_macro.syntax.parser",
        "fanuc_macro.evaluator",
        "fanuc_macro.rules",
        "fanuc_macro.workspace",
        "fanuc_macro.lsp.features",
        "lark",
    }
    assert not later & loaded


def test_check_of_a_clean_file_compiles_no_regex_of_rejected_blocks_nor_the_grammar(
    tmp_path: Path,
) -> None:
    """The dialects' forms, the messages' regexes for rejected blocks and the other thread
    systems' forms are compiled when a text needs them; so are the lexer's master regexes, and
    the grammar is not loaded into Lark (its tables are shipped)."""
    program = tmp_path / "o1000.nc"
    program.write_text(SMALL_PROGRAM)
    script = (
        "import contextlib, io, json, sys\n"
        "from fanuc_macro.cli import main\n"
        "from fanuc_macro.lazy_regex import LazyPattern\n"
        "from fanuc_macro.syntax import dialects, parser\n"
        "from fanuc_macro.threads import designation\n"
        # The check parses with its workspace's parser (one per analysis database): the
        # parsers made during the check are the ones to look at.
        "made = []\n"
        "made_by = parser.BlockParser.__init__\n"
        "def recording(self, *args, **kwargs):\n"
        "    made_by(self, *args, **kwargs)\n"
        "    made.append(self)\n"
        "parser.BlockParser.__init__ = recording\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    status = main(['check', sys.argv[1]])\n"
        "assert made, 'the check made no parser'\n"
        "assert status == 0, status\n"
        "lazy = [p for table in (dialects._RAW_PATTERNS, dialects._PATTERNS,\n"
        "                        dialects._WEAK_PATTERNS, designation._NON_METRIC)\n"
        "        for p, *_ in table]\n"
        "lazy += [v for v in vars(parser).values() if isinstance(v, LazyPattern)]\n"
        "scanners = [m for p in made for m in p._table._scanners.values()]\n"
        "compiled = {id(m) for m in scanners if hasattr(m, '__self__')}\n"
        "lark = any('_lark' in vars(p) for p in made)\n"
        "print(json.dumps([len(lazy), [p.pattern for p in lazy if p._compiled],\n"
        "                  len(compiled), len({id(m) for m in scanners}), lark]))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script, str(program)], capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr
    found = json.loads(done.stdout.splitlines()[-1])
    count, compiled, scanners_compiled, scanners, lark_loaded = found
    assert count > 30 and compiled == []
    assert 0 < scanners_compiled < scanners / 2
    assert not lark_loaded  # the parser runs the shipped tables: no grammar loaded into Lark


def test_a_lazy_pattern_answers_as_the_compiled_one() -> None:
    lazy = LazyPattern(r"(?<![A-Z])N(\d+)", re.I)
    compiled = re.compile(r"(?<![A-Z])N(\d+)", re.I)
    text = "n10 G01 XN20 N30"
    assert lazy._compiled is None
    assert lazy.search(text, 1).span() == compiled.search(text, 1).span()
    assert lazy.match(text) is not None and lazy.match(text, 1) is None
    assert lazy.fullmatch("N7") is not None and lazy.fullmatch("N7", 0, 1) is None
    assert [m.span() for m in lazy.finditer(text)] == [m.span() for m in compiled.finditer(text)]
    assert lazy._compiled is compiled  # re's cache: the same pattern object
