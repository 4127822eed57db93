"""Fuzzing in the test suite: byte, token and grammar-level mutations of the fixtures and the
corpus (see tests/fuzzing.py), a few hundred inputs in all, the same ones on every run.

Each input must be analysed without an exception or an internal error, within its budget, to
the same result after other analyses as in a fresh database; its edit-path parse must equal a
fresh parse, and each version of its edit path (from the unmutated program, an empty document,
a binary file, or the mutated text with one-character edits), analysed as the language server
does, must give what a fresh analysis gives. The long campaign
(``python bench/fuzz_campaign.py``) runs the same checks on a hundred thousand inputs and more.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, TypeVar

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from fuzzing import LEVELS, STARTS, check, describe, make_input, seeds

T = TypeVar("T")


class DataDraw:
    """Choices drawn from Hypothesis, which can then shrink a failing input."""

    def __init__(self, data: st.DataObject) -> None:
        self.data = data

    def integer(self, low: int, high: int) -> int:
        return self.data.draw(st.integers(low, high))

    def choice(self, options: Sequence[T]) -> T:
        return self.data.draw(st.sampled_from(options))


def test_the_seeds_are_the_fixtures_and_the_corpus() -> None:
    names = [name for name, _ in seeds()]
    assert any(n.startswith("tests/fixtures/rules/") for n in names)
    assert any(n.startswith("tests/fixtures/seeds/") for n in names)
    assert sum(n.startswith("corpus/") for n in names) > 50 or not any(
        n.startswith("corpus/") for n in names
    )  # the corpus is beside the project when it is there at all


@pytest.mark.parametrize("start", STARTS)
@pytest.mark.parametrize("level", LEVELS)
@settings(
    max_examples=30,
    deadline=None,  # check() measures the time of the analysis itself
    derandomize=True,  # the same inputs on every run: a failure is reproducible
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
@given(data=st.data())
def test_mutated_programs_are_analysed_soundly(level: str, start: str, data: Any) -> None:
    case = make_input(DataDraw(data), level, start)
    problem = check(case)
    assert problem is None, f"{problem}\n{describe(case)}"
