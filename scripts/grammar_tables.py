"""Writes server/fanuc_macro/syntax/grammar_tables.py: the grammar's LALR tables as data, so that
the parser starts without loading the grammar into Lark.

    python3 scripts/grammar_tables.py          # writes the module
    python3 scripts/grammar_tables.py --check  # exits 1, saying so, if the module is stale

Run it after editing the grammar (server/fanuc_macro/data/macro_b.lark) or the tables' format
(lalr_driver.TABLES_FORMAT); until then the parser builds the tables with Lark at each start,
and tests/test_lalr_driver.py fails. The package is read from this checkout's server/.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "server" / "fanuc_macro" / "syntax" / "grammar_tables.py"

HEADER = (
    '"""The LALR tables of the grammar (data/macro_b.lark) as data: what the parser\'s driver\n'
    "runs, without Lark loading the grammar at each start. Written by scripts/grammar_tables.py,\n"
    'not by hand; tests/test_lalr_driver.py fails when they are not what Lark builds from it."""\n'
    "\n"
    "from __future__ import annotations\n"
    "\n"
    "from typing import Any\n"
    "\n"
)


def _plain(data: Any) -> Any:
    """``data`` with Lark's Token names (str subclasses, which repr() writes as calls) as
    plain strings: equal to them, and what the module can hold."""
    if isinstance(data, dict):
        return {_plain(k): _plain(v) for k, v in data.items()}
    if isinstance(data, list | tuple):
        return type(data)(_plain(v) for v in data)
    if isinstance(data, str) and type(data) is not str:
        return str(data)
    return data


def module_text() -> str:
    sys.path.insert(0, str(ROOT / "server"))
    from fanuc_macro.syntax.lalr_driver import lalr_tables
    from fanuc_macro.syntax.parser import grammar_crc32, grammar_lark

    tables: dict[str, Any] = _plain(lalr_tables(grammar_lark()))
    body = (
        f"GRAMMAR_CRC32 = {grammar_crc32()!r}\n\n\n"
        "def tables() -> dict[str, Any]:\n"
        '    """The tables, built at each call: the parser converts them once, and a module-level\n'
        '    dict would be kept (and could be changed) for the whole process."""\n'
        f"    return {tables!r}\n"
    )
    formatted = subprocess.run(
        [sys.executable, "-m", "ruff", "format", "--stdin-filename", str(OUTPUT), "-"],
        input=HEADER + body,
        capture_output=True,
        text=True,
        check=True,
        cwd=ROOT,
    )
    return formatted.stdout


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 if the module is stale")
    args = parser.parse_args(argv)
    text = module_text()
    if args.check:
        if not OUTPUT.exists() or OUTPUT.read_text("utf-8") != text:
            print(f"{OUTPUT.relative_to(ROOT)} is stale: run python3 scripts/grammar_tables.py")
            return 1
        return 0
    OUTPUT.write_text(text, "utf-8")
    print(f"wrote {OUTPUT.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
