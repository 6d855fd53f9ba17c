"""validate(): any suite, as ``vgroove validate`` runs it (validation/validate.h), the report as a dict."""

from __future__ import annotations

import json
import os
from typing import Optional, Union

from . import _vgroove
from ._args import ProgressFn, integer, opt_integer, progress as _progress
from ._ranges import fill_ranges


def validate(suite: Union[str, os.PathLike, dict], *, rays: Optional[int] = None, threads: int = 0,
             sampling: Optional[str] = None, eq6_form: Optional[str] = None, seed: Optional[int] = None,
             model_table: Optional[str] = None, verbose: bool = False,
             progress: Optional[ProgressFn] = None) -> dict:
    """Runs a suite as ``vgroove validate SUITE [--rays ...]`` does and returns its report.

    Parameters
    ----------
    suite : str, os.PathLike or dict
        A suite file (data/suites/*.json; docs/schemas/suite.schema.json), or the suite itself as
        the dict json.load gives for such a file (the file names of a set's "suites" are then
        taken relative to the current directory; messages name it "suite").
    rays : int, optional
        Per lit facet (single grooves) or per case (rough surfaces), in [1, $max_rays].
    threads : int
        In [0, $max_threads] (0: all cores); the figures do not depend on it.
    sampling, eq6_form : str, optional
        Single-groove suites: "stratified" or "random"; "corrected" or "printed".
    seed : int, optional
        In [0, 2^63 - 1].
    model_table : str, optional
        A foreign model's bin-integrated lobes for a "brdf" suite (``vgroove validate
        --model-table``; docs/schemas/model_table.schema.json), traced on the suite's surface
        (``"surface": "heightfield"``: check_brdf's random heightfields, e.g.
        data/suites/brdf_heightfield.json).
    verbose : bool
        Print the command line's table.
    progress : callable, optional
        ``progress(done, total)``: the run's work items (cases or chunks of them), per suite.

    Returns
    -------
    dict
        The report ``--out`` writes (docs/schemas/report.schema.json), as a dict; "pass" says
        whether every threshold held.

    Raises
    ------
    ValueError
        The command line's message for the same suite or override (naming the file, or "suite"
        for a dict, and the JSON path), or a dict that is not JSON (e.g. NaN).

    Examples
    --------
    >>> import vgroove
    >>> suite = {"name": "tiny", "kind": "table1",
    ...          "groove": {"type": "symmetric", "theta_v_deg": {"from": 60, "to": 120, "step": 60}},
    ...          "theta_i_deg": {"from": 0, "to": 40, "step": 40}, "rays": 100, "sampling": "stratified",
    ...          "seed": 1, "thresholds": {"max_l1": 0.1, "mean_l1": 0.1, "max_theta_o_error_rad": 1e-9}}
    >>> r = vgroove.validate(suite)
    >>> r["pass"], len(r["cases"])
    (True, 4)
    >>> vgroove.validate(dict(suite, rays=0))
    Traceback (most recent call last):
    ...
    ValueError: suite: /rays = 0 is out of range [1, 1000000000]
    """
    suite_json = None
    if isinstance(suite, dict):
        try:
            suite_json = json.dumps(suite, allow_nan=False)
        except (TypeError, ValueError) as e:
            raise ValueError(f"suite is not JSON: {e}") from None
        path = "suite"
    elif isinstance(suite, (str, os.PathLike)):
        path = os.fspath(suite)
    else:
        raise ValueError(f"suite = {suite!r} must be a suite file's path or a suite (dict)")
    return _vgroove.validate(str(path), opt_integer(rays, "rays"), integer(threads, "threads"), sampling, eq6_form,
                             opt_integer(seed, "seed"), None if model_table is None else str(model_table),
                             bool(verbose), suite_json, _progress(progress))


validate.__doc__ = fill_ranges(validate.__doc__)
