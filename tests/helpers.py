"""Helpers shared by the tests (importable because pyproject sets pytest's pythonpath to tests/)."""
from __future__ import annotations

import numpy as np


def max_ulp_diff(a, b) -> int:
    """Largest distance in units in the last place between two float32 arrays (same-sign finite values)."""
    a = np.asarray(a, dtype=np.float32).ravel().view(np.int32).astype(np.int64)
    b = np.asarray(b, dtype=np.float32).ravel().view(np.int32).astype(np.int64)
    return int(np.max(np.abs(a - b))) if a.size else 0
