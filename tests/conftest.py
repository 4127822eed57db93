"""What every test runs with."""

from __future__ import annotations

import os

# The findings `check` keeps between runs would let one test's run answer for another's:
# each test analyses what it checks (tests/test_check_cache.py turns the cache on, in a
# folder of its own, for its runs).
os.environ["FANUC_MACRO_CHECK_CACHE"] = "0"
