"""The analysis database: tables per database, the active one per thread and context, what
closing a document frees."""

from __future__ import annotations

import contextvars
import threading
from typing import Any

import pytest

from fanuc_macro import database
from fanuc_macro.database import Database, Derived, TableKey, current

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


# ---- derived per-document queries -----------------------------------------------------------


class _Doc:
    """A document's inputs, as a query reads them."""

    def __init__(self, index: object, read_to: int | None, facts_needed: bool = False) -> None:
        self.index = index
        self.read_to = read_to
        self.facts_needed = facts_needed


def _counting_query() -> tuple[Derived[_Doc, list[int]], list[_Doc]]:
    computed: list[_Doc] = []

    def compute(doc: _Doc) -> tuple[list[int], bool]:
        computed.append(doc)
        return [len(computed)], not doc.facts_needed

    query: Derived[_Doc, list[int]] = Derived(
        "tests.derived", lambda doc: (doc.index, doc.read_to), compute
    )
    return query, computed


def test_a_derived_value_is_computed_again_only_when_an_input_changed() -> None:
    query, computed = _counting_query()
    index = object()
    with Database().active():
        first = query("a", _Doc(index, None))
        assert query("a", _Doc(index, None)) is first  # the same inputs: kept
        assert query("b", _Doc(index, None)) is not first  # another document
        assert query("a", _Doc(index, 10)) is not first  # a number read changed
        assert query("a", _Doc(object(), 10)) is not first  # another index
        assert len(computed) == 4


def test_inputs_compare_by_identity_but_numbers_and_strings_by_value() -> None:
    query, computed = _counting_query()
    with Database().active():
        query("a", _Doc([1], 10**6 + 1))
        query("a", _Doc([1], int("1000001")))  # an equal list is another input
        assert len(computed) == 2
        same = [1]
        query("a", _Doc(same, int("1000001")))
        query("a", _Doc(same, int("1000001")))  # an equal int, another object: the same
        assert len(computed) == 3


def test_a_value_that_read_more_than_its_inputs_is_not_kept() -> None:
    query, computed = _counting_query()
    index = object()
    other = object()  # an index with a jump whose diagnostic reads the facts, say
    with Database().active():
        query("a", _Doc(index, None))
        query("a", _Doc(other, None, facts_needed=True))  # not kept, and the last one dropped
        query("a", _Doc(other, None, facts_needed=True))
        query("a", _Doc(index, None))
        assert len(computed) == 4


def test_derived_values_are_the_database_s_and_freed_with_the_document() -> None:
    query, computed = _counting_query()
    index = object()
    one, two = Database(), Database()
    with one.active():
        query("a", _Doc(index, None))
    with two.active():
        query("a", _Doc(index, None))  # another database computes its own
    assert len(computed) == 2
    one.close_document("a")
    with one.active():
        query("a", _Doc(index, None))
    assert len(computed) == 3


def test_a_derived_query_keeps_the_last_few_documents() -> None:
    computed: list[str] = []

    def compute(uri: str) -> tuple[str, bool]:
        computed.append(uri)
        return uri, True

    query: Derived[str, str] = Derived("tests.few", lambda uri: (uri,), compute, kept=2)
    with Database().active():
        for uri in ("a", "b", "c", "a"):
            query(uri, uri)
    assert computed == ["a", "b", "c", "a"]  # "a" was dropped when "c" came


def test_the_jumps_rule_after_an_edit_equals_a_fresh_analysis(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The jumps rule reads the program index: an edit the index skips gives back the last
    diagnostics without a look at the jumps, an edit of a label looks again; each time they
    are those of an analysis from scratch, in a new workspace (a new database)."""
    from fanuc_macro.rules import jumps
    from fanuc_macro.workspace import Workspace

    looked: list[int] = []
    real = jumps._check

    def spy(ctx: Any, found: list[Any]) -> bool:
        looked.append(len(ctx.doc.blocks))
        return real(ctx, found)

    monkeypatch.setattr(jumps, "_check", spy)
    lines = [
        "O1000",
        "#1=0",
        "G00 X10.",
        "IF [#1 GT 3] GOTO 30",
        "WHILE [#1 LT 5] DO1",
        "N20 #1=#1+1",
        "END1",
        "GOTO 20",
        "N10 M05",
        "M30",
    ]
    uri = "file:///jumps.nc"
    edited = Workspace()

    def jumps_of(workspace: Workspace) -> list[object]:
        workspace.add_text(uri, "\n".join(lines))
        return [d for d in workspace.analyse(uri).diagnostics if d.code.startswith("MB10")]

    def fresh() -> list[object]:
        return jumps_of(Workspace())

    first = jumps_of(edited)
    assert {d.code for d in first} >= {"MB101", "MB103"}  # type: ignore[attr-defined]
    assert first == fresh()
    assert looked == [10, 10]  # once each for the edited and the fresh workspace
    lines[2] = "G00 X20."  # a motion: the index is kept
    looked.clear()
    assert jumps_of(edited) == first
    assert looked == []
    assert jumps_of(edited) == fresh()
    lines.insert(9, "N30")  # the missing label: looked at again
    looked.clear()
    again = jumps_of(edited)
    assert looked == [len(lines)]
    assert again == fresh() and "MB101" not in {d.code for d in again}  # type: ignore[attr-defined]


def _per_document_entries(db: Database, uri: str) -> list[str]:
    """The names of the per-document tables of ``db`` that hold something for ``uri``."""
    return [
        key.name for key, table in list(db._tables.items()) if key.per_document and uri in table
    ]


def test_a_workspace_keeps_what_it_derives_in_its_database_and_frees_a_removed_document() -> None:
    from fanuc_macro.analysis import lines_with_findings
    from fanuc_macro.workspace import Workspace

    uri = "file:///kept.nc"
    text = "O1000\n#1=1.\nIF [#1 GT 0] GOTO 10\nG01 X#1 F0.2\nM30\n"
    one, two = Workspace(), Workspace()
    one.add_text(uri, text)
    one.analyse(uri)
    held = _per_document_entries(one.db, uri)
    assert any(name.startswith("line_maps.") for name in held)
    assert _per_document_entries(two.db, uri) == []  # another workspace: nothing of it
    assert _per_document_entries(database.default(), uri) == []  # nor the process default
    with one.db.active():
        looked = lines_with_findings.looked
        assert looked > 0
    with two.db.active():
        assert lines_with_findings.looked == 0
    one.remove(uri)
    assert _per_document_entries(one.db, uri) == []


def test_removing_many_documents_at_once_equals_removing_them_one_by_one() -> None:
    from fanuc_macro.workspace import Workspace

    texts = {
        "file:///main.nc": "O1000\n#1=2.\nM98 P2000\nG01 X#100 F0.2\nM30\n",
        "file:///sub.nc": "O2000\n#100=#1*3.\nM99\n",
        "file:///other.nc": "O3000\n#2=1./0.\nM30\n",
        "file:///spare.nc": "O4000\nG00 X1.\nM30\n",
    }
    one, many = Workspace(), Workspace()
    for workspace in (one, many):
        for uri, text in texts.items():
            workspace.add_text(uri, text)
            workspace.analyse(uri)
    for uri in ("file:///other.nc", "file:///spare.nc"):
        one.remove(uri)
    many.remove_all(uri for uri in ("file:///other.nc", "file:///spare.nc"))
    assert sorted(many.uris()) == sorted(one.uris()) == ["file:///main.nc", "file:///sub.nc"]
    for uri in ("file:///other.nc", "file:///spare.nc"):
        assert _per_document_entries(many.db, uri) == []
    assert set(many.indexes()) == set(one.indexes())
    first, second = one.analyse("file:///main.nc"), many.analyse("file:///main.nc")
    assert first.diagnostics == second.diagnostics
