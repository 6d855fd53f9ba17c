"""The arguments of vgroove's functions and methods, converted before they reach the extension:
numbers of the right kind or a one-line ValueError naming the argument (the ranges are checked by
the extension, against validation/ranges.h, with the command line's messages)."""

from __future__ import annotations

import numbers
import operator
from typing import Any, Callable, Optional, Sequence, Union

import numpy as np

ArrayLike = Union[float, Sequence[float], np.ndarray]
#: A progress callback: called as ``progress(done, total)`` (ints) while a call runs.
ProgressFn = Callable[[int, int], Any]


def real(x, name):
    """x as a float: Python and NumPy real scalars (and 0-d real arrays); bools, complex values and
    everything else raise ValueError naming the argument."""
    if isinstance(x, np.ndarray) and x.ndim == 0:
        x = x[()]
    if isinstance(x, (bool, np.bool_)):
        raise ValueError(f"{name} = {x!r} must be a real number, not a bool")
    if isinstance(x, (complex, np.complexfloating)):
        raise ValueError(f"{name} = {x!r} must be a real number, not complex (its imaginary part would be lost)")
    if not isinstance(x, numbers.Real):
        raise ValueError(f"{name} = {x!r} must be a real number")
    return float(x)


def opt_real(x, name):
    return None if x is None else real(x, name)


def opt_complex(x, name):
    """x as a complex number (None stays None): Python and NumPy real or complex scalars; bools and
    everything else raise ValueError naming the argument."""
    if x is None:
        return None
    if isinstance(x, np.ndarray) and x.ndim == 0:
        x = x[()]
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, numbers.Complex):
        raise ValueError(f"{name} = {x!r} must be a number (complex: eta + i kappa)")
    return complex(x)


def integer(x, name):
    """x as an int: Python and NumPy integers (and 0-d integer arrays); bools, floats and
    everything else raise ValueError naming the argument. The range is checked by the extension."""
    if isinstance(x, np.ndarray) and x.ndim == 0:
        x = x[()]
    if isinstance(x, (bool, np.bool_)):
        raise ValueError(f"{name} = {x!r} must be an integer, not a bool")
    if not isinstance(x, numbers.Integral):
        raise ValueError(f"{name} = {x!r} must be an integer")
    return operator.index(x)


def opt_integer(x, name):
    return None if x is None else integer(x, name)


def text(x, name, choices: Optional[Sequence[str]] = None):
    """x as a str (None stays None); with `choices`, one of them. ValueError naming the argument."""
    if x is None:
        return None
    if not isinstance(x, str):
        raise ValueError(f"{name} = {x!r} must be a string")
    if choices is not None and x not in choices:
        raise ValueError(f"{name} = \"{x}\" is not one of " + ", ".join(f"\"{c}\"" for c in choices))
    return x


def progress(x, name="progress"):
    """A progress callback or None, else ValueError naming the argument."""
    if x is not None and not callable(x):
        raise ValueError(f"{name} = {x!r} must be a callable progress(done, total) or None")
    return x


def reals(x, name):
    """x as a float array: real numbers only (complex and bool arrays raise ValueError naming the
    argument)."""
    a = np.asarray(x)
    if a.dtype.kind == "c":
        raise ValueError(f"{name} has complex values (dtype {a.dtype}): give real numbers (the imaginary part would "
                         "be lost)")
    if a.dtype.kind not in "iuf":
        if a.dtype.kind == "b" or a.dtype.kind == "O" and any(isinstance(v, (bool, np.bool_)) for v in a.flat):
            raise ValueError(f"{name} has bools (dtype {a.dtype}): give real numbers")
        if a.dtype.kind == "O" and any(isinstance(v, (complex, np.complexfloating)) for v in a.flat):
            raise ValueError(f"{name} has complex values (dtype {a.dtype}): give real numbers (the imaginary part "
                             "would be lost)")
        try:
            return a.astype(float)
        except (TypeError, ValueError):
            raise ValueError(f"{name} must hold real numbers (dtype {a.dtype})") from None
    return a.astype(float, copy=False)


def vectors(x, name):
    """x as a float array of shape (..., 3), else ValueError naming the argument."""
    a = reals(x, name)
    if a.shape[-1:] != (3,):
        raise ValueError(f"{name} must be an array of unit vectors, shape (..., 3); got {a.shape}")
    return a


def rows(a, shape, width):
    """a broadcast to shape + (width,) and flattened to rows (n, width), C-contiguous; one row when
    a has no batch dimensions of its own beyond ones (the extension uses that row for every item,
    without a copy)."""
    if a.size == width:
        return np.ascontiguousarray(a.reshape(1, width))
    return np.ascontiguousarray(np.broadcast_to(a, shape + (width,))).reshape(-1, width)
