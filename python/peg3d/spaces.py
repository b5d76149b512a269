"""Gymnasium-style spaces: gymnasium.spaces.Box when gymnasium can be imported, else a Box of the same
contract (shape, dtype, low, high, sample(), contains(), seed())."""

import numpy as np

try:  # pragma: no cover - gymnasium is not a Debian package; used when present
    from gymnasium.spaces import Box  # type: ignore
except ImportError:

    class Box:
        """A box of R^n: every x with low <= x <= high, of one shape and dtype."""

        def __init__(self, low, high, shape=None, dtype=np.float32, seed=None):
            self.dtype = np.dtype(dtype)
            if shape is None:
                shape = np.shape(low)
            self.shape = tuple(int(s) for s in shape)
            self.low = np.broadcast_to(np.asarray(low, dtype=self.dtype), self.shape).copy()
            self.high = np.broadcast_to(np.asarray(high, dtype=self.dtype), self.shape).copy()
            if not (np.all(np.isfinite(self.low)) and np.all(np.isfinite(self.high))):
                raise ValueError("peg3d boxes have finite bounds")
            self._rng = np.random.default_rng(seed)

        def seed(self, seed=None):
            self._rng = np.random.default_rng(seed)
            return [seed]

        @property
        def np_random(self):
            return self._rng

        def sample(self):
            x = self._rng.uniform(self.low.astype(np.float64), self.high.astype(np.float64))
            return np.clip(x.astype(self.dtype), self.low, self.high)

        def contains(self, x):
            if not isinstance(x, np.ndarray):
                try:
                    x = np.asarray(x, dtype=self.dtype)
                except (ValueError, TypeError):
                    return False
            return bool(
                np.can_cast(x.dtype, self.dtype)
                and x.shape == self.shape
                and np.all(x >= self.low)
                and np.all(x <= self.high)
            )

        def __contains__(self, x):
            return self.contains(x)

        def __eq__(self, other):
            return (
                isinstance(other, Box)
                and self.shape == other.shape
                and self.dtype == other.dtype
                and np.array_equal(self.low, other.low)
                and np.array_equal(self.high, other.high)
            )

        def __repr__(self):
            return f"Box({self.low.min()}, {self.high.max()}, {self.shape}, {self.dtype})"
