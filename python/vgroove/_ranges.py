"""The ranges the module enforces: those of validation/ranges.h (the command line's), exported by
the extension as ``_vgroove.ranges``, and filled into the docstrings that state them, so that no
docstring states a range the code does not enforce (tests/python/test_docs.py holds this dict
against validation/ranges.h itself)."""

from __future__ import annotations

import string

from . import _vgroove

#: The ranges the module enforces, by name (validation/ranges.h).
RANGES: dict = dict(_vgroove.ranges)


def number(v) -> str:
    """A range's bound as the docstrings print it: integers in full, others as %g."""
    if isinstance(v, int) or (isinstance(v, float) and v.is_integer() and abs(v) < 1e15):
        return str(int(v))
    return f"{v:g}"


def fill_ranges(doc: str, values: dict = None) -> str:
    """``doc`` with each ``$name`` replaced by RANGES[name] (or values[name]); a name that is not
    there raises KeyError (a docstring cannot name a range the module does not have)."""
    table = {k: number(v) for k, v in RANGES.items()}
    table.update({k: number(v) for k, v in (values or {}).items()})
    return string.Template(doc).substitute(table)
