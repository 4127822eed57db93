"""The cache of generated class code (code_cache.py): a second start compiles none of what the
first compiled, builds the same classes, and a bad file only means compiling again."""

from __future__ import annotations

import builtins
import dataclasses
import json
import os
import subprocess
import sys
from pathlib import Path

import attr._make
import pytest

from fanuc_macro import code_cache
from fanuc_macro.code_cache import CodeCache, cache_file

ROOT = Path(__file__).resolve().parents[1]
SMALL = ROOT / "tests" / "fixtures" / "seeds" / "o2_arc_thread_roughing.nc"

# What a process reports of its cache: the sources it compiled, those it used in all.
REPORT = (
    "import json\n"
    "from fanuc_macro import code_cache\n"
    "cache = code_cache._installed\n"
    "print(json.dumps(None if cache is None else [cache.compiled, len(cache.used)]))\n"
)


def _run(script: str, directory: str) -> list[int] | None:
    env = {**os.environ, "FANUC_MACRO_CODE_CACHE": directory}
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, env=env, timeout=120
    )
    assert done.returncode == 0, done.stderr
    report: list[int] | None = json.loads(done.stdout.splitlines()[-1])
    return report


def _check(program: Path) -> str:
    """A check of the program, its JSON output printed on one line."""
    return (
        "import contextlib, io, json\n"
        "from fanuc_macro.cli import main\n"
        "with contextlib.redirect_stdout(io.StringIO()) as out:\n"
        f"    main(['check', '--format', 'json', {str(program)!r}])\n"
        "print(json.dumps(out.getvalue()))\n"
    )


def _check_then_report(program: Path) -> str:
    return _check(program) + REPORT


def test_a_second_check_compiles_none_of_the_class_code(tmp_path: Path) -> None:
    first = _run(_check_then_report(SMALL), str(tmp_path))
    assert first is not None
    compiled, used = first
    assert compiled == used > 50  # the package's dataclasses, all compiled the first time
    assert cache_file(tmp_path, "cli").is_file()
    second = _run(_check_then_report(SMALL), str(tmp_path))
    assert second == [0, used]


def test_a_check_reports_the_same_with_the_cache_and_without(tmp_path: Path) -> None:
    script = _check(SMALL)
    outputs = set()
    for directory in (str(tmp_path), str(tmp_path), "0"):  # writes it, reads it, none
        env = {**os.environ, "FANUC_MACRO_CODE_CACHE": directory}
        done = subprocess.run(
            [sys.executable, "-c", script], capture_output=True, text=True, env=env, timeout=120
        )
        assert done.returncode == 0, done.stderr
        outputs.add(done.stdout)
    assert len(outputs) == 1 and "MB" in outputs.pop()  # the seed's findings, alike


def test_a_second_server_start_compiles_at_most_the_sources_that_change(tmp_path: Path) -> None:
    start = "import fanuc_macro.lsp.server\nfrom fanuc_macro.code_cache import save_code_cache\n"
    first = _run(start + "save_code_cache()\n" + REPORT, str(tmp_path))
    assert first is not None and first[0] == first[1] > 500  # lsprotocol's attrs classes
    second = _run(start + REPORT, str(tmp_path))
    assert second is not None
    assert second[1] == first[1]
    assert second[0] <= code_cache.CHANGING_SOURCES


def test_the_cache_is_off_when_the_environment_says_so(tmp_path: Path) -> None:
    assert _run(_check_then_report(SMALL), "0") is None
    assert not any(tmp_path.iterdir())


def test_a_corrupt_file_is_compiled_again_and_written_anew(tmp_path: Path) -> None:
    path = cache_file(tmp_path, "cli")
    path.write_bytes(b"\x00not marshal data")
    report = _run(_check_then_report(SMALL), str(tmp_path))
    assert report is not None and report[0] == report[1] > 50
    assert _run(_check_then_report(SMALL), str(tmp_path)) == [0, report[1]]


def test_cached_code_is_the_code_the_builder_would_compile(tmp_path: Path) -> None:
    """The same code objects as the builtin gives in the builder's module: the future flags it
    compiles with (attrs' module has ``from __future__ import annotations``) included."""
    cache = CodeCache(None, {})
    shadow = code_cache._compile_through(cache, code_cache._future_flags(attr._make))
    source = "def f(x: Undefined) -> None:\n    pass\n"
    expected = builtins.compile(
        source, "<f>", "exec", code_cache._future_flags(attr._make), dont_inherit=True
    )
    code = shadow(source, "<f>", "exec")
    assert code == expected and cache.compiled == 1
    assert shadow(source, "<f>", "exec") is code and cache.compiled == 1  # found, not compiled
    namespace: dict[str, object] = {}
    builtins.exec(code, namespace)
    function: object = namespace["f"]
    assert function.__annotations__ == {"x": "Undefined", "return": "None"}  # type: ignore[attr-defined]


def test_dataclasses_built_through_the_cache_behave_alike() -> None:
    cache = CodeCache(None, {})
    shadow_exec = code_cache._exec_through(cache, code_cache._future_flags(dataclasses))
    real = dataclasses.__dict__.get("exec")
    dataclasses.exec = shadow_exec  # type: ignore[attr-defined]
    try:

        @dataclasses.dataclass(frozen=True, order=True)
        class Pass:
            depth: float
            x: float = 0.0

        compiled = cache.compiled

        @dataclasses.dataclass(frozen=True, order=True)
        class Same:  # the same generated sources: found, not compiled again
            depth: float
            x: float = 0.0

    finally:
        if real is None:
            del dataclasses.exec  # type: ignore[attr-defined]
        else:
            dataclasses.exec = real  # type: ignore[attr-defined]
    # A source per method (__init__, __repr__, __eq__, the orderings...), and from Python 3.13
    # on one source for all the methods of a class.
    assert compiled >= (1 if sys.version_info >= (3, 13) else 4)
    assert cache.compiled == compiled == len(cache.used)
    assert Pass(0.5) == Pass(0.5, 0.0) and Pass(0.5) < Pass(0.6)
    assert repr(Same(1.0, 2.0)).endswith("Same(depth=1.0, x=2.0)")
    assert hash(Pass(0.5)) == hash(Pass(0.5))


def test_no_home_directory_means_no_cache(monkeypatch: pytest.MonkeyPatch) -> None:
    def no_home() -> Path:
        raise RuntimeError("Could not determine home directory.")

    monkeypatch.delenv("FANUC_MACRO_CODE_CACHE", raising=False)
    monkeypatch.delenv("XDG_CACHE_HOME", raising=False)
    monkeypatch.delenv("LOCALAPPDATA", raising=False)
    monkeypatch.setattr(Path, "home", no_home)
    assert code_cache.cache_directory() is None


def _message(payload: dict[str, object]) -> bytes:
    body = json.dumps(payload).encode()
    return f"Content-Length: {len(body)}\r\n\r\n".encode() + body


def test_a_server_session_over_stdio_writes_the_cache_once(tmp_path: Path) -> None:
    """initialize, initialized, shutdown and exit, as an editor sends them: the first session
    writes the server's file, the second finds everything in it and leaves it alone."""
    session = b"".join(
        _message(m)
        for m in (
            {"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": {"capabilities": {}}},
            {"jsonrpc": "2.0", "method": "initialized", "params": {}},
            {"jsonrpc": "2.0", "id": 2, "method": "shutdown"},
            {"jsonrpc": "2.0", "method": "exit"},
        )
    )
    env = {**os.environ, "FANUC_MACRO_CODE_CACHE": str(tmp_path)}
    path = cache_file(tmp_path, "server")
    written = []
    for _ in range(2):
        done = subprocess.run(
            [sys.executable, "-m", "fanuc_macro.lsp.server"],
            input=session,
            capture_output=True,
            env=env,
            timeout=120,
        )
        assert done.returncode == 0, done.stderr
        assert b'"id": 2' in done.stdout or b'"id":2' in done.stdout  # shutdown answered
        written.append(path.read_bytes())
    assert len(written[0]) > 100_000
    assert written[1] == written[0]
