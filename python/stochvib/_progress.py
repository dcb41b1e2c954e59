"""Progress of Monte Carlo runs: a bar in terminals and notebooks, or the caller's callable."""

from __future__ import annotations

import sys
from typing import Any, Callable, Optional, Tuple

__all__ = ["make"]


class _TextBar:
    """``shard k/n (p %)`` on stderr, rewritten in place (``\\r``): terminals and Jupyter both render it."""

    def __init__(self) -> None:
        self._last: Optional[tuple] = None

    def __call__(self, done: int, total: int) -> None:
        if self._last == (done, total):
            return
        self._last = (done, total)
        pct = 100.0 * done / max(total, 1)
        width = 30
        filled = int(round(width * done / max(total, 1)))
        sys.stderr.write(f"\rshards [{'#' * filled}{'.' * (width - filled)}] {done}/{total} ({pct:.0f} %)")
        sys.stderr.flush()

    def close(self) -> None:
        if self._last is not None:
            sys.stderr.write("\n")
            sys.stderr.flush()


class _TqdmBar:
    """tqdm.auto's bar (a widget in notebooks with ipywidgets, text otherwise)."""

    def __init__(self, tqdm: Any) -> None:
        self._tqdm = tqdm
        self._bar: Any = None

    def __call__(self, done: int, total: int) -> None:
        if self._bar is None:
            self._bar = self._tqdm(total=total, unit="shard", desc="stochvib", leave=True)
        self._bar.n = done
        self._bar.refresh()

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()


def make(progress: Any) -> Tuple[Optional[Callable[[int, int], Any]], Optional[Callable[[], Any]]]:
    """(call, close) for ``progress``: ``True``: a bar (tqdm.auto when installed, else text on stderr);
    ``False``/``None``: nothing; a callable: itself, called as ``progress(done_shards, total_shards)`` after
    every shard (and once at the start). ``close`` (or None) is called at the end, whatever happens."""
    if progress is None or progress is False:
        return None, None
    if progress is True:
        try:
            from tqdm.auto import tqdm  # type: ignore[import-not-found]
        except Exception:
            bar: Any = _TextBar()
        else:
            bar = _TqdmBar(tqdm)
        return bar, bar.close
    if callable(progress):
        return progress, None
    raise TypeError(f"progress must be True, False or a callable(done, total), not {progress!r}")
