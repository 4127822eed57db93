"""The analysis database: tables per database, the active one per thread and context, what
closing a document frees."""

from __future__ import annotations

import contextvars
import threading

from fanuc_macro import database
from fanuc_macro.database import Database, TableKey, current

NAMES: TableKey[str, int] = TableKey("tests.names")
BY_URI: TableKey[str, list[int]] = TableKey("tests.by_uri", per_document=True)


def test_each_database_has_its_own_tables() -> None:
    a, b = Database(), Database()
    a.table(NAMES)["x"] = 1
    assert a.table(NAMES) == {"x": 1}
    assert a.table(NAMES) is a.table(NAMES)  # made once, then the same dict
    assert b.table(NAMES) == {}
    assert a.tables() == {"tests.names": 1}


def test_keys_compare_by_identity() -> None:
    db = Database()
    other: TableKey[str, int] = TableKey("tests.names")  # same name, another table
    db.table(NAMES)["x"] = 1
    assert db.table(other) == {}


def test_active_nests_and_restores() -> None:
    outer, inner = Database(), Database()
    assert current() is database.default()
    with outer.active() as active:
        assert active is outer
        assert current() is outer
        with inner.active():
            assert current() is inner
        assert current() is outer
    assert current() is database.default()


def test_active_is_restored_after_an_exception() -> None:
    db = Database()
    try:
        with db.active():
            raise ValueError
    except ValueError:
        pass
    assert current() is database.default()


def test_a_thread_does_not_inherit_the_active_database() -> None:
    db = Database()
    seen: list[Database] = []
    with db.active():
        thread = threading.Thread(target=lambda: seen.append(current()))
        thread.start()
        thread.join()
        copied = contextvars.copy_context()
        carried = threading.Thread(target=lambda: seen.append(copied.run(current)))
        carried.start()
        carried.join()
    assert seen == [database.default(), db]


def test_threads_have_their_own_active_database() -> None:
    first, second = Database(), Database()
    ready = threading.Barrier(2)
    seen: dict[str, Database] = {}

    def run(name: str, db: Database) -> None:
        with db.active():
            ready.wait()  # both are inside active() at once
            seen[name] = current()
            ready.wait()

    threads = [
        threading.Thread(target=run, args=("first", first)),
        threading.Thread(target=run, args=("second", second)),
    ]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert seen == {"first": first, "second": second}
    assert current() is database.default()


def test_close_document_frees_the_per_document_tables() -> None:
    db = Database()
    db.table(BY_URI)["file:///a.nc"] = [1]
    db.table(BY_URI)["file:///b.nc"] = [2]
    db.table(NAMES)["file:///a.nc"] = 3  # not per document: kept
    db.close_document("file:///a.nc")
    assert db.table(BY_URI) == {"file:///b.nc": [2]}
    assert db.table(NAMES) == {"file:///a.nc": 3}
    db.close_document("file:///never-opened.nc")


def test_forget_drops_everything() -> None:
    db = Database()
    db.table(NAMES)["x"] = 1
    table = db.table(BY_URI)
    table["u"] = [1]
    db.forget()
    assert db.tables() == {}
    assert db.table(NAMES) == {}
    assert db.table(BY_URI) is not table


def test_the_default_database_serves_code_outside_any_workspace() -> None:
    assert current() is database.default()
    table = current().table(NAMES)
    assert database.default().table(NAMES) is table


def test_tables_made_at_once_on_two_threads_are_one() -> None:
    db = Database()
    key: TableKey[int, int] = TableKey("tests.race")
    start = threading.Barrier(8)
    tables: list[dict[int, int]] = []

    def make() -> None:
        start.wait()
        tables.append(db.table(key))

    threads = [threading.Thread(target=make) for _ in range(8)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert all(table is tables[0] for table in tables)
