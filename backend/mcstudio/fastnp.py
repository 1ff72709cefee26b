"""numpy entry points for the control period without the array-function dispatch layer.

`np.count_nonzero` and `np.copyto` run a Python-level dispatcher on every call (for `__array_function__`), which
costs more than the work on the small per-axis arrays of a period; the kernel only passes plain ndarrays, so it calls
the C implementations directly (falling back to the public functions if numpy moves them). Ufuncs are called with a
positional output array (`np.add(a, b, out)`), which skips keyword parsing.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

try:  # numpy ≥ 2
    from numpy._core.multiarray import count_nonzero as _count_nonzero
except ImportError:  # pragma: no cover - other numpy layouts
    _count_nonzero = np.count_nonzero

count_nonzero: Callable[[np.ndarray], int] = _count_nonzero
copyto: Callable[..., Any] = getattr(np.copyto, "_implementation", np.copyto)
