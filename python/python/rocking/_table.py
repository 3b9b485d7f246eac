"""Structured arrays with an optional pandas view.

A `Table` is a numpy structured array (one field per CSV column of the
CLI, same names) that also offers `.to_pandas()` when pandas is installed;
pandas is never required.
"""

from __future__ import annotations

from typing import Any, Mapping, Sequence

import numpy as np

class Table(np.ndarray):
    """A numpy structured array whose fields are the CLI's CSV columns.

    A missing value in a float column (no overturning, no exponent) is
    NaN, so `==` between tables is False there; `equals` compares them
    as values, NaN equal to NaN."""

    def equals(self, other: Any) -> bool:
        """Whether `other` has the same fields and values, a missing value
        (NaN) equal to a missing value."""
        a, b = np.asarray(self), np.asarray(other)
        if a.dtype.names != b.dtype.names or a.shape != b.shape:
            return False
        for name in a.dtype.names or ():
            x, y = a[name], b[name]
            nan = x.dtype.kind == "f" and y.dtype.kind == "f"
            if not np.array_equal(x, y, equal_nan=nan):
                return False
        return True

    def to_pandas(self) -> Any:
        """The table as a `pandas.DataFrame` (needs pandas)."""
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("to_pandas() needs pandas: pip install pandas") from e
        return pd.DataFrame({name: np.asarray(self[name]) for name in self.dtype.names or ()})


def names(values: Any) -> np.ndarray:
    """A column of names (record names, outcomes, modes) as a string array
    as wide as its longest name: never cut (a fixed width once cut
    `RSN1063_NORTHR_RRS228` and `…RRS318` to the same 16 characters)."""
    values = [str(v) for v in values]
    width = max((len(v) for v in values), default=1)
    return np.array(values, dtype=f"U{max(width, 1)}")


def table(columns: Mapping[str, Any], order: Sequence[str]) -> Table:
    """A `Table` of `columns` (arrays or lists of names) with fields in `order`."""
    arrays = []
    for name in order:
        col = columns[name]
        arrays.append(col if isinstance(col, np.ndarray) else names(col))
    n = len(arrays[0]) if arrays else 0
    dtype = [(name, a.dtype) for name, a in zip(order, arrays)]
    out = np.empty(n, dtype=dtype)
    for name, a in zip(order, arrays):
        out[name] = a
    return out.view(Table)


def concat(parts: Sequence[Table]) -> Table:
    """Tables of one kind joined end to end; a string field takes the
    widest of the parts' widths (chunks computed apart have their own)."""
    arrays = [np.asarray(p) for p in parts]
    fields = arrays[0].dtype.names or ()
    dtype = [(f, np.result_type(*[a.dtype[f] for a in arrays])) for f in fields]
    return np.concatenate([a.astype(dtype) for a in arrays]).view(Table)
