"""Structured arrays with an optional pandas view.

A `Table` is a numpy structured array (one field per CSV column of the
CLI, same names) that also offers `.to_pandas()` when pandas is installed;
pandas is never required.
"""

from __future__ import annotations

from typing import Any, Mapping, Sequence

import numpy as np

#: Width of the string fields: the longest name written is
#: "quasiperiodic" (13 characters).
NAME_WIDTH = 16


class Table(np.ndarray):
    """A numpy structured array whose fields are the CLI's CSV columns."""

    def to_pandas(self) -> Any:
        """The table as a `pandas.DataFrame` (needs pandas)."""
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("to_pandas() needs pandas: pip install pandas") from e
        return pd.DataFrame({name: np.asarray(self[name]) for name in self.dtype.names or ()})


def table(columns: Mapping[str, Any], order: Sequence[str]) -> Table:
    """A `Table` of `columns` (arrays or lists of names) with fields in `order`."""
    arrays = []
    for name in order:
        col = columns[name]
        if isinstance(col, np.ndarray):
            arrays.append(col)
        else:
            arrays.append(np.array(col, dtype=f"U{NAME_WIDTH}"))
    n = len(arrays[0]) if arrays else 0
    dtype = [(name, a.dtype) for name, a in zip(order, arrays)]
    out = np.empty(n, dtype=dtype)
    for name, a in zip(order, arrays):
        out[name] = a
    return out.view(Table)


def concat(parts: Sequence[Table]) -> Table:
    """Tables of one kind joined end to end."""
    return np.concatenate([np.asarray(p) for p in parts]).view(Table)
