"""The cache of generated class code (code_cache.py): a second start compiles none of what the
first compiled, builds the same classes, and a bad file only means compiling again."""

from __future__ import annotations

import builtins
import dataclasses
import json
import marshal
import os
import stat
import subprocess
import sys
from pathlib import Path
from types import CodeType

import attr._make
import pytest

from fanuc_macro import code_cache
from fanuc_macro.code_cache import CodeCache, Key, cache_file

ROOT = Path(__file__).resolve().parents[1]
SMALL = ROOT / "tests" / "fixtures" / "seeds" / "o2_arc_thread_roughing.nc"

# What a process reports of its cache: the sources it compiled, those it used in all.
REPORT = (
    "import json\n"
    "from fanuc_macro import code_cache\n"
    "cache = code_cache.installed_code_cache()\n"
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


# Loading a file runs its code: only a file this user wrote, unchanged, is read.

DETAIL = (
    "import json\n"
    "from fanuc_macro import code_cache\n"
    "cache = code_cache.installed_code_cache()\n"
    "print(json.dumps(None if cache is None else {'compiled': cache.compiled,"
    " 'used': len(cache.used), 'loaded': cache.loaded, 'rejected': cache.rejected,"
    " 'writes': cache.path is not None}))\n"
)
OTHER_USER = 12345


def _check_in(directory: Path) -> tuple[str, dict[str, object]]:
    """The JSON output of a check of the seed, and what the process reports of its cache."""
    env = {**os.environ, "FANUC_MACRO_CODE_CACHE": str(directory)}
    done = subprocess.run(
        [sys.executable, "-c", _check(SMALL) + DETAIL],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    output, detail = done.stdout.splitlines()[-2:]
    report: dict[str, object] = json.loads(detail)
    return output, report


@pytest.fixture(scope="module")
def expected_output(tmp_path_factory: pytest.TempPathFactory) -> str:
    """The check's output, and a file the package wrote, beside it."""
    directory = tmp_path_factory.mktemp("written")
    output, report = _check_in(directory)
    assert report["loaded"] == 0 and report["rejected"] is None
    return output


def _written(tmp_path: Path) -> bytes:
    directory = tmp_path / "written"
    _check_in(directory)
    return cache_file(directory, "cli").read_bytes()


def _poisoned(data: bytes, marker: Path) -> dict[Key, CodeType]:
    """The file's code, each piece made to create ``marker`` before doing what it did."""
    known = code_cache.decode(data)
    assert isinstance(known, dict) and known
    poison = f"open({str(marker)!r}, 'a').close()\n"
    return {
        key: builtins.compile(poison + key[0], key[1], key[2], key[3], dont_inherit=True)
        for key in known
    }


def _assert_ignored(directory: Path, marker: Path, expected: str) -> dict[str, object]:
    output, report = _check_in(directory)
    assert not marker.exists()
    assert output == expected
    assert report["loaded"] == 0 and report["compiled"] == report["used"]
    assert report["rejected"]
    return report


def test_the_poisoned_code_would_run_from_a_file_the_user_wrote(
    tmp_path: Path, expected_output: str
) -> None:
    """What the tests below keep out: the digest is no signature, whoever writes the file can
    write a digest that matches."""
    marker = tmp_path / "marker"
    path = cache_file(tmp_path, "cli")
    path.write_bytes(code_cache.encode(_poisoned(_written(tmp_path), marker)))
    path.chmod(0o600)
    output, report = _check_in(tmp_path)
    assert marker.exists() and output == expected_output
    assert report["loaded"] and report["rejected"] is None


def test_a_file_whose_content_was_altered_is_not_run(tmp_path: Path, expected_output: str) -> None:
    marker = tmp_path / "marker"
    data = _written(tmp_path)
    header = data[: len(code_cache.MARK) + code_cache.DIGEST_SIZE]  # the digest of the original
    path = cache_file(tmp_path, "cli")
    path.write_bytes(header + marshal.dumps(_poisoned(data, marker)))
    path.chmod(0o600)
    report = _assert_ignored(tmp_path, marker, expected_output)
    assert "digest" in str(report["rejected"])
    assert code_cache.decode(path.read_bytes())  # written anew, by the package


def test_a_file_owned_by_another_user_is_not_run(tmp_path: Path, expected_output: str) -> None:
    marker = tmp_path / "marker"
    path = cache_file(tmp_path, "cli")
    path.write_bytes(code_cache.encode(_poisoned(_written(tmp_path), marker)))
    path.chmod(0o600)
    os.chown(path, OTHER_USER, OTHER_USER)
    report = _assert_ignored(tmp_path, marker, expected_output)
    assert "owned by another user" in str(report["rejected"])


def test_a_file_others_can_write_is_not_run(tmp_path: Path, expected_output: str) -> None:
    marker = tmp_path / "marker"
    path = cache_file(tmp_path, "cli")
    path.write_bytes(code_cache.encode(_poisoned(_written(tmp_path), marker)))
    path.chmod(0o666)
    report = _assert_ignored(tmp_path, marker, expected_output)
    assert "others can write" in str(report["rejected"])
    assert stat.S_IMODE(path.stat().st_mode) == 0o600  # written anew, for the user only


def test_a_file_in_a_directory_others_can_write_is_not_run(
    tmp_path: Path, expected_output: str
) -> None:
    """Without the sticky bit, another user could have put the file there under the user's
    name (renamed the user's own away): it is not read, nor written."""
    marker = tmp_path / "marker"
    shared = tmp_path / "shared"
    shared.mkdir()
    path = cache_file(shared, "cli")
    data = code_cache.encode(_poisoned(_written(tmp_path), marker))
    path.write_bytes(data)
    path.chmod(0o600)
    shared.chmod(0o777)
    report = _assert_ignored(shared, marker, expected_output)
    assert "directory others can write" in str(report["rejected"])
    assert report["writes"] is False and path.read_bytes() == data


def test_a_file_in_a_directory_owned_by_another_user_is_not_run(
    tmp_path: Path, expected_output: str
) -> None:
    marker = tmp_path / "marker"
    theirs = tmp_path / "theirs"
    theirs.mkdir()
    path = cache_file(theirs, "cli")
    path.write_bytes(code_cache.encode(_poisoned(_written(tmp_path), marker)))
    path.chmod(0o600)
    os.chown(theirs, OTHER_USER, OTHER_USER)
    report = _assert_ignored(theirs, marker, expected_output)
    assert "directory owned by another user" in str(report["rejected"])


def test_a_sticky_shared_directory_keeps_the_users_own_file(
    tmp_path: Path, expected_output: str
) -> None:
    """As in /tmp: others may write there, but neither replace nor rename the user's file."""
    sticky = tmp_path / "sticky"
    sticky.mkdir()
    sticky.chmod(0o1777)
    first_output, first = _check_in(sticky)
    assert first["writes"] is True and first["compiled"] == first["used"]
    output, second = _check_in(sticky)
    assert output == first_output == expected_output
    assert second["rejected"] is None and second["compiled"] == 0
    assert second["loaded"] == second["used"] == first["used"]


def test_a_truncated_file_is_compiled_again(tmp_path: Path, expected_output: str) -> None:
    data = _written(tmp_path)
    path = cache_file(tmp_path, "cli")
    path.write_bytes(data[: len(data) // 2])
    path.chmod(0o600)
    report = _assert_ignored(tmp_path, tmp_path / "marker", expected_output)
    assert "digest" in str(report["rejected"])
    output, again = _check_in(tmp_path)  # the file written anew is read
    assert output == expected_output
    assert again["compiled"] == 0 and again["loaded"] == report["used"]


def test_a_second_start_loads_from_the_file(tmp_path: Path, expected_output: str) -> None:
    old = os.umask(0)  # the file is the user's alone whatever the umask
    try:
        first_output, first = _check_in(tmp_path)
    finally:
        os.umask(old)
    assert stat.S_IMODE(cache_file(tmp_path, "cli").stat().st_mode) == 0o600
    output, second = _check_in(tmp_path)
    assert output == first_output == expected_output
    assert first["loaded"] == 0 and first["compiled"] == first["used"]
    assert second["compiled"] == 0 and second["loaded"] == second["used"] == first["used"]


def test_the_owner_is_compared_with_the_effective_user(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = cache_file(tmp_path, "cli")
    known = {("x = 1\n", "<x>", "exec", 0): builtins.compile("x = 1\n", "<x>", "exec")}
    path.write_bytes(code_cache.encode(known))
    path.chmod(0o600)
    os.chown(path, OTHER_USER, OTHER_USER)
    assert code_cache._read(path)[0] == {}
    monkeypatch.setattr(os, "geteuid", lambda: OTHER_USER)
    assert code_cache._read(path) == (known, None, True)


def test_a_fifo_in_the_files_place_is_refused_without_blocking(tmp_path: Path) -> None:
    os.mkfifo(cache_file(tmp_path, "cli"), 0o600)
    known, rejected, writable = code_cache._read(cache_file(tmp_path, "cli"))
    assert known == {} and "not a regular file" in str(rejected) and writable


def test_a_file_of_another_version_of_the_package_is_not_read(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = cache_file(tmp_path, "cli")
    known = {("x = 1\n", "<x>", "exec", 0): builtins.compile("x = 1\n", "<x>", "exec")}
    path.write_bytes(code_cache.encode(known))
    path.chmod(0o600)
    assert code_cache._read(path)[0] == known
    monkeypatch.setattr(code_cache, "DIGEST_KEY", b"another version")
    assert code_cache._read(path)[0] == {}


def test_a_file_someone_put_in_the_place_of_the_temporary_one_is_left_alone(
    tmp_path: Path,
) -> None:
    path = cache_file(tmp_path, "cli")
    theirs = path.with_name(f"{path.name}.{os.getpid()}.tmp")
    theirs.write_bytes(b"theirs")
    cache = CodeCache(path, {})
    cache.code("x = 1\n", "<x>", "exec", 0)
    assert cache.save() is False  # not written through it, and no error
    assert theirs.read_bytes() == b"theirs" and not path.exists()
