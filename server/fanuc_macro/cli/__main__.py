"""``python -m fanuc_macro.cli``."""

import sys

from . import main

sys.exit(main())
