"""What every test runs with."""

from __future__ import annotations

import os

# The findings `check` keeps between runs would let one test's run answer for another's:
# each test analyses what it checks (tests/test_check_cache.py turns the cache on, in a
# folder of its own, for its runs).
os.environ["FANUC_MACRO_CHECK_CACHE"] = "0"

# The command line speaks the language of LC_ALL, LC_MESSAGES or LANG: the tests read its
# English unless they ask for another language (tests/test_cli_language.py sets its own).
for _name in ("LC_ALL", "LC_MESSAGES"):
    os.environ.pop(_name, None)
os.environ["LANG"] = "C.UTF-8"
