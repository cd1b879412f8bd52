"""Argument checks of the public functions, before anything reaches the compiled core.

A wrong *type* raises ``TypeError`` naming the Python argument and the type it expects; a bad
*value* raises :class:`tack.TackError` (a ``ValueError``) naming the Python argument, the value
and the allowed range. Numbers are Python ``int``/``float`` or numpy integer/float scalars (or
0-d arrays of them); ``bool``, ``str``, ``bytes``, ``None`` and complex numbers are not numbers
here, even where Python's ``float()`` would convert them. Arrays are anything numpy reads as an
array of integers or floats; arrays of strings, objects, complex numbers or booleans are wrong
types.
"""

from __future__ import annotations

import math
import numbers
import os
import sys
from collections.abc import Iterable, Mapping, Sequence
from typing import Any, Callable, List, Optional, Tuple

import numpy as np

from ._tack import TackError

#: Largest number of elements along one axis of a grid (``tack::geometry::Grid``).
MAX_ELEMENTS_PER_AXIS = 1 << 16

#: dtype kinds numpy uses for signed integers, unsigned integers and floats.
_REAL_KINDS = "iuf"

_DTYPE_WORDS = {
    "b": "booleans",
    "c": "complex numbers",
    "U": "strings",
    "S": "bytes",
    "O": "Python objects",
    "M": "datetimes",
    "m": "timedeltas",
    "V": "raw records",
}


def num(x: float) -> str:
    """A number as the messages show it (as tack's Rust messages do: ``-1``, ``0.1``, ``NaN``,
    ``inf``)."""
    if math.isnan(x):
        return "NaN"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    if x == int(x) and abs(x) < 1e16:
        return str(int(x))
    return repr(float(x))


def describe(value: Any) -> str:
    """The type of ``value`` as a message shows it, with a short repr for strings."""
    if value is None:
        return "None"
    name = type(value).__name__
    if isinstance(value, np.ndarray):
        return f"a numpy array of dtype {value.dtype}"
    if isinstance(value, (str, bytes)):
        text = repr(value)
        if len(text) > 40:
            text = text[:37] + "..."
        return f"{name} {text}"
    return name


def is_bool(value: Any) -> bool:
    return isinstance(value, (bool, np.bool_))


def is_real(value: Any) -> bool:
    """Whether ``value`` is a real number: int, float, numpy integer/float scalar, a 0-d array
    of those; not a bool."""
    if is_bool(value):
        return False
    if isinstance(value, np.ndarray):
        return value.ndim == 0 and value.dtype.kind in _REAL_KINDS
    return isinstance(value, numbers.Real)


def is_integer(value: Any) -> bool:
    """Whether ``value`` is an integer: int, numpy integer scalar, a 0-d integer array; not a
    bool."""
    if is_bool(value):
        return False
    if isinstance(value, np.ndarray):
        return value.ndim == 0 and value.dtype.kind in "iu"
    return isinstance(value, numbers.Integral)


def real(name: str, value: Any, what: str = "a real number (int or float)") -> float:
    """``value`` as a float; ``TypeError`` naming ``name`` unless it is a real number."""
    if not is_real(value):
        hint = ""
        if isinstance(value, (str, bytes)):
            hint = " (convert text with float(...) first)"
        elif is_bool(value):
            hint = " (a bool is not a number here)"
        elif isinstance(value, numbers.Complex) or (
            isinstance(value, np.ndarray) and value.dtype.kind == "c"
        ):
            hint = " (complex numbers are not accepted)"
        raise TypeError(f"{name}: expected {what}, got {describe(value)}{hint}")
    return float(value)


def integer(name: str, value: Any, what: str = "an int") -> int:
    """``value`` as an int; ``TypeError`` naming ``name`` unless it is an integer."""
    if not is_integer(value):
        raise TypeError(f"{name}: expected {what}, got {describe(value)}")
    return int(value)


def optional(check: Callable[..., Any], name: str, value: Any, *args: Any) -> Any:
    """``None``, or ``check(name, value, *args)``."""
    return None if value is None else check(name, value, *args)


def flag(name: str, value: Any) -> bool:
    """A bool (``True``/``False``, or a numpy bool); ``TypeError`` otherwise (``1``, ``"no"``
    and ``None`` are not flags)."""
    if not is_bool(value):
        raise TypeError(f"{name}: expected a bool (True or False), got {describe(value)}")
    return bool(value)


def invalid(name: str, value: Any, allowed: str) -> TackError:
    """The ``TackError`` of a bad value: ``name = value is invalid: must be allowed``."""
    shown = num(value) if isinstance(value, float) else str(value)
    return TackError(f"{name} = {shown} is invalid: must be {allowed}")


def finite(name: str, value: Any) -> float:
    x = real(name, value)
    if not math.isfinite(x):
        raise invalid(name, x, "a finite number")
    return x


def positive(name: str, value: Any, note: str = "") -> float:
    x = real(name, value)
    if not (math.isfinite(x) and x > 0.0):
        raise invalid(name, x, "a finite number > 0" + note)
    return x


def non_negative(name: str, value: Any) -> float:
    x = real(name, value)
    if not (math.isfinite(x) and x >= 0.0):
        raise invalid(name, x, "a finite number ≥ 0")
    return x


def fraction(name: str, value: Any) -> float:
    x = real(name, value)
    if not (0.0 < x < 1.0):
        raise invalid(name, x, "a number in (0, 1)")
    return x


def count(name: str, value: Any, low: int = 1, high: int = sys.maxsize) -> int:
    """An integer in ``low..=high``."""
    n = integer(name, value)
    if not low <= n <= high:
        open_ended = high == sys.maxsize and n < low
        allowed = f"an integer ≥ {low}" if open_ended else f"an integer in {low}..={high}"
        raise invalid(name, n, allowed)
    return n


def threads(value: Any, max_threads: int) -> Optional[int]:
    """``threads``: None (every core) or an integer from 1 to ``max_threads`` (the message of the library's one check, ``tack::check_threads``)."""
    if value is None:
        return None
    n = integer("threads", value, "an int (or None for every core)")
    if not 1 <= n <= max_threads:
        raise invalid("threads", n, f"an integer from 1 to {max_threads}")
    return n


def path(name: str, value: Any) -> str:
    """A filesystem path: ``str`` or ``os.PathLike``."""
    if isinstance(value, str):
        return value
    if isinstance(value, os.PathLike):
        return os.fsdecode(os.fspath(value))
    hint = " (decode it with os.fsdecode)" if isinstance(value, bytes) else ""
    raise TypeError(f"{name}: expected a path (str or os.PathLike), got {describe(value)}{hint}")


def _as_array(name: str, value: Any, what: str) -> np.ndarray:
    """``value`` as a numpy array of integers or floats (any shape); ``TypeError`` naming
    ``name`` for other dtypes, ``TackError`` for what numpy cannot read as an array."""
    if value is None or isinstance(value, (str, bytes)):
        raise TypeError(f"{name}: expected {what}, got {describe(value)}")
    try:
        array = np.asarray(value)
    except (TypeError, ValueError) as e:
        raise TackError(f"{name}: cannot be read as an array ({e})") from None
    kind = array.dtype.kind
    if kind not in _REAL_KINDS:
        words = _DTYPE_WORDS.get(kind, "non-numbers")
        raise TypeError(
            f"{name}: expected {what}, got an array of {words} (dtype {array.dtype})"
        )
    return array


def _first_bad(bad: np.ndarray) -> Tuple[Tuple[int, ...], str]:
    """The index of the first ``True`` of ``bad`` (row-major), and as a message shows it
    (``[i, j]``)."""
    index = tuple(int(i) for i in np.unravel_index(int(np.argmax(bad.ravel())), bad.shape))
    return index, "[" + ", ".join(str(i) for i in index) + "]"


def _ndim(value: Any) -> int:
    """``np.ndim(value)``; 1 for what numpy cannot read (``_as_array`` then says why)."""
    try:
        return int(np.ndim(value))
    except (TypeError, ValueError):
        return 1


def heights(value: Any, name: str = "heights") -> np.ndarray:
    """A 2-D, non-empty array of finite real numbers, as C-contiguous float64."""
    what = "a 2-D array of real numbers (nx, ny)"
    if _ndim(value) == 0 and not isinstance(value, np.ndarray):
        raise TypeError(f"{name}: expected {what}, got {describe(value)}")
    array = _as_array(name, value, what)
    if array.ndim != 2:
        raise TackError(
            f"{name}: expected a 2-D array (nx, ny), got a {array.ndim}-D array of shape "
            f"{array.shape}"
        )
    nx, ny = array.shape
    if nx == 0 or ny == 0:
        raise TackError(
            f"{name}: the array is empty ({nx} × {ny}); it needs at least one element along "
            "each axis"
        )
    for axis, n in enumerate(array.shape):
        if n > MAX_ELEMENTS_PER_AXIS:
            raise invalid(
                f"{name}.shape[{axis}]", n, f"an integer in 1..={MAX_ELEMENTS_PER_AXIS}"
            )
    out = np.ascontiguousarray(array, dtype=np.float64)
    bad = ~np.isfinite(out)
    if bad.any():
        index, shown = _first_bad(bad)
        raise invalid(f"{name}{shown}", float(out[index]), "a finite number")
    return out


def approaches(value: Any, name: str = "approach") -> Tuple[List[float], bool]:
    """The approaches of :func:`tack.contact_sweep` (``name``): a number, or a non-empty 1-D
    sequence of them; returns the list and whether a single number was given."""
    what = "a real number or a 1-D sequence of them"
    if _ndim(value) == 0 and not isinstance(value, np.ndarray):
        return [finite_as(name, value, what)], True
    if isinstance(value, Mapping) or not isinstance(value, Iterable):
        raise TypeError(f"{name}: expected {what}, got {describe(value)}")
    if not isinstance(value, (Sequence, np.ndarray)):
        value = list(value)
    array = _as_array(name, value, what)
    if array.ndim == 0:
        return [finite(name, float(array))], True
    if array.ndim != 1:
        raise TackError(
            f"{name}: expected a number or a 1-D sequence of numbers, got an array of shape "
            f"{array.shape}"
        )
    if array.size == 0:
        raise TackError(f"{name}: the sequence is empty; give at least one approach")
    out = array.astype(np.float64)
    bad = ~np.isfinite(out)
    if bad.any():
        k = int(np.argmax(bad))
        raise invalid(f"{name}[{k}]", float(out[k]), "a finite number")
    return [float(d) for d in out], False


def finite_as(name: str, value: Any, what: str) -> float:
    """:func:`finite` with the expected type spelled ``what`` in a ``TypeError``."""
    x = real(name, value, what)
    if not math.isfinite(x):
        raise invalid(name, x, "a finite number")
    return x


def shape(value: Any) -> Tuple[int, int]:
    """``shape`` of the surface functions: ``n`` or ``(nx, ny)``, integers in
    ``1..=65536``."""
    what = "n or (nx, ny), integers"
    if is_integer(value):
        nx = ny = int(value)
        shown = str(nx)
    else:
        if isinstance(value, (str, bytes)) or not isinstance(value, (Sequence, np.ndarray)):
            raise TypeError(f"shape: expected {what}, got {describe(value)}")
        items = list(value)
        if len(items) != 2:
            raise TackError(
                f"shape: expected n or (nx, ny), got a sequence of {len(items)} items"
            )
        nx, ny = (integer(f"shape[{k}]", item) for k, item in enumerate(items))
        shown = f"({nx}, {ny})"
    if not (1 <= nx <= MAX_ELEMENTS_PER_AXIS and 1 <= ny <= MAX_ELEMENTS_PER_AXIS):
        raise TackError(
            f"shape = {shown} is invalid: nx and ny must be integers in "
            f"1..={MAX_ELEMENTS_PER_AXIS}"
        )
    return nx, ny


#: Value rules of the closed forms' arguments, by name: (test, allowed range).
_DOMAINS = {
    "e_star": (lambda x: np.isfinite(x) & (x > 0), "a finite number > 0"),
    "radius": (lambda x: np.isfinite(x) & (x > 0), "a finite number > 0"),
    "wavelength": (lambda x: np.isfinite(x) & (x > 0), "a finite number > 0"),
    "dx": (lambda x: np.isfinite(x) & (x > 0), "a finite number > 0"),
    "kappa": (lambda x: np.isfinite(x) & (x > 0), "a finite number > 0"),
    "q0": (lambda x: np.isfinite(x) & (x > 0), "a finite number > 0"),
    "q1": (lambda x: np.isfinite(x) & (x > 0), "a finite number > 0"),
    "gamma": (lambda x: np.isfinite(x) & (x >= 0), "a finite number ≥ 0"),
    "h": (lambda x: np.isfinite(x) & (x >= 0), "a finite number ≥ 0"),
    "a": (lambda x: np.isfinite(x) & (x >= 0), "a finite number ≥ 0"),
    "alpha": (lambda x: np.isfinite(x) & (x >= 0), "a finite number ≥ 0"),
    "alpha_star": (lambda x: np.isfinite(x) & (x >= 0), "a finite number ≥ 0"),
    "hurst": (lambda x: (x > 0) & (x < 1), "a number in the open interval (0, 1)"),
    "d": (lambda x: np.isfinite(x), "a finite number"),
    "c": (lambda x: np.isfinite(x) & (x > 0), "a finite number > 0"),
    "exponent": (lambda x: (x >= 1) & (x <= 16), "a number in [1, 16]"),
    "sigma0": (lambda x: np.isfinite(x) & (x > 0), "a finite number > 0"),
    "lam": (lambda x: np.isfinite(x) & (x > 0), "a finite number > 0"),
}


def closed_form_args(
    function: str, names: Sequence[str], values: Sequence[Any]
) -> Tuple[List[Any], bool]:
    """Checks the arguments of a closed form: each a real number or an array of them (numpy
    broadcasting), each in its domain (``_DOMAINS``); returns them (floats, or float64 arrays)
    and whether they are all scalars."""
    what = "a real number or an array of them"
    out: List[Any] = []
    for name, value in zip(names, values):
        test, allowed = _DOMAINS[name]
        if _ndim(value) == 0 and not isinstance(value, np.ndarray):
            x: Any = real(name, value, what)
            if not bool(test(np.float64(x))):
                raise invalid(name, x, allowed)
        else:
            x = _as_array(name, value, what).astype(np.float64)
            bad = ~test(x)
            if bad.any():
                index, shown = _first_bad(np.atleast_1d(bad))
                value_at = float(np.atleast_1d(x)[index])
                raise invalid(f"{name}{shown}" if x.ndim else name, value_at, allowed)
            if x.ndim == 0:
                x = float(x)
        out.append(x)
    scalar = all(isinstance(x, float) for x in out)
    if not scalar:
        shapes = [np.shape(x) for x in out]
        try:
            np.broadcast_shapes(*shapes)
        except ValueError:
            listed = ", ".join(f"{n} {s}" for n, s in zip(names, shapes))
            raise TackError(
                f"{function}: the arguments' shapes do not broadcast together: {listed}"
            ) from None
    return out, scalar


def above(names: Sequence[str], values: Sequence[Any], name: str, bound: Any) -> None:
    """The checked argument ``name`` is above ``bound``, a number or the name of another
    argument (elementwise, broadcast); ``TackError`` naming the first element that is not."""
    x = values[list(names).index(name)]
    other = bound if isinstance(bound, str) else None
    limit = values[list(names).index(other)] if other else bound
    x_b, limit_b = np.broadcast_arrays(np.asarray(x, dtype=np.float64), limit)
    bad = np.atleast_1d(~(x_b > limit_b))
    if not bad.any():
        return
    index, shown = _first_bad(bad)
    at = index if x_b.ndim else ()
    edge = num(float(limit_b[at]))
    if other is None:
        allowed = f"a finite number > {edge}"
    elif x_b.ndim:
        allowed = f"> {other} (here {edge})"
    else:
        allowed = f"> {other} = {edge}"
    raise invalid(f"{name}{shown}" if x_b.ndim else name, float(x_b[at]), allowed)
