"""vgroove plots: figures drawn with matplotlib from a report JSON alone, nothing recomputed.

    python3 -m vgroove.plot REPORT.json [--out BASE[.png|.svg|.pdf]] [--format png|svg|pdf] [--force]
    vgroove plot REPORT.json ...            (runs this file)

One or more images per report, named after the report (or --out) with a suffix per figure:

    single-groove suites (Table 1, stress)   BASE.png       heatmaps of L1 over (theta_v, theta_i), one per
                                                            suite of a set, side by side, thresholds marked
    "brdf" suites (Fig. 11)                  BASE-NDF-DIM.png  one grid per (NDF, dimension): rows theta_i,
                                                            columns alpha; traced lobe as bars, the model
                                                            as a line, per k dashed, Cook-Torrance dotted
    "furnace"                                BASE.png       albedo against theta_i per alpha: Eq. 17 by
                                                            quadrature (+ the light beyond max_k), by
                                                            importance sampling (+- standard error),
                                                            Cook-Torrance (what it loses), the traced line;
                                             BASE-errors.png  energy error and estimate error per case
    "sampling"                               BASE.png       chi-square per case: observed vs expected counts;
                                             BASE-variance.png  variance and ns per sample per strategy;
                                             BASE-furnace.png, BASE-furnace-errors.png  its furnace
    "nonsymmetric_brdf"                      BASE.png       L1 / threshold per case (model, other partner law);
                                             BASE[-aniso]-NDF-DIM.png  lobe grids on the plane of incidence
    "profiles"                               BASE.png       masking G1 per facet normal: traced, V-cavity, Smith;
                                             BASE-lobes.png  lobes: traced profiles, random walk, V-groove model
    "heightfield"                            BASE-NDF.png   per model (Smith walk, Cook-Torrance with Smith G,
                                                            V-groove), L1 / threshold of each k's lobe (1, 2,
                                                            3+) against theta_i, a series per alpha (<= 1:
                                                            within noise), and E_k model minus traced;
                                             BASE-lobes-NDF.png  the lobe per k = 1, 2, 3+ over theta_o
                                                            (a row per case): traced (2 se) and each model;
                                             BASE-masking-NDF.png  G1 per facet-normal bin: traced,
                                                            Smith, V-cavity (a row per alpha, a column per view);
                                                            the masking controls' verdict in the title, a G1
                                                            control's panel titled held / NOT within noise
    "heightfield_albedo"                     BASE-NDF.png   E, E_1, E_ms over mu, a row per alpha: traced
                                                            (2 se bars) against the Smith walk, Smith's
                                                            exact E_ss (E_1) and the V-groove model
    "energy_audit"                           BASE-REF-NDF.png  per compensation formula, its albedo minus the
                                                            exact one over (mu, alpha), the grey F0 with the
                                                            largest |error| per cell (REF: vgroove, smith_walk)
    "dielectric_brdf"                        BASE-SURFACE-DIM-NDF-SIDE.png  rows alpha, columns theta_i x
                                                            (reflected, transmitted): traced lobe (every k,
                                                            k = 1, k = 2) and each model (3D: theta marginal)
    "table2"                                 BASE.png       the paper's bounce counts, ours, the traced ones
    `bench accuracy --out`                   BASE.png       L1 against wall time (log-log);
                                             BASE-cost.png  tracer vs model cost against theta_v
    check_brdf reports                       BASE.png       L1 and albedo against their thresholds per theta_i,
                                                            and the worst bins
    `validate --model-table` reports         BASE-NDF-DIM.png  the same per (NDF, dimension), a series per alpha

The report is validated before anything is drawn: a field that is missing, of the wrong type,
an empty or short array, null or a non-finite number is a one-line error (ValueError; the
command exits 2). Output is all or nothing: every figure is rendered to a temporary file beside
its target first and the targets are replaced only when all of them rendered (an existing file
only with --force). Names and other text from the report are drawn as plain text (no mathtext),
with control characters escaped, so any suite name renders.

This file imports only the standard library, NumPy and matplotlib (not the extension module), so
it runs wherever those are installed, including next to a sanitizer build.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

FORMATS = ("png", "svg", "pdf")
# Figure extensions the suffix map may add; the only characters a generated file name part may hold.
_NAME_CHARS = set("abcdefghijklmnopqrstuvwxyz0123456789-_")


class ReportError(ValueError):
    """The report cannot be drawn: the message names the file and the JSON path."""


# ----------------------------------------------------------------------------------------------
# Reading the report strictly.

class Node:
    """A JSON value with its path, for messages: Node(report, "r.json")["cases"][3]["l1"]."""

    def __init__(self, value: Any, file: str, path: str = "") -> None:
        self.value, self.file, self.path = value, file, path

    def fail(self, what: str) -> "ReportError":
        return ReportError(f"{self.file}: {self.path or '/'} {what}")

    def has(self, key: str) -> bool:
        return isinstance(self.value, dict) and key in self.value

    def __getitem__(self, key: Any) -> "Node":
        if isinstance(key, str):
            if not isinstance(self.value, dict):
                raise self.fail(f"is {_kind(self.value)}, not an object")
            if key not in self.value:
                raise self.fail(f"has no \"{safe_text(key)}\"")
            return Node(self.value[key], self.file, f"{self.path}/{key}")
        if not isinstance(self.value, list):
            raise self.fail(f"is {_kind(self.value)}, not a list")
        if not 0 <= key < len(self.value):
            raise self.fail(f"has {len(self.value)} entries, needs entry {key}")
        return Node(self.value[key], self.file, f"{self.path}/{key}")

    def items(self) -> List["Node"]:
        if not isinstance(self.value, list):
            raise self.fail(f"is {_kind(self.value)}, not a list")
        return [self[n] for n in range(len(self.value))]

    def nonempty(self) -> List["Node"]:
        out = self.items()
        if not out:
            raise self.fail("is an empty list")
        return out

    def number(self, lo: float = -math.inf, hi: float = math.inf) -> float:
        v = self.value
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise self.fail(f"is {_kind(v)}, not a number")
        try:
            x = float(v)
        except OverflowError:
            raise self.fail("is a number too large for a double") from None
        if not math.isfinite(x) or not lo <= x <= hi:
            raise self.fail(f"= {_num(x)} is out of range [{_num(lo)}, {_num(hi)}]")
        return x

    def text(self) -> str:
        if not isinstance(self.value, str):
            raise self.fail(f"is {_kind(self.value)}, not a string")
        return self.value

    def boolean(self) -> bool:
        if not isinstance(self.value, bool):
            raise self.fail(f"is {_kind(self.value)}, not true or false")
        return self.value

    def one_of(self, allowed: Sequence[str]) -> str:
        s = self.text()
        if s not in allowed:
            raise self.fail(f"= \"{safe_text(s)}\" is not one of {', '.join(allowed)}")
        return s

    def numbers(self, length: Optional[int] = None, lo: float = -math.inf, hi: float = math.inf,
                min_length: int = 1) -> List[float]:
        items = self.items()
        if length is not None and len(items) != length:
            raise self.fail(f"has {len(items)} values, needs {length}")
        if len(items) < min_length:
            raise self.fail(f"has {len(items)} values, needs at least {min_length}")
        return [i.number(lo, hi) for i in items]

    def numbers_or_gaps(self, length: int, lo: float = -math.inf, hi: float = math.inf) -> List[float]:
        """numbers() where "nan" (or null) is a gap (NaN, not drawn): a value the report leaves undefined
        (docs/conventions.md: NaN is written as the string "nan")."""
        items = self.items()
        if len(items) != length:
            raise self.fail(f"has {len(items)} values, needs {length}")
        return [math.nan if i.value is None or i.value == "nan" else i.number(lo, hi) for i in items]

    def opt_text(self, key: str, fallback: str = "?") -> str:
        return self[key].text() if self.has(key) and isinstance(self.value[key], str) else fallback


def _kind(v: Any) -> str:
    if v is None:
        return "null"
    if isinstance(v, bool):
        return "a boolean"
    if isinstance(v, (int, float)):
        return "a number"
    if isinstance(v, str):
        return "a string"
    if isinstance(v, list):
        return "a list"
    if isinstance(v, dict):
        return "an object"
    return type(v).__name__


def _num(x: float) -> str:
    return repr(x) if math.isfinite(x) else ("inf" if x > 0 else "-inf" if x < 0 else "nan")


def safe_text(s: Any, limit: int = 80) -> str:
    """Text from a report as plain, printable, one-line text: control, format and unpaired
    surrogate characters escaped, '$' escaped (never mathtext), at most `limit` characters."""
    out = []
    for ch in str(s):
        o = ord(ch)
        if ch == "$":
            out.append("\\$")
        elif o < 0x20 or o == 0x7F or 0x80 <= o < 0xA0 or 0xD800 <= o < 0xE000 or o in _BIDI_AND_FORMAT:
            out.append(f"\\u{o:04x}" if o <= 0xFFFF else f"\\U{o:08x}")
        else:
            out.append(ch)
    t = "".join(out)
    return t if len(t) <= limit else t[: limit - 3] + "..."


# Bidirectional controls, zero-width and other format characters that reorder or hide text.
_BIDI_AND_FORMAT = set(range(0x200B, 0x2010)) | set(range(0x202A, 0x202F)) | set(range(0x2060, 0x2070)) | {
    0x061C, 0xFEFF, 0x00AD}


def _title_bits(report: Node) -> str:
    return (f"vgroove {safe_text(report.opt_text('version'), 24)}, git {safe_text(report.opt_text('git'), 24)}")


# ----------------------------------------------------------------------------------------------
# Report kinds.

def report_kind(report: Node) -> str:
    v = report.value
    if not isinstance(v, dict):
        raise report.fail(f"is {_kind(v)}: a report is a JSON object")
    kind = v.get("kind")
    if kind in ("brdf", "furnace", "table2", "check_brdf", "sampling", "nonsymmetric_brdf", "profiles",
                "energy_audit", "model_table", "heightfield", "heightfield_albedo", "dielectric_brdf",
                "glass_energy"):
        return kind
    if "runs" in v:
        return "accuracy"
    if "suites" in v or "cases" in v:
        return "single_grooves"
    raise report.fail("is not a vgroove report (no \"kind\", \"runs\", \"suites\" or \"cases\")")


Figure = Any  # matplotlib.figure.Figure
Drawer = Callable[[], Figure]


def _figure(width: float, height: float) -> Figure:
    from matplotlib.figure import Figure as _Fig
    return _Fig(figsize=(width, height), dpi=100, layout="constrained")


def _suptitle(fig: Figure, title: str, sub: str) -> None:
    import textwrap
    width = max(40, int(fig.get_figwidth() * 10))  # characters per line at this font size
    fig.suptitle("\n".join(textwrap.wrap(title, width) + textwrap.wrap(sub, width)), fontsize=11)


# Single-groove suites: Table 1 heatmaps -------------------------------------------------------

def _single_suite(s: Node) -> Dict[str, Any]:
    cases = s["cases"].nonempty()
    th = s["thresholds"]
    out: Dict[str, Any] = {
        "name": safe_text(s["suite"].text()),
        "max_l1": th["max_l1"].number(0.0),
        "paper": s["paper"]["max_l1"].number(0.0) if s.has("paper") and s["paper"].value is not None else None,
        "v": [], "i": [], "l1": [],
    }
    for c in cases:
        if c.has("degenerate"):
            continue
        out["v"].append(c["theta_v_deg"].number(0.0, 180.0))
        out["i"].append(c["theta_i_deg"].number(-90.0, 90.0))
        out["l1"].append(c["l1"].number(0.0, 2.0))
    if not out["l1"]:
        raise s["cases"].fail("has no compared case (all degenerate)")
    return out


def single_groove_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    suites = report["suites"].nonempty() if report.has("suites") else [report]
    data = [_single_suite(s) for s in suites]
    title = safe_text(report["suite"].text()) if report.has("suite") else "?"

    def draw() -> Figure:
        import numpy as np
        from matplotlib.colors import LogNorm, Normalize
        fig = _figure(6.0 * len(data) + 1.0, 5.2)
        axes = fig.subplots(1, len(data), squeeze=False)[0]
        for ax, d in zip(axes, data):
            v, i, l1 = (np.asarray(d[k], dtype=float) for k in ("v", "i", "l1"))
            thr = d["max_l1"]
            marks = [x for x in (thr, d["paper"]) if x is not None and x > 0]
            vmax = max([float(l1.max())] + marks) or 1.0
            # Thresholds far below the paper's (exact fractions, e.g. by breakpoint search): a
            # logarithmic scale from a tenth of the smallest nonzero L1 (zeros drawn at its floor).
            log = 0.0 < thr < 1e-3 * vmax
            if log:
                positive = l1[l1 > 0.0]
                floor = max(1e-20, 0.1 * min(thr, float(positive.min())) if positive.size else 1e-6 * thr)
                norm = LogNorm(floor, vmax, clip=True)
                l1 = np.maximum(l1, floor)
                at = float(np.log(thr / floor) / np.log(vmax / floor))
            else:
                norm = Normalize(0.0, vmax)
                at = thr / vmax
            vs, is_ = np.unique(v), np.unique(i)
            over = l1 > thr
            if len(vs) * len(is_) <= 4 * len(l1) and len(vs) > 1 and len(is_) > 1:
                # A grid: each cell the largest L1 of its cases (nonsymmetric grooves share theta_v).
                grid = np.full((len(vs), len(is_)), np.nan)
                vi, ii = np.searchsorted(vs, v), np.searchsorted(is_, i)
                np.fmax.at(grid, (vi, ii), l1)
                mesh = ax.pcolormesh(_edges(is_), _edges(vs), np.ma.masked_invalid(grid), cmap="viridis", norm=norm,
                                     shading="flat")
                if over.any():
                    # The cells above the threshold, outlined.
                    ax.contour(is_, vs, np.nan_to_num(grid, nan=0.0) > thr, levels=[0.5], colors="red",
                               linewidths=0.8)
            else:
                mesh = ax.scatter(i, v, c=l1, cmap="viridis", norm=norm, s=12,
                                  edgecolors=np.where(over, "red", "none"), linewidths=0.8)
            if over.any():
                ax.plot([], [], color="red", lw=1, label=f"L1 > threshold: {int(over.sum())} of {len(l1)} cases")
                ax.legend(loc="upper right", fontsize=7)
            cb = fig.colorbar(mesh, ax=ax)
            cb.set_label("L1 error of the model (fraction of the rays)" + (", log scale" if log else ""))
            cb.ax.axhline(thr, color="red", lw=2)
            cb.ax.text(1.05, at, " threshold", transform=cb.ax.transAxes, color="red", fontsize=7,
                       va="center", clip_on=False)
            if d["paper"] is not None:
                cb.ax.axhline(d["paper"], color="white", lw=1.5, ls="--")
            ax.set_xlabel("theta_i (deg)")
            ax.set_ylabel("theta_v (deg)")
            paper = f", paper max {d['paper']:.4g}" if d["paper"] is not None else ""
            ax.set_title(f"{d['name']}: max L1 {float(l1.max()):.4g} (threshold {thr:.4g}{paper})", fontsize=9)
        _suptitle(fig, f"{title}: L1 over (theta_v, theta_i), largest per cell",
                  f"{_title_bits(report)}; red line: the suite's threshold, white dashed: the paper's max L1")
        return fig

    return [("", draw)]


def _edges(centres):
    import numpy as np
    c = np.asarray(centres, dtype=float)
    mid = (c[1:] + c[:-1]) / 2
    return np.concatenate([[c[0] - (mid[0] - c[0])], mid, [c[-1] + (c[-1] - mid[-1])]])


# "brdf" suites: the Fig. 11 grids ---------------------------------------------------------------

def brdf_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    groups: Dict[Tuple[str, str], List[Dict[str, Any]]] = {}
    for c in report["cases"].nonempty():
        ndf = _ndf_label(c)
        dim = c["dimension"].one_of(("flatland", "3d"))
        pl = c["plane"]
        th = pl["theta_deg"].numbers(lo=-90.0, hi=90.0)
        n = len(th)
        panel = {
            "alpha": c["alpha"].number(0.0, 2.0), "theta_i": c["theta_i_deg"].number(-90.0, 90.0),
            "theta": th, "sim": pl["sim"].numbers(n, 0.0), "model": pl["model"].numbers(n),
            "ct": pl["cook_torrance"].numbers(n), "unit": safe_text(pl["unit"].text()),
            "model_k": [k.numbers(n) for k in pl["model_by_k"].items()[:4]] if pl.has("model_by_k") else [],
            "l1": c["l1"].number(0.0, 2.0), "thr": c["l1_threshold"].number(0.0), "pass": c["pass"].boolean(),
            "rays": c["rays"].number(0.0),
        }
        groups.setdefault((ndf, dim), []).append(panel)
    name = safe_text(report["suite"].text())
    figures = []
    for (ndf, dim), panels in groups.items():
        figures.append((f"-{ndf}-{dim}", _brdf_grid(report, name, ndf, dim, panels)))
    return figures


def _brdf_grid(report: Node, name: str, ndf: str, dim: str, panels: List[Dict[str, Any]]) -> Drawer:
    def draw() -> Figure:
        import numpy as np
        alphas = sorted({p["alpha"] for p in panels})
        thetas = sorted({p["theta_i"] for p in panels})
        fig = _figure(3.0 * len(alphas) + 1.0, 2.3 * len(thetas) + 1.2)
        axes = fig.subplots(len(thetas), len(alphas), squeeze=False)
        for ax in axes.flat:
            ax.set_visible(False)
        colors = ["#1f77b4", "#ff7f0e", "#9467bd", "#8c564b"]
        for p in panels:
            ax = axes[thetas.index(p["theta_i"])][alphas.index(p["alpha"])]
            ax.set_visible(True)
            th = np.asarray(p["theta"])
            width = float(np.min(np.abs(np.diff(th)))) if len(th) > 1 else 1.0
            ax.bar(th, p["sim"], width=width, color="#8fd18f", label="traced")
            for k, mk in enumerate(p["model_k"]):
                ax.plot(th, mk, color=colors[k], lw=0.8, ls="--", label=f"model, k = {k + 1}")
            ax.plot(th, p["ct"], color="black", lw=1.0, ls=":", label="Cook-Torrance")
            ax.plot(th, p["model"], color="#d62728", lw=1.4, label="model, all k")
            ax.set_xlim(-90, 90)
            top = max(max(p["sim"]), max(p["model"]), 1e-300)
            ax.set_ylim(0, 1.08 * top)
            ax.set_title(f"alpha {p['alpha']:g}, theta_i {p['theta_i']:g} deg", fontsize=8)
            ax.text(0.02, 0.97, f"L1 {p['l1']:.4f} (thr {p['thr']:.4f})\n{p['rays']:.2g} rays",
                    transform=ax.transAxes, fontsize=6, va="top", color="#555" if p["pass"] else "#d62728")
            ax.tick_params(labelsize=6)
            ax.set_xlabel("theta_o (deg; < 0: mirror side)", fontsize=7)
            ax.set_ylabel(p["unit"].replace("fraction of the flux", "flux"), fontsize=7)
        next(a for a in axes.flat if a.get_visible()).legend(fontsize=5, loc="upper right")
        _suptitle(fig, f"{name}: {ndf}, {dim} (Lee et al. 2018, Fig. 11): lobe on the plane of incidence",
                  _title_bits(report) + f", seed {report['seed'].number() if report.has('seed') else '?'}")
        return fig
    return draw


# Furnace ------------------------------------------------------------------------------------------

_NDFS = ("ggx", "beckmann", "phong", "student_t")
_DIMS = ("flatland", "3d")


def _ndf_label(c: Node) -> str:
    """A case's NDF, Student-T with its tail gamma ("student_t-g1.6")."""
    ndf = c["ndf"].one_of(_NDFS)
    return ndf if ndf != "student_t" else f"student_t-g{c['gamma'].number(1.5, 1e4):g}"


def _furnace_cases(cases: List[Node]) -> Dict[Tuple[str, str], Dict[float, List[Dict[str, float]]]]:
    """The furnace's cases (kind "furnace", and the "furnace" part of a "sampling" report) by
    (dimension, ndf) and alpha."""
    rows: Dict[Tuple[str, str], Dict[float, List[Dict[str, float]]]] = {}
    for c in cases:
        key = (c["dimension"].one_of(_DIMS), _ndf_label(c))
        p = {"theta_i": c["theta_i_deg"].number(-90.0, 90.0), "quad": c["albedo_quadrature"].number(-1.0, 3.0),
             "beyond": c["flux_beyond_max_k"].number(-1.0, 2.0), "energy": c["energy_error"].number(-2.0, 2.0),
             "est": c["albedo_estimate"].number(-1.0, 3.0), "se": c["standard_error"].number(0.0),
             "est_err": c["estimate_error"].number(-3.0, 3.0), "ct": c["cook_torrance_quadrature"].number(-1.0, 3.0),
             "ct_est": c["cook_torrance_estimate"].number(-1.0, 3.0), "sim": c["albedo_sim"].number(0.0, 2.0),
             "energy_ok": c["energy_ok"].boolean(), "estimate_ok": c["estimate_ok"].boolean(),
             "pass": c["pass"].boolean()}
        rows.setdefault(key, {}).setdefault(c["alpha"].number(0.0, 2.0), []).append(p)
    return rows


def _furnace_drawers(report: Node, name: str, cases: Node, tolerance: Optional[Node],
                     sigmas: Optional[float]) -> List[Tuple[str, Drawer]]:
    rows = _furnace_cases(cases.nonempty())
    tol = {d: tolerance[d].number(0.0) for d in _DIMS} if tolerance is not None else {}

    def draw_albedo() -> Figure:
        import matplotlib
        keys = sorted(rows)
        cols = min(3, len(keys))
        nrows = (len(keys) + cols - 1) // cols
        fig = _figure(max(4.6 * cols + 0.5, 10.0), 3.6 * nrows + 1.2)
        axes = fig.subplots(nrows, cols, squeeze=False)
        for ax in axes.flat[len(keys):]:
            ax.set_visible(False)
        cmap = matplotlib.colormaps["plasma"]
        for ax, key in zip(axes.flat, keys):
            alphas = sorted(rows[key])
            for n, a in enumerate(alphas):
                pts = sorted(rows[key][a], key=lambda p: p["theta_i"])
                col = cmap(0.85 * n / max(1, len(alphas) - 1))
                t = [p["theta_i"] for p in pts]
                ax.plot(t, [p["quad"] + p["beyond"] for p in pts], color=col, lw=1.3, marker="_", ms=8,
                        label=f"alpha {a:g}")
                ax.plot(t, [p["quad"] for p in pts], color=col, lw=0.8, ls="--")
                ax.errorbar(t, [p["est"] + p["beyond"] for p in pts], yerr=[p["se"] for p in pts], color=col,
                            marker="o", ms=3, ls="none", capsize=2)
                ax.plot(t, [p["ct"] for p in pts], color=col, lw=1.0, ls=":", marker="v", ms=3)
                ax.plot(t, [p["sim"] for p in pts], color=col, marker="x", ms=4, ls="none")
            ax.set_title(f"{key[0]}, {key[1]}", fontsize=9)
            ax.set_xlabel("theta_i (deg)")
            ax.set_ylabel("albedo (fraction of the incident flux)")
            ax.set_xlim(-3, 93)
            ax.set_ylim(0, 1.08)
            ax.legend(fontsize=6, loc="lower left")
        _suptitle(fig, f"{name}: white furnace (F = 1), albedo of Eq. 17 per alpha",
                  "solid: quadrature + light beyond max_k (must be 1); dashed: quadrature, k <= max_k; dots: "
                  "importance-sampled estimate + beyond (+- 1 standard error); dotted, triangles: Cook-Torrance (its loss); "
                  f"x: traced sanity line. {_title_bits(report)}")
        return fig

    def draw_errors() -> Figure:
        import numpy as np
        flat = [(key, a, p) for key in sorted(rows) for a in sorted(rows[key]) for p in rows[key][a]]
        fig = _figure(min(16.0, max(8.0, 0.12 * len(flat) + 4.0)), 6.5)
        a1, a2 = fig.subplots(2, 1, sharex=True)
        x = np.arange(len(flat))
        colors = {k: c for k, c in zip(sorted(rows), ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                                      "#8c564b"])}
        energy = np.array([max(abs(p["energy"]), 1e-17) for _, _, p in flat])
        z = np.array([abs(p["est_err"]) / p["se"] if p["se"] > 0 else 0.0 for _, _, p in flat])
        for key in sorted(rows):
            idx = [n for n, f in enumerate(flat) if f[0] == key]
            a1.plot(x[idx], energy[idx], "o", ms=3, color=colors[key], label=f"{key[0]}, {key[1]}")
            a2.plot(x[idx], z[idx], "o", ms=3, color=colors[key])
        for d, ls in zip(_DIMS, ("-", "--")):
            if d in tol and tol[d] > 0:
                a1.axhline(tol[d], color="red", lw=0.8, ls=ls, label=f"quadrature tolerance, {d}")
        if sigmas is not None:
            a2.axhline(sigmas, color="red", lw=0.8, label=f"{sigmas:g} standard errors")
        bad = [n for n, f in enumerate(flat) if not f[2]["pass"]]
        if bad:
            a1.plot(x[bad], energy[bad], "s", mfc="none", mec="red", ms=7, label="case fails")
        a1.set_yscale("log")
        a1.set_ylabel("|albedo + beyond max_k - 1|")
        a1.legend(fontsize=6, ncol=2)
        a2.set_ylabel("|estimate + beyond - 1| / standard error")
        a2.set_xlabel("case (dimension, ndf, alpha, theta_i as in the report)")
        a2.legend(fontsize=6)
        _suptitle(fig, f"{name}: white furnace errors per case (quadrature above, importance sampling below)",
                  _title_bits(report))
        return fig

    return [("", draw_albedo), ("-errors", draw_errors)]


def furnace_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    return _furnace_drawers(report, safe_text(report["suite"].text()), report["cases"],
                            *_furnace_thresholds(report["inputs"] if report.has("inputs") else None))


def _furnace_thresholds(inputs: Optional[Node]) -> Tuple[Optional[Node], Optional[float]]:
    """The furnace's quadrature tolerances (per dimension) and sigmas, from its "inputs"."""
    if inputs is None:
        return None, None
    tol = inputs["quadrature_tolerance"] if inputs.has("quadrature_tolerance") else None
    return tol, (inputs["sigmas"].number(0.0) if inputs.has("sigmas") else None)


# Sampling: chi-square tables, variance per strategy, furnace -------------------------------------

def sampling_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    name = safe_text(report["suite"].text())
    tests = []
    for c in report["chi_square"].nonempty():
        t = c["table"]
        rows_e = t["row_edges"].numbers(lo=-1.0, hi=1.0, min_length=2)
        cols_e = t["col_edges"].numbers(lo=-4.0, hi=4.0, min_length=2)
        nr, nc = len(rows_e) - 1, len(cols_e) - 1
        obs = [r.numbers(nc, 0.0) for r in t["observed"].items()]
        exp = [r.numbers(nc, 0.0) for r in t["expected"].items()]
        if len(obs) != nr or len(exp) != nr:
            raise t.fail(f"has {len(obs)} observed and {len(exp)} expected rows, needs {nr}")
        tests.append({
            "dim": c["dimension"].one_of(_DIMS), "ndf": _ndf_label(c), "alpha": c["alpha"].number(0.0, 2.0),
            "theta_i": c["theta_i_deg"].number(-90.0, 90.0), "strategy": safe_text(c["strategy"].text(), 16),
            "model": " nonsymmetric" if c.has("model") and c["model"].text() == "vgroove-nonsymmetric" else "",
            "samples": c["samples"].number(1.0), "p": c["p_value"].number(0.0, 1.0), "dof": c["dof"].number(0.0),
            "stat": c["statistic"].number(0.0), "level": c["level"].number(0.0, 1.0), "pass": c["pass"].boolean(),
            "norm": c["normalization_error"].number(), "rows": rows_e, "cols": cols_e, "obs": obs, "exp": exp,
            "obs_none": t["observed_no_direction"].number(0.0), "exp_none": t["expected_no_direction"].number()})
    variance = []
    for v in report["variance"].items():
        strategies = []
        rows, timing = v["strategies"].nonempty(), v["timing"]["strategies"]
        for n, r in enumerate(rows):
            strategies.append((safe_text(r["strategy"].text(), 16), r["variance"].number(0.0),
                               timing[n]["ns_per_sample"].number(0.0)))
        ns = " nonsym." if v.has("model") and v["model"].text() == "vgroove-nonsymmetric" else ""
        variance.append({"label": f"{v['dimension'].one_of(_DIMS)}{ns} {_ndf_label(v)} "
                                  f"a {v['alpha'].number(0.0, 2.0):g} ti {v['theta_i_deg'].number(-90.0, 90.0):g}\n"
                                  f"{safe_text(v['fresnel'].text(), 24)}", "rows": strategies})

    def draw_chi2() -> Figure:
        import numpy as np
        cols = min(4, len(tests))
        nrows = (len(tests) + cols - 1) // cols
        fig = _figure(4.2 * cols + 0.5, 3.2 * nrows + 1.2)
        axes = fig.subplots(nrows, cols, squeeze=False)
        for ax in axes.flat[len(tests):]:
            ax.set_visible(False)
        for ax, t in zip(axes.flat, tests):
            exp = np.asarray(t["exp"], dtype=float)
            obs = np.asarray(t["obs"], dtype=float)
            if t["dim"] == "flatland":
                e = np.degrees(np.asarray(t["cols"]))
                x = (e[1:] + e[:-1]) / 2
                ax.bar(x, exp[0], width=np.diff(e), color="#bbbbbb", label="expected (pdf over the bin)")
                ax.errorbar(x, obs[0], yerr=np.sqrt(np.maximum(exp[0], 1.0)), fmt="o", ms=2, color="#1f77b4",
                            capsize=1, label="observed (+- sqrt(expected))")
                ax.set_xlabel("theta_o (deg)", fontsize=7)
            else:
                # Cells in row-major order: cos(theta_o) bands, phi_o within each.
                x = np.arange(exp.size)
                ax.bar(x, exp.ravel(), width=1.0, color="#bbbbbb", label="expected (pdf over the cell)")
                ax.errorbar(x, obs.ravel(), yerr=np.sqrt(np.maximum(exp.ravel(), 1.0)), fmt="o", ms=2,
                            color="#1f77b4", capsize=1, label="observed (+- sqrt(expected))")
                for r in range(1, len(t["rows"]) - 1):
                    ax.axvline(r * (len(t["cols"]) - 1) - 0.5, color="#999", lw=0.4)
                ax.set_xlabel("cell: cos(theta_o) band x phi_o bin", fontsize=7)
            ax.set_ylabel("samples per cell", fontsize=7)
            ax.tick_params(labelsize=6)
            verdict = "pass" if t["pass"] else "FAIL"
            ax.set_title(f"{t['dim']}{t['model']} {t['ndf']} alpha {t['alpha']:g} theta_i {t['theta_i']:g}, "
                         f"{t['strategy']}\n"
                         f"chi2 {t['stat']:.1f} dof {t['dof']:g} p {t['p']:.3g}; none {t['obs_none']:.0f} "
                         f"(exp {t['exp_none']:.1f}): {verdict}", fontsize=7,
                         color="black" if t["pass"] else "#d62728")
        axes.flat[0].legend(fontsize=5)
        _suptitle(fig, f"{name}: chi-square of the sampled directions against the sampler's pdf (Lee et al. 2018, "
                       "Sec. 6)", _title_bits(report))
        return fig

    def draw_variance() -> Figure:
        import numpy as np
        strategies = sorted({r[0] for v in variance for r in v["rows"]})
        fig = _figure(max(7.0, 1.1 * len(variance) + 3.0), 6.0)
        a1, a2 = fig.subplots(2, 1, sharex=True)
        x = np.arange(len(variance))
        w = 0.8 / max(1, len(strategies))
        for n, s in enumerate(strategies):
            var = [next((r[1] for r in v["rows"] if r[0] == s), np.nan) for v in variance]
            ns = [next((r[2] for r in v["rows"] if r[0] == s), np.nan) for v in variance]
            a1.bar(x + (n - (len(strategies) - 1) / 2) * w, np.maximum(var, 1e-30), w, label=s)
            a2.bar(x + (n - (len(strategies) - 1) / 2) * w, ns, w, label=s)
        a1.set_yscale("log")
        a1.set_ylabel("variance of rho cos / pdf (1e-30: zero)")
        a1.legend(fontsize=7, ncol=3)
        a2.set_yscale("log")
        a2.set_ylabel("time per sample (ns)")
        a2.set_xticks(x, [v["label"] for v in variance], fontsize=6)
        a2.set_xlabel("case (dimension, NDF, alpha, theta_i in deg; Fresnel)")
        _suptitle(fig, f"{name}: variance and cost of the estimator per sampling strategy", _title_bits(report))
        return fig

    figs: List[Tuple[str, Drawer]] = [("", draw_chi2)]
    if variance:
        figs.append(("-variance", draw_variance))
    if report.has("furnace") and report["furnace"]["cases"].value:
        f = report["furnace"]
        figs += [("-furnace" + s, d) for s, d in
                 _furnace_drawers(report, name, f["cases"], *_furnace_thresholds(f["inputs"] if f.has("inputs")
                                                                                  else None))]
    return figs


# Nonsymmetric grooves (Eq. 23) and anisotropy --------------------------------------------------

def nonsymmetric_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    groups: Dict[Tuple[str, str, str], List[Dict[str, Any]]] = {}
    summary = []
    for c in report["cases"].nonempty():
        ndf = c["ndf"].one_of(_NDFS)
        dim = c["dimension"].one_of(_DIMS)
        aniso = c["anisotropic_block"].boolean()
        pl = c["plane"]
        th = pl["theta_deg"].numbers(lo=-90.0, hi=90.0)
        n = len(th)
        p = {"ax": c["alpha_x"].number(0.0, 2.0), "ay": c["alpha_y"].number(0.0, 2.0),
             "theta_i": c["theta_i_deg"].number(-90.0, 90.0), "phi_i": c["phi_i_deg"].number(-360.0, 360.0),
             "partner": safe_text(c["partner"].text(), 16), "other": safe_text(c["other_partner"].text(), 16),
             "theta": th, "sim": pl["sim"].numbers(n, 0.0), "model": pl["model"].numbers(n),
             "other_model": pl["other_model"].numbers(n), "unit": safe_text(pl["unit"].text()),
             "l1": c["l1"].number(0.0, 2.0), "thr": c["l1_threshold"].number(0.0),
             "l1_other": c["l1_other_model"].number(0.0, 2.0), "pass": c["pass"].boolean(),
             "rejected": c["other_model_rejected"].boolean(), "rays": c["rays"].number(0.0)}
        if aniso:
            p["row"], p["col"] = (p["ay"], f"phi_i {p['phi_i']:g} deg, {p['partner']}")
            p["title"] = f"alpha {p['ax']:g} x {p['ay']:g}, phi_i {p['phi_i']:g}, theta_i {p['theta_i']:g}"
        else:
            p["row"], p["col"] = (p["theta_i"], p["ax"])
            p["title"] = f"alpha {p['ax']:g}, theta_i {p['theta_i']:g} deg"
        groups.setdefault(("-aniso" if aniso else "", ndf, dim), []).append(p)
        summary.append((ndf, dim, aniso, p))
    name = safe_text(report["suite"].text())

    def grid(block: str, ndf: str, dim: str, panels: List[Dict[str, Any]]) -> Drawer:
        def draw() -> Figure:
            import numpy as np
            rows = sorted({p["row"] for p in panels})
            cols = sorted({p["col"] for p in panels}, key=str)
            fig = _figure(3.0 * len(cols) + 1.0, 2.3 * len(rows) + 1.4)
            axes = fig.subplots(len(rows), len(cols), squeeze=False)
            for ax in axes.flat:
                ax.set_visible(False)
            for p in panels:
                ax = axes[rows.index(p["row"])][cols.index(p["col"])]
                ax.set_visible(True)
                th = np.asarray(p["theta"])
                width = float(np.min(np.abs(np.diff(th)))) if len(th) > 1 else 1.0
                ax.bar(th, p["sim"], width=width, color="#8fd18f", label="traced")
                ax.plot(th, p["other_model"], color="black", lw=1.0, ls=":", label="the other partner law's model")
                ax.plot(th, p["model"], color="#d62728", lw=1.4, label="model (Eq. 23)")
                ax.set_xlim(-90, 90)
                ax.set_ylim(0, 1.08 * max(max(p["sim"]), max(p["model"]), 1e-300))
                ax.set_title(p["title"] + ("" if not block else f", {p['partner']}"), fontsize=7)
                ax.text(0.02, 0.97, f"L1 {p['l1']:.4f} (thr {p['thr']:.4f})\nother {p['l1_other']:.4f}"
                        f"{' rejected' if p['rejected'] else ''}", transform=ax.transAxes, fontsize=6, va="top",
                        color="#555" if p["pass"] else "#d62728")
                ax.tick_params(labelsize=6)
                ax.set_xlabel("theta_o (deg; < 0: mirror side)", fontsize=7)
                ax.set_ylabel(p["unit"].replace("fraction of the flux", "flux"), fontsize=7)
            next(a for a in axes.flat if a.get_visible()).legend(fontsize=5, loc="upper right")
            what = "anisotropic" if block else "nonsymmetric grooves"
            _suptitle(fig, f"{name}: {ndf}, {dim}, {what} (Lee et al. 2018, Eq. 23): lobe on the plane of incidence",
                      _title_bits(report))
            return fig
        return draw

    def draw_summary() -> Figure:
        import numpy as np
        fig = _figure(min(16.0, max(8.0, 0.1 * len(summary) + 4.0)), 4.6)
        ax = fig.subplots()
        x = np.arange(len(summary))
        ratio = np.array([p["l1"] / p["thr"] if p["thr"] > 0 else 0.0 for *_, p in summary])
        other = np.array([p["l1_other"] / p["thr"] if p["thr"] > 0 else 0.0 for *_, p in summary])
        ax.plot(x, np.maximum(ratio, 1e-6), "o", ms=3, label="model (Eq. 23)")
        ax.plot(x, np.maximum(other, 1e-6), "x", ms=4, label="the other partner law's model")
        ax.axhline(1.0, color="red", lw=1, label="threshold")
        ax.set_yscale("log")
        ax.set_xlabel("case (as in the report: dimension, ndf, alpha, theta_i; then the anisotropic block)")
        ax.set_ylabel("L1 / threshold (> 1 fails)")
        ax.legend(fontsize=7)
        _suptitle(fig, f"{name}: L1 of the lobes against the traced surfaces, per case", _title_bits(report))
        return fig

    figs: List[Tuple[str, Drawer]] = [("", draw_summary)]
    for (block, ndf, dim), panels in groups.items():
        figs.append((f"{block}-{ndf}-{dim}", grid(block, ndf, dim, panels)))
    return figs


# Profiles: masking and lobes beyond V-grooves ---------------------------------------------------

def _row_sums(rows: Node, bins: int) -> List[float]:
    """The sum over the k rows of a (rows x bins) table: the lobe over every k."""
    out = [0.0] * bins
    for r in rows.nonempty():
        for b, v in enumerate(r.numbers(bins, 0.0)):
            out[b] += v
    return out


def profiles_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    bins = report["bins"]
    normal_edges = bins["normal_deg_edges"].numbers(lo=-90.0, hi=90.0, min_length=2)
    exit_edges = bins["exit_deg_edges"].numbers(lo=-90.0, hi=90.0, min_length=2)
    nn, ne = len(normal_edges) - 1, len(exit_edges) - 1
    cases = []
    for c in report["cases"].nonempty():
        surfaces = []
        for sf in c["surfaces"].nonempty():
            g1 = sf["g1"]
            surfaces.append({
                "surface": safe_text(sf["surface"].text(), 16), "pass": sf["pass"].boolean(),
                # G1 is undefined (null) in bins no facet normal fell into.
                "g1": g1["traced"].numbers_or_gaps(nn), "g1_se": g1["traced_se"].numbers_or_gaps(nn, 0.0),
                "g1_vcavity": g1["vcavity"].numbers_or_gaps(nn), "g1_smith": g1["smith"].number(),
                "lobe": _row_sums(sf["lobe"]["traced_by_k"], ne)})
        cases.append({"ndf": c["ndf"].one_of(_NDFS), "alpha": c["alpha"].number(0.0, 2.0),
                      "theta": c["theta_deg"].number(-90.0, 90.0), "pass": c["pass"].boolean(),
                      "walk": _row_sums(c["walk"]["lobe_by_k"], ne),
                      "model": _row_sums(c["vgroove_model"]["lobe_by_k"], ne), "surfaces": surfaces})
    name = safe_text(report["suite"].text())
    colors = ["#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd"]

    def layout(width: float, height: float):
        rows = sorted({(c["ndf"], c["alpha"]) for c in cases})
        cols = sorted({c["theta"] for c in cases})
        fig = _figure(width * len(cols) + 1.0, height * len(rows) + 1.4)
        axes = fig.subplots(len(rows), len(cols), squeeze=False)
        for ax in axes.flat:
            ax.set_visible(False)
        return fig, [(axes[rows.index((c["ndf"], c["alpha"]))][cols.index(c["theta"])], c) for c in cases]

    def centres(edges: List[float]) -> List[float]:
        return [(a + b) / 2 for a, b in zip(edges[:-1], edges[1:])]

    def draw_masking() -> Figure:
        fig, panels = layout(3.2, 2.5)
        x = centres(normal_edges)
        for ax, c in panels:
            ax.set_visible(True)
            for n, sf in enumerate(c["surfaces"]):
                col = colors[n % 4]
                ax.errorbar(x, sf["g1"], yerr=sf["g1_se"], fmt="o", ms=2, color=col, capsize=1,
                            label=f"traced, {sf['surface']} profile")
                ax.plot(x, sf["g1_vcavity"], color=col, lw=0.9, ls="--", label=f"V-cavity, {sf['surface']}")
            if c["surfaces"]:
                ax.axhline(c["surfaces"][0]["g1_smith"], color="black", lw=0.8, ls=":", label="Smith")
            ax.set_ylim(-0.02, 1.05)
            ax.set_title(f"{c['ndf']} alpha {c['alpha']:g}, view {c['theta']:g} deg", fontsize=7,
                         color="black" if c["pass"] else "#d62728")
            ax.set_xlabel("microfacet normal angle m (deg)", fontsize=7)
            ax.set_ylabel("G1(view, m)", fontsize=7)
            ax.tick_params(labelsize=6)
        next(a for a in fig.axes if a.get_visible()).legend(fontsize=5)
        _suptitle(fig, f"{name}: masking G1 per facet normal on traced profiles, V-cavity and Smith",
                  _title_bits(report))
        return fig

    def draw_lobes() -> Figure:
        import numpy as np
        fig, panels = layout(3.2, 2.5)
        x = np.asarray(centres(exit_edges))
        width = float(np.min(np.diff(exit_edges)))
        for ax, c in panels:
            ax.set_visible(True)
            for n, sf in enumerate(c["surfaces"]):
                ax.step(x, sf["lobe"], where="mid", color=colors[n % 4], lw=1.0, label=f"traced, {sf['surface']}")
            ax.plot(x, c["walk"], color="black", lw=0.9, ls=":", label="Smith random walk")
            ax.plot(x, c["model"], color="#d62728", lw=1.2, ls="--", label="V-groove model")
            ax.set_xlim(-90, 90)
            ax.set_title(f"{c['ndf']} alpha {c['alpha']:g}, theta_i {c['theta']:g} deg", fontsize=7,
                         color="black" if c["pass"] else "#d62728")
            ax.set_xlabel("exit angle (deg)", fontsize=7)
            ax.set_ylabel(f"flux per {width:g} deg bin", fontsize=7)
            ax.tick_params(labelsize=6)
        next(a for a in fig.axes if a.get_visible()).legend(fontsize=5)
        _suptitle(fig, f"{name}: flatland lobes (every k) on traced profiles, the random walk and the V-groove model",
                  _title_bits(report))
        return fig

    return [("", draw_masking), ("-lobes", draw_lobes)]


# The energy audit: error maps of the compensation formulas -------------------------------------------

def _number_or_nan(n: Node, lo: float = -math.inf, hi: float = math.inf) -> float:
    """A report's exact double: a number, or "nan" where the value is undefined (a gap, not drawn)."""
    if n.value == "nan":
        return math.nan
    return n.number(lo, hi)


def energy_audit_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    grid = report["grid"]
    ndfs = [n.one_of(("ggx", "beckmann")) for n in grid["ndf"].nonempty()]
    alphas = grid["alpha"].numbers(lo=0.0, hi=2.0)
    mus = grid["mu"].numbers(lo=0.0, hi=1.0)
    channels = report["channels"].nonempty()
    grey = [c for c, ch in enumerate(channels) if ch["group"].text() == "grey"]
    if not grey:
        raise report["channels"].fail("has no channel of group \"grey\"")
    grey_F0 = [channels[c]["F0"].number(0.0, 1.0) for c in grey]
    variants = [safe_text(v["id"].text(), 40) for v in report["variants"].nonempty()]
    errors = report["errors"]
    if not isinstance(errors.value, dict) or not errors.value:
        raise errors.fail("is not an object of the formulas' errors")
    refs = ("vgroove", "smith_walk")
    # maps[(ref, ndf)] = [(variant, worst signed error over grey F0 [alpha][mu], its F0 [alpha][mu])]
    maps: Dict[Tuple[str, str], List[Tuple[str, List[List[float]], List[List[float]]]]] = {}
    for v, vid in enumerate(variants):
        raw = report["variants"][v]["id"].text()
        if not errors.has(raw):
            continue
        for ref in refs:
            if not errors[raw].has(ref):
                continue
            by_ndf = errors[raw][ref]
            if len(by_ndf.items()) != len(ndfs):
                raise by_ndf.fail(f"has {len(by_ndf.items())} NDFs, the grid {len(ndfs)}")
            for d, ndf in enumerate(ndfs):
                e_map, f_map = [], []
                rows = by_ndf[d].items()
                if len(rows) != len(alphas):
                    raise by_ndf[d].fail(f"has {len(rows)} alpha rows, the grid {len(alphas)}")
                for a, row in enumerate(rows):
                    cells = row.items()
                    if len(cells) != len(mus):
                        raise row.fail(f"has {len(cells)} mu values, the grid {len(mus)}")
                    e_row, f_row = [], []
                    for cell in cells:
                        if len(cell.items()) != len(channels):
                            raise cell.fail(f"has {len(cell.items())} channels, the report {len(channels)}")
                        vals = [_number_or_nan(cell[c], -4.0, 4.0) for c in grey]
                        finite = [(abs(x), x, f) for x, f in zip(vals, grey_F0) if math.isfinite(x)]
                        if finite:
                            _, x, f = max(finite)
                            e_row.append(x)
                            f_row.append(f)
                        else:
                            e_row.append(math.nan)
                            f_row.append(math.nan)
                    e_map.append(e_row)
                    f_map.append(f_row)
                maps.setdefault((ref, ndf), []).append((vid, e_map, f_map))
    if not maps:
        raise errors.fail("holds no formula's errors against vgroove or smith_walk")
    name = safe_text(report["suite"].text())
    what = {"vgroove": "the V-groove model (formulas fed with the V-cavity single scattering)",
            "smith_walk": "the Smith random walk (formulas fed with Smith's height-correlated single scattering; "
                          "@moonray_table with the separable one)"}

    def drawer(ref: str, ndf: str, panels: List[Tuple[str, List[List[float]], List[List[float]]]]) -> Drawer:
        def draw() -> Figure:
            import numpy as np
            from matplotlib.colors import TwoSlopeNorm
            cols = min(4, len(panels))
            rows = (len(panels) + cols - 1) // cols
            fig = _figure(3.4 * cols + 1.2, 2.9 * rows + 1.2)
            axes = fig.subplots(rows, cols, squeeze=False)
            # The colour scale spans the compensated formulas' errors; the uncompensated lobe
            # ("single", several times larger) saturates it (its panel title gives its worst).
            def largest(ps):
                xs = [abs(x) for _, e, _ in ps for r in e for x in r if math.isfinite(x)]
                return max(xs) if xs else 0.0
            lim = largest([p for p in panels if p[0] != "single"]) or largest(panels) or 1.0
            norm = TwoSlopeNorm(0.0, -lim, lim)
            mesh = None
            for k, ax in enumerate(axes.flat):
                if k >= len(panels):
                    ax.set_axis_off()
                    continue
                vid, e, _ = panels[k]
                z = np.ma.masked_invalid(np.asarray(e, dtype=float))
                mesh = ax.pcolormesh(_edges(mus) if len(mus) > 1 else [mus[0] - 0.5, mus[0] + 0.5],
                                     _edges(alphas) if len(alphas) > 1 else [alphas[0] - 0.5, alphas[0] + 0.5],
                                     z, cmap="RdBu_r", norm=norm, shading="flat")
                worst = float(np.nanmax(np.abs(z.filled(np.nan)))) if z.count() else math.nan
                ax.set_title(f"{vid}: worst |error| {worst:.3g}", fontsize=8)
                ax.set_xlabel("mu = cos theta", fontsize=8)
                ax.set_ylabel("alpha", fontsize=8)
                ax.tick_params(labelsize=7)
            if mesh is not None:
                cb = fig.colorbar(mesh, ax=axes, shrink=0.8, extend="both")
                cb.set_label("albedo of the formula minus the exact one (red: too bright, blue: too dark)")
            _suptitle(fig, f"{name}: energy compensation against {what[ref]}, {ndf}",
                      f"each cell: the grey Schlick F0 ({', '.join(f'{f:g}' for f in grey_F0)}) with the largest "
                      f"|error|; {_title_bits(report)}")
            return fig
        return draw

    return [(f"-{ref.replace('_', '-')}-{ndf}", drawer(ref, ndf, panels)) for (ref, ndf), panels in maps.items()]


# Rough glass (`vgroove energy --eta`): error maps of the compensation forms ------------------------

_GLASS_QUANTITIES = ("R", "T", "R+T")


def glass_energy_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    """One figure per (NDF, side, eta): rows R', T', R' + T', one column per form, each cell the
    form minus the traced value over (mu, alpha) as the report's error_maps hold it; a circle marks
    a cell within noise (|z| at most the z_threshold of the form's summary line for that side)."""
    kc = report["kulla_conty_glass"]
    if not kc.has("error_maps"):
        raise kc.fail("has no \"error_maps\" (the forms are audited on 3D cells only, not in the conductor limit)")
    maps = kc["error_maps"]
    shape = [int(x) for x in maps["shape"].numbers(5, lo=1.0)]
    axes = maps["axes"]
    ndfs = [n.one_of(("ggx", "beckmann")) for n in axes["ndf"].nonempty()]
    sides = [x.one_of(("above", "below")) for x in axes["side"].nonempty()]
    etas = axes["eta"].numbers(lo=0.0)
    alphas = axes["alpha"].numbers(lo=0.0, hi=2.0)
    mus = axes["mu"].numbers(lo=0.0, hi=1.0)
    if [len(ndfs), len(sides), len(etas), len(alphas), len(mus)] != shape:
        raise maps["shape"].fail(f"is {shape}, the axes {[len(ndfs), len(sides), len(etas), len(alphas), len(mus)]}")
    size = shape[0] * shape[1] * shape[2] * shape[3] * shape[4]
    forms = [f["id"].text() for f in kc["forms"].nonempty()]
    threshold: Dict[Tuple[str, str, str], float] = {}
    for line in kc["summary"].items():
        if line["region"].text() == "all":
            threshold[(line["form"].text(), line["side"].text(), line["quantity"].text())] = \
                line["z_threshold"].number(0.0)
    values: Dict[Tuple[str, str], Tuple[List[float], List[float]]] = {}
    for f in forms:
        fm = maps["forms"][f]
        for q in _GLASS_QUANTITIES:
            err = fm[q]["error"].numbers_or_gaps(size, -4.0, 4.0)
            z = fm[q]["z"].numbers_or_gaps(size)
            values[(f, q)] = (err, z)
    reference = safe_text(report["grid"]["reference"].text(), 24) if report["grid"].has("reference") else "vgroove"

    def panel(err: List[float], n: int, s: int, e: int) -> List[List[float]]:
        base_i = ((n * shape[1] + s) * shape[2] + e) * shape[3]
        return [[err[(base_i + a) * shape[4] + u] for u in range(shape[4])] for a in range(shape[3])]

    def drawer(n: int, s: int, e: int) -> Drawer:
        def draw() -> Figure:
            import numpy as np
            from matplotlib.colors import TwoSlopeNorm
            fig = _figure(3.2 * len(forms) + 1.6, 2.8 * len(_GLASS_QUANTITIES) + 1.2)
            grid = fig.subplots(len(_GLASS_QUANTITIES), len(forms), squeeze=False)
            xe = _edges(mus) if len(mus) > 1 else [mus[0] - 0.5, mus[0] + 0.5]
            ye = _edges(alphas) if len(alphas) > 1 else [alphas[0] - 0.5, alphas[0] + 0.5]
            for qi, q in enumerate(_GLASS_QUANTITIES):
                panels = [(f, np.ma.masked_invalid(np.asarray(panel(values[(f, q)][0], n, s, e), dtype=float)),
                           np.asarray(panel(values[(f, q)][1], n, s, e), dtype=float)) for f in forms]
                lim = max([float(np.nanmax(np.abs(p.filled(np.nan)))) for _, p, _ in panels if p.count()] or [0.0])
                norm = TwoSlopeNorm(0.0, -(lim or 1.0), lim or 1.0)
                mesh = None
                for fi, (f, err, z) in enumerate(panels):
                    ax = grid[qi][fi]
                    mesh = ax.pcolormesh(xe, ye, err, cmap="RdBu_r", norm=norm, shading="flat")
                    zm = threshold.get((f, sides[s], q), math.nan)
                    within = [(mus[u], alphas[a]) for a in range(len(alphas)) for u in range(len(mus))
                              if math.isfinite(z[a][u]) and abs(z[a][u]) <= zm]
                    if within:
                        ax.scatter([w[0] for w in within], [w[1] for w in within], s=18, facecolors="none",
                                   edgecolors="black", linewidths=0.8)
                    if err.count():
                        k = int(np.nanargmax(np.abs(err.filled(np.nan))))
                        worst, wz = float(err.flat[k]), float(z.flat[k])
                        ax.set_title(f"{safe_text(f, 24)} {q}': worst {worst:+.3g} ({wz:+.1f} se)", fontsize=8)
                    else:
                        ax.set_title(f"{safe_text(f, 24)} {q}': no cell", fontsize=8)
                    ax.set_xlabel("mu = cos theta", fontsize=8)
                    ax.set_ylabel("alpha", fontsize=8)
                    ax.tick_params(labelsize=7)
                if mesh is not None:
                    cb = fig.colorbar(mesh, ax=list(grid[qi]), shrink=0.85, extend="both")
                    cb.set_label(f"{q}' - traced", fontsize=8)
            _suptitle(fig, f"Rough-glass compensation against {reference}: {ndfs[n]}, light from {sides[s]}, "
                           f"eta {etas[e]:g}",
                      f"cells: the form minus the traced albedo (red: too bright, blue: too dark); circles: within "
                      f"noise (|z| <= the form's z_threshold over the grid); {_title_bits(report)}")
            return fig
        return draw

    out = []
    for n, ndf in enumerate(ndfs):
        for s, side in enumerate(sides):
            for e, eta in enumerate(etas):
                tag = f"{eta:g}".replace(".", "p").replace("+", "").replace("-", "m")
                out.append((f"-{ndf}-{side}-eta-{tag}".lower(), drawer(n, s, e)))
    return out


# Table 2 -------------------------------------------------------------------------------------------

def table2_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    entries = []
    for e in report["entries"].nonempty():
        entries.append((e["percentile"].number(0.0, 100.0), e["ndf"].one_of(("ggx", "beckmann", "phong")),
                        e["alpha"].number(0.0, 2.0), e["paper"].number(0.0, 1e12), e["ours"].number(0.0, 1e12),
                        e["traced_percentile_k"].number(0.0, 1e12)))
    name = safe_text(report["suite"].text())

    def draw() -> Figure:
        import numpy as np
        fig = _figure(max(6.0, 0.5 * len(entries) + 2.0), 4.5)
        ax = fig.subplots()
        x = np.arange(len(entries))
        ax.bar(x - 0.27, [e[3] for e in entries], 0.27, label="paper (Table 2)", color="#bbbbbb")
        ax.bar(x, [e[4] for e in entries], 0.27, label="rule, ours", color="#1f77b4")
        ax.bar(x + 0.27, [e[5] for e in entries], 0.27, label="traced percentile", color="#2ca02c")
        ax.set_xticks(x, [f"{e[1]} {e[2]:g}\n{e[0]:g}%" for e in entries], fontsize=6)
        ax.set_ylabel("bounce count k at the percentile")
        ax.set_xlabel("NDF, alpha, percentile of D")
        ax.legend(fontsize=8)
        _suptitle(fig, f"{name}: bounce counts at percentiles of D (Lee et al. 2018, Table 2)", _title_bits(report))
        return fig

    return [("", draw)]


# Accuracy against time and the cost curve ---------------------------------------------------------

def accuracy_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    lines: Dict[str, List[Tuple[float, float, float, float]]] = {}
    for r in report["runs"].nonempty():
        p = (r["wall_s"].number(0.0), r["max_l1"].number(0.0, 2.0), r["mean_l1"].number(0.0, 2.0),
             r["rays_per_facet"].number(1.0))
        if p[0] > 0 and p[1] > 0 and p[2] > 0:  # log axes
            lines.setdefault(safe_text(r["sampling"].text(), 24), []).append(p)
    if not lines:
        raise report["runs"].fail("has no run with positive wall time and errors to draw on log axes")
    name = safe_text(report["suite"].text())
    thr = report["thresholds"] if report.has("thresholds") else None
    thresholds = (thr["max_l1"].number(0.0), thr["mean_l1"].number(0.0)) if thr is not None else None
    cost = []
    if report.has("cost_vs_theta_v"):
        for p in report["cost_vs_theta_v"]["points"].nonempty():
            q = (p["theta_v_deg"].number(0.0, 180.0), p["tracer_ns_per_ray"].number(0.0),
                 p["model_ns_per_eval"].number(0.0))
            if min(q) > 0:
                cost.append(q)

    def draw_accuracy() -> Figure:
        fig = _figure(7.5, 5.0)
        ax = fig.subplots()
        colors = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd"]
        for n, (s, pts) in enumerate(sorted(lines.items())):
            pts = sorted(pts)
            c = colors[n % 4]
            ax.plot([p[0] for p in pts], [p[1] for p in pts], color=c, marker="o", label=f"{s}, max L1")
            ax.plot([p[0] for p in pts], [p[2] for p in pts], color=c, marker="o", ls="--", label=f"{s}, mean L1")
            for p in pts:
                ax.annotate(f"N={p[3]:.0f}", (p[0], p[1]), fontsize=7, xytext=(3, 3), textcoords="offset points")
        if thresholds is not None:
            for t, ls in zip(thresholds, ("-", "--")):
                if t > 0:
                    ax.axhline(t, color="gray", lw=0.8, ls=ls)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("wall time (s)")
        ax.set_ylabel("L1 error (fraction of the rays)")
        ax.legend(fontsize=8)
        _suptitle(fig, f"{name}: L1 error against wall time (gray: the suite's thresholds)", _title_bits(report))
        return fig

    def draw_cost() -> Figure:
        fig = _figure(7.5, 4.5)
        ax = fig.subplots()
        cost.sort()
        ax.plot([c[0] for c in cost], [c[1] for c in cost], marker="o", label="tracer, per ray")
        ax.plot([c[0] for c in cost], [c[2] for c in cost], marker="o", label="model Eq. 4-6, per evaluation")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("theta_v (deg)")
        ax.set_ylabel("time (ns)")
        ax.legend(fontsize=8)
        _suptitle(fig, f"{name}: cost against aperture, one thread", _title_bits(report))
        return fig

    return [("", draw_accuracy)] + ([("-cost", draw_cost)] if cost else [])


# check_brdf and model tables --------------------------------------------------------------------
# A BRDF of the user's (check_brdf) or a table of its bin fluxes (validate --model-table) against
# the traced lobes: per incidence the L1 distances over their thresholds, the albedos, and the
# bins where the two differ most.

def _verdict_case(c: Node, theta_i: Optional[Node] = None) -> Dict[str, Any]:
    worst = [(w["theta_o_deg"].number(-90.0, 90.0), w["phi_o_deg"].number(-180.0, 180.0), w["sim"].number(),
              w["model"].number()) for w in c["worst_bins"].items()]
    theta = (theta_i if theta_i is not None else c["theta_i_deg"]).number(-90.0, 90.0)
    return {"theta_i": theta, "l1": c["l1"].number(), "l1_thr": c["l1_threshold"].number(),
            "flux": c["l1_flux"].number(), "flux_thr": c["l1_flux_threshold"].number(),
            "a_sim": c["albedo_sim"].number(), "a_model": c["albedo_model"].number(),
            "a_thr": c["albedo_threshold"].number(), "pass": c["pass"].boolean(), "worst": worst}


def _verdict_drawer(report: Node, title: str, series: Dict[str, List[Dict[str, Any]]], model: str) -> Drawer:
    """Three panels for the cases of one or more series (a label each: an alpha, or "" alone)."""
    def draw() -> Figure:
        import numpy as np
        fig = _figure(12.0, 4.2)
        a1, a2, a3 = fig.subplots(1, 3)
        colors = ["#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2"]
        for n, (label, cases) in enumerate(series.items()):
            cases = sorted(cases, key=lambda c: c["theta_i"])
            col = colors[n % len(colors)]
            tag = f" ({label})" if label else ""
            t = np.array([c["theta_i"] for c in cases])
            a1.plot(t, [c["l1"] / c["l1_thr"] if c["l1_thr"] > 0 else 0 for c in cases], "o-", color=col,
                    label=f"lobe shape{tag}")
            a1.plot(t, [c["flux"] / c["flux_thr"] if c["flux_thr"] > 0 else 0 for c in cases], "s--", color=col,
                    label=f"flux per bin{tag}")
            a2.errorbar(t, [c["a_sim"] for c in cases], yerr=[c["a_thr"] for c in cases], fmt="o", capsize=3,
                        color=col, label=f"traced (+- threshold){tag}")
            a2.plot(t, [c["a_model"] for c in cases], "x-", color=col, alpha=0.7, label=f"{model}{tag}")
            for c in cases:
                for w in c["worst"]:
                    a3.scatter(w[1], w[0], s=12 + 4000 * abs(w[2] - w[3]), alpha=0.5,
                               color="#d62728" if w[3] > w[2] else "#1f77b4")
        a1.axhline(1.0, color="red", lw=1)
        a1.set_xlabel("theta_i (deg)")
        a1.set_ylabel("L1 / threshold (> 1 fails)")
        a1.legend(fontsize=7)
        a2.set_xlabel("theta_i (deg)")
        a2.set_ylabel("albedo (fraction of the incident flux)")
        a2.legend(fontsize=7)
        a3.set_xlim(-180, 180)
        a3.set_ylim(-90, 90)
        a3.set_xlabel("phi_o (deg; 0: mirror side)")
        a3.set_ylabel("theta_o (deg)")
        a3.set_title("worst bins (red: model too high, blue: too low)", fontsize=8)
        verdict = "PASS" if all(c["pass"] for cs in series.values() for c in cs) else "FAIL"
        _suptitle(fig, f"{title}: {verdict}", _title_bits(report))
        return fig

    return draw


def check_brdf_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    cases = [_verdict_case(c) for c in report["cases"].nonempty()]
    name = safe_text(report["name"].text()) if report.has("name") else "check_brdf"
    inputs = report["inputs"] if report.has("inputs") else None
    what = ""
    if inputs is not None and inputs.has("ndf") and inputs.has("alpha"):
        what = f" ({safe_text(inputs['ndf'].text(), 12)}, alpha {inputs['alpha'].number():g})"
    if not any(c.has("lobes") for c in report["cases"].nonempty()):
        return [("", _verdict_drawer(report, f"{name}{what}", {"": cases}, "the BRDF checked"))]
    # A BSDF (check_brdf with eta): both lobes as one, and the reflected and transmitted apart.
    series: Dict[str, List[Dict[str, Any]]] = {"R + T": cases}
    for c in report["cases"].nonempty():
        for s in c["lobes"].nonempty():
            series.setdefault(s["lobe"].one_of(("reflected", "transmitted")), []).append(
                _verdict_case(s, c["theta_i_deg"]))
    eta = f", eta {inputs['eta'].number():g} from {safe_text(inputs['side'].text(), 8)}" if inputs is not None and \
        inputs.has("eta") and inputs.has("side") else ""
    return [("", _verdict_drawer(report, f"{name}{what}{eta}", series, "the BSDF checked"))]


def model_table_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    """`vgroove validate SUITE --model-table TABLE`: one figure per NDF and dimension, a series per
    alpha. The table itself (its cases hold only fluxes) is not a report."""
    if not report["cases"].nonempty()[0].has("albedo_sim"):
        raise report.fail("is a model table, not a report: draw the report of "
                          "`vgroove validate SUITE --model-table TABLE --out REPORT`")
    groups: Dict[Tuple[str, str], Dict[str, List[Dict[str, Any]]]] = {}
    for c in report["cases"].nonempty():
        ndf = c["ndf"].one_of(_NDFS)
        dim = c["dimension"].one_of(_DIMS)
        alpha = c["alpha"].number(0.0, 2.0)
        groups.setdefault((ndf, dim), {}).setdefault(f"alpha {alpha:g}", []).append(_verdict_case(c))
    name = safe_text(report["suite"].text())
    model = safe_text(report["model"].text(), 40) if report.has("model") else "the model table"
    return [(f"-{ndf}-{dim}", _verdict_drawer(report, f"{name}, {ndf} {dim}: {model} against the traced lobes",
                                              series, model or "the model table"))
            for (ndf, dim), series in groups.items()]


_HF_MODELS = ("smith_walk", "cook_torrance_smith", "vgroove")
_HF_MARKS = {"1": "o-", "2": "s--", "3+": "^:"}


def heightfield_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    """The "heightfield" suite: one figure per NDF, a column per model."""
    groups: Dict[str, List[Dict[str, Any]]] = {}
    for c in report["cases"].nonempty():
        ndf = c["ndf"].one_of(_NDFS)
        case = {"alpha": c["alpha"].number(0.0, 2.0), "theta_i": c["theta_i_deg"].number(0.0, 90.0), "models": {}}
        for m in _HF_MODELS:
            rows = []
            if c[m].has("skipped"):  # an isotropic model on an anisotropic case: no lobe to draw
                case["models"][m] = rows
                continue
            for r in c[m]["against_traced"]["rows"].nonempty():
                rows.append((r["k"].one_of(tuple(_HF_MARKS)), r["l1"].number(0.0), r["l1_threshold"].number(0.0),
                             -r["energy_diff"].number(-1.0, 1.0), r["energy_threshold"].number(0.0)))
            case["models"][m] = rows
        groups.setdefault(ndf, []).append(case)
    name = safe_text(report["suite"].text())

    def drawer(ndf: str, cases: List[Dict[str, Any]]) -> Drawer:
        def draw() -> Figure:
            fig = _figure(13.0, 7.0)
            axes = fig.subplots(2, len(_HF_MODELS), squeeze=False)
            colors = ["#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2"]
            alphas = sorted({c["alpha"] for c in cases})
            for j, m in enumerate(_HF_MODELS):
                top, bottom = axes[0][j], axes[1][j]
                for n, a in enumerate(alphas):
                    sel = sorted((c for c in cases if c["alpha"] == a), key=lambda c: c["theta_i"])
                    for k in _HF_MARKS:
                        pts = [(c["theta_i"], r[1] / r[2] if r[2] > 0 else 0.0, r[3], r[4]) for c in sel
                               for r in c["models"][m] if r[0] == k]
                        if not pts:
                            continue
                        t = [p[0] for p in pts]
                        top.plot(t, [p[1] for p in pts], _HF_MARKS[k], color=colors[n % len(colors)],
                                 label=f"alpha {a:g}, k {k}")
                        bottom.errorbar(t, [p[2] for p in pts], yerr=[p[3] for p in pts], fmt=_HF_MARKS[k],
                                        capsize=2, color=colors[n % len(colors)])
                top.axhline(1.0, color="red", lw=1)
                top.set_yscale("log")
                top.set_title(m, fontsize=9)
                top.set_xlabel("theta_i (deg)")
                top.set_ylabel("L1 / threshold (<= 1: within noise)")
                bottom.axhline(0.0, color="black", lw=0.8)
                bottom.set_xlabel("theta_i (deg)")
                bottom.set_ylabel("E_k model - traced (bars: threshold)")
            axes[0][0].legend(fontsize=6, ncol=2)
            _suptitle(fig, f"{name}: {ndf} heightfields traced in 3D against three models",
                      "per k = 1, 2, 3+: the lobe's L1 over its noise threshold, and the energy's miss")
            return fig
        return draw

    out = [(f"-{ndf}", drawer(ndf, cases)) for ndf, cases in groups.items()]
    return out + _heightfield_lobe_figures(report, name) + _heightfield_masking_figures(report, name)


_HF_LOBE_MODELS = (("smith_walk", "Smith walk", "C1"), ("cook_torrance_smith", "Cook-Torrance, Smith G (k = 1)", "C2"),
                   ("vgroove", "V-groove model", "C3"))


def heightfield_theta_marginal(rows: Node, k: int, theta_bins: int, phi_bins: int, squared: bool = False) -> List[float]:
    """Row k of a lobe [k][t * phi_bins + p] summed over phi_o: one value per theta_o bin (with
    squared, the sum of squares, for standard errors)."""
    row = rows[k].numbers(theta_bins * phi_bins)
    f = (lambda v: v * v) if squared else (lambda v: v)
    return [sum(f(row[t * phi_bins + p]) for p in range(phi_bins)) for t in range(theta_bins)]


def _heightfield_lobe_figures(report: Node, name: str) -> List[Tuple[str, Drawer]]:
    """The "heightfield" suite's lobes per k: one figure per NDF, a row per case, a column per k =
    1, 2, 3+; the flux over theta_o (summed over phi_o), traced with 2 se bars (the bins' se
    combined as if independent) against each model's lobe as the report gives it."""
    tb, pb = (int(report["inputs"][key].number(1, 100000)) for key in ("theta_bins", "phi_bins"))
    groups: Dict[str, List[Node]] = {}
    for c in report["cases"].nonempty():
        groups.setdefault(c["ndf"].one_of(_NDFS), []).append(c)
    edges = [90.0 * t / tb for t in range(tb + 1)]
    centres = [0.5 * (edges[t] + edges[t + 1]) for t in range(tb)]
    rows_k = list(_HF_MARKS)

    def drawer(ndf: str, cases: List[Node]) -> Drawer:
        def draw() -> Figure:
            fig = _figure(11.0, 2.2 * len(cases) + 1.0)
            axes = fig.subplots(len(cases), len(rows_k), squeeze=False)
            for i, c in enumerate(cases):
                title = (f"alpha {c['alpha'].number():g}, theta_i {c['theta_i_deg'].number():g}"
                         + (f", aspect {c['aspect'].number():g}" if c.has("aspect") and c["aspect"].number() != 1 else ""))
                for k in range(len(rows_k)):
                    ax = axes[i][k]
                    traced = heightfield_theta_marginal(c["traced"]["lobe_by_k"], k, tb, pb)
                    se = [math.sqrt(v) for v in heightfield_theta_marginal(c["traced"]["lobe_se_by_k"], k, tb, pb, True)]
                    ax.errorbar(centres, traced, yerr=[2 * v for v in se], fmt="o", ms=3, capsize=2, color="black",
                                label="traced")
                    for key, label, color in _HF_LOBE_MODELS:
                        m = c[key]
                        if m.has("skipped"):
                            continue
                        if key == "cook_torrance_smith":
                            if k != 0:
                                continue
                            row = m["lobe_k1"].numbers(tb * pb)
                            y = [sum(row[t * pb + p] for p in range(pb)) for t in range(tb)]
                        else:
                            y = heightfield_theta_marginal(m["lobe_by_k"], k, tb, pb)
                        ax.plot(centres, y, "-", color=color, label=label)
                    ax.set_title(f"{title}: k {rows_k[k]}", fontsize=8)
                    ax.set_xlabel("theta_o (deg)", fontsize=7)
                    ax.tick_params(labelsize=7)
            axes[0][0].legend(fontsize=6)
            _suptitle(fig, f"{name}: {ndf} heightfields, the lobe per bounce order",
                      "flux per theta_o bin (summed over phi_o): traced (2 se) against each model")
            return fig
        return draw

    return [(f"-lobes-{ndf}", drawer(ndf, cases)) for ndf, cases in groups.items()]


def _heightfield_masking_figures(report: Node, name: str) -> List[Tuple[str, Drawer]]:
    """The "heightfield" suite's masking section: G1 per facet-normal bin (traced with its error
    over the fields, Smith, V-cavity), one figure per NDF, a row per alpha, a column per view
    angle (from each alpha's first case: G1 does not depend on theta_i)."""
    inputs = report["inputs"]
    if not inputs.has("masking"):
        return []
    m = inputs["masking"]
    tb = int(m["theta_m_bins"].number(1, 90))
    pb = int(m["phi_m_bins"].number(1, 360))
    bins = tb * pb
    groups: Dict[str, Dict[float, List[Dict[str, Any]]]] = {}
    for c in report["cases"].nonempty():
        if not c.has("masking"):
            continue
        ndf = c["ndf"].one_of(_NDFS)
        alpha = c["alpha"].number(0.0, 2.0)
        if alpha in groups.get(ndf, {}):
            continue
        views = []
        for g in c["masking"]["g1"].nonempty():
            t = g["theta_o_deg"].number(0.0, 90.0)
            if t <= 0.0:
                continue  # nothing hidden
            views.append({"theta_o": t, "g1": g["bins"].numbers_or_gaps(bins),
                          "se": g["bins_se"].numbers_or_gaps(bins, 0.0),
                          "smith": g["models"]["smith"]["value"].number(0.0, 1.0),
                          "vcavity": g["models"]["vcavity"]["bins"].numbers_or_gaps(bins)})
        groups.setdefault(ndf, {})[alpha] = views
    # The masking controls (the verdict): held / all, those that failed by name, and per G1 panel
    # (ndf, alpha, view) whether its controls held.
    held, failed, panel = 0, [], {}
    controls = report["masking_controls"].items() if report.has("masking_controls") else []
    for c in controls:
        ok = c["within_noise"].boolean()
        held += ok
        g = c["g"].one_of(("g1", "g2"))
        what = (f"{g.upper()} {safe_text(c['model'].text(), 40)} {c['ndf'].one_of(_NDFS)} alpha "
                f"{c['alpha'].number(0.0, 2.0):g} view {c['theta_o_deg'].number(0.0, 90.0):g}")
        if not ok:
            failed.append(what)
        if g == "g1":
            key = (c["ndf"].one_of(_NDFS), c["alpha"].number(0.0, 2.0), c["theta_o_deg"].number(0.0, 90.0))
            panel[key] = panel.get(key, True) and ok
    verdict = ""
    if controls:
        verdict = f"; masking controls: {held}/{len(controls)} within noise"
        if failed:
            verdict += " (NOT: " + "; ".join(failed) + ")"

    def drawer(ndf: str, by_alpha: Dict[float, List[Dict[str, Any]]]) -> Drawer:
        def draw() -> Figure:
            alphas = sorted(by_alpha)
            cols = sorted({v["theta_o"] for vs in by_alpha.values() for v in vs})
            fig = _figure(3.4 * max(1, len(cols)) + 1.0, 2.6 * len(alphas) + 1.4)
            axes = fig.subplots(len(alphas), max(1, len(cols)), squeeze=False)
            x = list(range(bins))
            labels = [f"{90 * t // tb}-{90 * (t + 1) // tb}\n{360 * p // pb}" for t in range(tb) for p in range(pb)]
            for r, a in enumerate(alphas):
                for v in by_alpha[a]:
                    ax = axes[r][cols.index(v["theta_o"])]
                    ax.errorbar(x, v["g1"], yerr=v["se"], fmt="o", ms=3, capsize=2, color="#1f77b4",
                                label="traced (se over fields)")
                    ax.plot(x, v["vcavity"], "s--", ms=3, lw=0.9, color="#ff7f0e", label="V-cavity")
                    ax.axhline(v["smith"], color="black", lw=0.8, ls=":", label="Smith")
                    ax.set_ylim(-0.02, 1.05)
                    ctl = panel.get((ndf, a, v["theta_o"]))
                    tag = "" if ctl is None else (", control held" if ctl else ", control NOT within noise")
                    ax.set_title(f"{ndf} alpha {a:g}, view {v['theta_o']:g} deg{tag}", fontsize=7,
                                 color="black" if ctl is not False else "#d62728")
                    ax.set_xticks(x)
                    ax.set_xticklabels(labels, fontsize=5)
                    ax.set_xlabel("facet normal bin: theta_m (deg), azimuth from the view (deg)", fontsize=6)
                    ax.set_ylabel("G1(view, m)", fontsize=7)
                    ax.tick_params(labelsize=6)
            axes[0][0].legend(fontsize=5)
            _suptitle(fig, f"{name}: masking G1 per facet-normal bin on traced heightfields, Smith and V-cavity",
                      _title_bits(report) + verdict)
            return fig
        return draw

    return [(f"-masking-{ndf}", drawer(ndf, by_alpha)) for ndf, by_alpha in groups.items()]


_HFA_ROWS = ("E", "E_1", "E_ms", "E_2", "E_3+")
_HFA_PANELS = ("E", "E_1", "E_ms")  # the rows drawn, one column each
_HFA_MODELS = {"smith_walk": ("-", "#1f77b4", "Smith walk"), "smith_ess": ("--", "black", "Smith E_ss (exact)"),
               "vgroove": (":", "#2ca02c", "V-groove model")}


def heightfield_albedo_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    """The "heightfield_albedo" suite: one figure per NDF, a row per alpha, columns E, E_1 and
    E_ms over mu: traced (the mean over the fields, bars 2 se) against each model's line."""
    groups: Dict[str, Dict[float, List[Dict[str, Any]]]] = {}
    for p in report["points"].nonempty():
        ndf = p["ndf"].one_of(_NDFS)
        alpha = p["alpha"].number(0.0, 2.0)
        point = {"mu": p["mu"].number(0.0, 1.0), "traced": p["traced"].numbers_or_gaps(len(_HFA_ROWS), 0.0, 1.0 + 1e-6),
                 "se": p["traced_se"].numbers_or_gaps(len(_HFA_ROWS), 0.0, 1.0),
                 "models": {m: p["models"][m]["value"].numbers_or_gaps(len(_HFA_ROWS), -1e-6, 1.0 + 1e-6)
                            for m in _HFA_MODELS}}
        groups.setdefault(ndf, {}).setdefault(alpha, []).append(point)
    name = safe_text(report["suite"].text())

    def drawer(ndf: str, by_alpha: Dict[float, List[Dict[str, Any]]]) -> Drawer:
        def draw() -> Figure:
            alphas = sorted(by_alpha)
            fig = _figure(3.6 * len(_HFA_PANELS) + 1.0, 2.3 * len(alphas) + 1.4)
            axes = fig.subplots(len(alphas), len(_HFA_PANELS), squeeze=False)
            for r, a in enumerate(alphas):
                pts = sorted(by_alpha[a], key=lambda q: q["mu"])
                mu = [q["mu"] for q in pts]
                for c, row in enumerate(_HFA_PANELS):
                    ax = axes[r][c]
                    i = _HFA_ROWS.index(row)
                    for m, (style, color, label) in _HFA_MODELS.items():
                        y = [q["models"][m][i] for q in pts]
                        if any(math.isfinite(v) for v in y):
                            ax.plot(mu, y, style, color=color, lw=1.0, label=label)
                    ax.errorbar(mu, [q["traced"][i] for q in pts], yerr=[2.0 * q["se"][i] for q in pts], fmt="o",
                                ms=3, capsize=2, color="#d62728", label="traced fields (2 se)")
                    if row == "E":  # 1 to rounding for every model and exactly 1 traced: no offset axis
                        ax.set_ylim(0.9, 1.05)
                        ax.ticklabel_format(axis="y", useOffset=False)
                    ax.set_title(f"{ndf} alpha {a:g}: {row}", fontsize=8)
                    ax.set_xlim(0.0, 1.02)
                    ax.set_xlabel("mu = cos theta_i", fontsize=7)
                    ax.tick_params(labelsize=6)
            axes[0][1].legend(fontsize=6)
            _suptitle(fig, f"{name}: albedo of {ndf} heightfields per bounce order, traced against three models",
                      "F = 1: E = 1 on the surface; E_1 single scattering, E_ms = E_2 + E_3+. " + _title_bits(report))
            return fig
        return draw

    return [(f"-{ndf}", drawer(ndf, by_alpha)) for ndf, by_alpha in groups.items()]


# Rough dielectrics: reflected and transmitted lobes against each model ----------------------------

_DIELECTRIC_MODELS = ("walter_vcavity", "walter_smith_separable", "walter_smith_correlated", "smith_walk",
                      "kaleidoscopic")


def _dielectric_curve(rows: Node, bins: int, dim: str, theta_bins: int, phi_bins: int, k: Optional[int]) -> List[float]:
    """One side's lobe: row k (None: every k summed); in 3D its theta marginal (summed over phi)."""
    table = [r.numbers(bins, 0.0) for r in rows.nonempty()]
    if k is not None and k >= len(table):
        raise rows.fail(f"has {len(table)} k rows, needs row {k}")
    v = table[k] if k is not None else [sum(col) for col in zip(*table)]
    if dim == "flatland":
        return v
    return [sum(v[t * phi_bins:(t + 1) * phi_bins]) for t in range(theta_bins)]


def dielectric_brdf_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    inputs = report["inputs"]
    fb = int(inputs["flatland_bins"].number(1))
    tb, pb = int(inputs["theta_bins"].number(1)), int(inputs["phi_bins"].number(1))
    groups: Dict[Tuple[str, str, str, str], List[Dict[str, Any]]] = {}
    for c in report["cases"].nonempty():
        dim = c["dimension"].one_of(("flatland", "3d"))
        bins = fb if dim == "flatland" else tb * pb
        case: Dict[str, Any] = {"alpha": c["alpha"].number(0.0, 2.0), "theta": c["theta_i_deg"].number(0.0, 90.0),
                                "eta": c["eta"].number(0.0), "pass": c["pass"].boolean(), "dim": dim, "sides": {},
                                "matching": [safe_text(m.text(), 32) for m in c["matching_models"].items()]}
        for side in ("reflected", "transmitted"):
            rows = c["traced"][side]["lobe_by_k"]
            models = {}
            for m in _DIELECTRIC_MODELS:
                if c["models"].has(m):
                    models[m] = _dielectric_curve(c["models"][m][side]["lobe_by_k"], bins, dim, tb, pb, None)
            case["sides"][side] = {"all": _dielectric_curve(rows, bins, dim, tb, pb, None),
                                   "k1": _dielectric_curve(rows, bins, dim, tb, pb, 1),
                                   "k2": _dielectric_curve(rows, bins, dim, tb, pb, 2), "models": models}
        key = (c["surface"].one_of(("vgroove", "profiles")), dim, c["ndf"].one_of(_NDFS), c["side"].one_of(("above", "below")))
        groups.setdefault(key, []).append(case)
    name = safe_text(report["suite"].text())
    colors = {"walter_vcavity": "#d62728", "walter_smith_separable": "#2ca02c",
              "walter_smith_correlated": "#1f77b4", "smith_walk": "#9467bd", "kaleidoscopic": "#ff7f0e"}

    def drawer(key: Tuple[str, str, str, str], cases: List[Dict[str, Any]]) -> Drawer:
        surface, dim, ndf, side = key

        def draw() -> Figure:
            rows = sorted({(c["alpha"], c["eta"]) for c in cases})
            cols = sorted({c["theta"] for c in cases})
            fig = _figure(2.6 * 2 * len(cols) + 1.0, 2.2 * len(rows) + 1.4)
            axes = fig.subplots(len(rows), 2 * len(cols), squeeze=False)
            for ax in axes.flat:
                ax.set_visible(False)
            if dim == "flatland":
                x = [-90.0 + (b + 0.5) * 180.0 / fb for b in range(fb)]
                xlabel = "exit angle from the exit side's normal (deg)"
            else:
                x = [(t + 0.5) * 90.0 / tb for t in range(tb)]
                xlabel = "theta_o from the exit side's normal (deg; summed over phi)"
            for c in cases:
                r = rows.index((c["alpha"], c["eta"]))
                for s, sname in enumerate(("reflected", "transmitted")):
                    ax = axes[r][2 * cols.index(c["theta"]) + s]
                    ax.set_visible(True)
                    d = c["sides"][sname]
                    ax.step(x, d["all"], where="mid", color="black", lw=1.1, label="traced, every k")
                    ax.step(x, d["k1"], where="mid", color="grey", lw=0.8, ls="--", label="traced, k = 1")
                    ax.step(x, d["k2"], where="mid", color="grey", lw=0.8, ls=":", label="traced, k = 2")
                    for m, v in d["models"].items():
                        ax.plot(x, v, color=colors[m], lw=0.9, label=m + (" (k = 1)" if m.startswith("walter") else ""))
                    ax.set_title(f"{sname}: alpha {c['alpha']:g}, eta {c['eta']:g}, theta_i {c['theta']:g}",
                                 fontsize=6, color="black" if c["pass"] else "#d62728")
                    ax.set_xlabel(xlabel, fontsize=6)
                    ax.set_ylabel("flux per bin", fontsize=6)
                    ax.tick_params(labelsize=5)
            next(a for a in fig.axes if a.get_visible()).legend(fontsize=5)
            _suptitle(fig, f"{name}: {surface} {dim} {ndf}, light from {side}: reflected and transmitted lobes, "
                           "traced per k against each model (red title: the tracer's checks failed)",
                      _title_bits(report))
            return fig
        return draw

    return [(f"-{s}-{d}-{n}-{side}", drawer((s, d, n, side), cs)) for (s, d, n, side), cs in groups.items()]


KINDS = {
    "single_grooves": single_groove_figures,
    "brdf": brdf_figures,
    "furnace": furnace_figures,
    "table2": table2_figures,
    "accuracy": accuracy_figures,
    "check_brdf": check_brdf_figures,
    "sampling": sampling_figures,
    "nonsymmetric_brdf": nonsymmetric_figures,
    "profiles": profiles_figures,
    "energy_audit": energy_audit_figures,
    "model_table": model_table_figures,
    "heightfield": heightfield_figures,
    "heightfield_albedo": heightfield_albedo_figures,
    "dielectric_brdf": dielectric_brdf_figures,
    "glass_energy": glass_energy_figures,
    # A new report kind adds a function here (and its name to report_kind).
}


def figures_for(report_json: Any, file: str) -> List[Tuple[str, Drawer]]:
    """Validates the report and returns (name suffix, draw) per figure; ReportError if it cannot be
    drawn. Nothing is rendered yet."""
    node = Node(report_json, file)
    figs = KINDS[report_kind(node)](node, file)
    for suffix, _ in figs:
        assert set(suffix) <= _NAME_CHARS, suffix
    return figs


def load_report(path: str) -> Any:
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise ReportError(f"{path}: cannot read: {e.strerror or e}") from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise ReportError(f"{path}: not UTF-8 text (byte {e.start})") from None

    def constant(name: str) -> Any:
        raise ReportError(f"{path}: {name} is not JSON")

    try:
        return json.loads(text, parse_constant=constant)
    except json.JSONDecodeError as e:
        raise ReportError(f"{path}: not JSON: {e.msg} at line {e.lineno} column {e.colno}") from None
    except RecursionError:
        raise ReportError(f"{path}: nested too deeply") from None


# ----------------------------------------------------------------------------------------------
# Output: all or nothing.

def output_base(report_path: str, out: Optional[str], fmt: Optional[str]) -> Tuple[str, str]:
    if out:
        root, ext = os.path.splitext(out)
        if ext.lstrip(".").lower() in FORMATS:
            if fmt and fmt != ext.lstrip(".").lower():
                raise ReportError(f"--out {out} and --format {fmt} disagree")
            return root, ext.lstrip(".").lower()
        return out, fmt or "png"
    root = report_path[:-5] if report_path.endswith(".json") else report_path
    return root, fmt or "png"


def render_all(figs: List[Tuple[str, Drawer]], base: str, fmt: str, force: bool) -> List[str]:
    """Renders every figure to a temporary file beside its target, then moves them all into place.
    Nothing is left behind when any figure fails; existing targets are replaced only with force."""
    targets = [f"{base}{suffix}.{fmt}" for suffix, _ in figs]
    for t in targets:
        if os.path.lexists(t) and not force:
            raise ReportError(f"{t} exists (use --force to overwrite)")
        if os.path.isdir(t):
            raise ReportError(f"{t} is a directory")
    temps: List[str] = []
    try:
        for (suffix, draw), target in zip(figs, targets):
            tmp = os.path.join(os.path.dirname(target) or ".",
                               f".{os.path.basename(target)}.tmp.{os.getpid()}")
            temps.append(tmp)
            fig = draw()
            try:
                fig.savefig(tmp, format=fmt, metadata=_metadata(fmt))
            except OSError as e:
                raise ReportError(f"{target}: cannot write: {e.strerror or e}") from None
        for tmp, target in zip(temps, targets):
            os.replace(tmp, target)
    except BaseException:
        for tmp in temps:
            try:
                os.unlink(tmp)
            except OSError:
                pass
        raise
    return targets


def _metadata(fmt: str) -> Dict[str, Any]:
    # Reproducible files: no creation date, the same bytes for the same report.
    if fmt == "png":
        return {"Software": "vgroove (matplotlib)"}
    if fmt == "svg":
        return {"Date": None}
    return {"CreationDate": None}


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(
        prog="vgroove plot", description="Draw a vgroove report (from its JSON alone) with matplotlib.")
    parser.add_argument("report", help="report JSON (vgroove validate --out, vgroove bench accuracy --out, "
                                       "check_brdf)")
    parser.add_argument("--out", help="output file or base name (default: the report's name); "
                                      "figures beyond the first get a suffix")
    parser.add_argument("--format", choices=FORMATS, help="png (default), svg or pdf")
    parser.add_argument("--force", action="store_true", help="overwrite existing files")
    parser.add_argument("--dry-run", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    try:
        figs = figures_for(load_report(args.report), args.report)
        base, fmt = output_base(args.report, args.out, args.format)
        if args.dry_run:
            return 0
        import matplotlib
        matplotlib.use("Agg")
        for t in render_all(figs, base, fmt, args.force):
            print(f"plot: {t}")
    except ReportError as e:
        print(f"vgroove: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("\nvgroove: interrupted; no plot written", file=sys.stderr)
        return 130
    return 0


if __name__ == "__main__":
    sys.exit(main())
