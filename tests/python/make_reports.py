"""Writes the small suites of conftest.py and the command line's reports for them into DIR (run
once by ctest as python.reports, before the other Python tests), then DIR/done."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from conftest import make_reports, make_suites  # noqa: E402

d = sys.argv[1]
os.makedirs(d, exist_ok=True)
if os.path.exists(os.path.join(d, "done")):
    os.unlink(os.path.join(d, "done"))
make_reports(d, make_suites(d))
open(os.path.join(d, "done"), "w").close()
