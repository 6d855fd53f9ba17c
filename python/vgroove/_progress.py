"""Progress of vgroove's long calls: every one takes ``progress=`` a callable ``progress(done,
total)``, called from the calling thread (with the GIL) about every 50 ms while the work runs on
worker threads, and once at the end with done == total. An exception raised by the callback stops
the work as Ctrl-C does and is raised by the call. :func:`tqdm_progress` draws the counts as a
tqdm bar (Debian's python3-tqdm)."""

from __future__ import annotations

from typing import Any, Optional


class TqdmProgress:
    """A progress callback that draws a tqdm bar: made by :func:`tqdm_progress`."""

    def __init__(self, tqdm, kwargs):
        self._tqdm = tqdm
        self._kwargs = kwargs
        self.bar: Optional[Any] = None

    def __call__(self, done: int, total: int) -> None:
        if self.bar is None or self.bar.total != total:
            if self.bar is not None:
                self.bar.close()
            self.bar = self._tqdm(total=total, **self._kwargs)
        self.bar.update(done - self.bar.n)
        if done >= total:
            self.bar.close()


def tqdm_progress(**kwargs: Any) -> TqdmProgress:
    """A progress callback for vgroove's long calls that draws a tqdm bar.

    Parameters
    ----------
    **kwargs
        Passed to ``tqdm.tqdm`` (``desc``, ``unit``, ``file``, ``disable``, ...). A new bar starts
        when the total changes (e.g. the next suite of a set); the bar closes when the call ends.

    Returns
    -------
    TqdmProgress
        The callback, to pass as ``progress=`` (its ``bar`` is the last tqdm bar it drew).

    Raises
    ------
    ImportError
        When tqdm is not installed (Debian: ``apt-get install python3-tqdm``).

    Examples
    --------
    >>> import io, vgroove
    >>> bar = vgroove.tqdm_progress(file=io.StringIO(), desc="albedo")
    >>> vgroove.BRDF().eval([0, 0, 1], [0, 0, 1], progress=bar).shape
    ()
    >>> bar.bar.n == bar.bar.total
    True
    """
    try:
        from tqdm import tqdm
    except ImportError:
        raise ImportError("vgroove.tqdm_progress needs tqdm, which is not installed "
                          "(Debian: apt-get install python3-tqdm)") from None
    return TqdmProgress(tqdm, kwargs)
