"""vgroove plots: figures drawn with matplotlib from a report JSON alone, nothing recomputed.

    python3 -m vgroove.plot REPORT.json [--out BASE[.png|.svg|.pdf]] [--format png|svg|pdf] [--force]
    vgroove plot REPORT.json ...            (runs this file)

One or more images per report, named after the report (or --out) with a suffix per figure:

    single-groove suites (Table 1, stress)   BASE.png       heatmaps of L1 over (theta_v, theta_i), one per
                                                            suite of a set, side by side, thresholds marked
    "brdf" suites (Fig. 11)                  BASE-NDF-DIM.png  one grid per (NDF, dimension): rows theta_i,
                                                            columns alpha; traced lobe as bars, the model
                                                            as a line, per k dashed, Cook-Torrance dotted
    "furnace"                                BASE.png       albedo against theta_i per alpha: traced,
                                                            model, Cook-Torrance (what it loses)
    "table2"                                 BASE.png       the paper's bounce counts, ours, the traced ones
    `bench accuracy --out`                   BASE.png       L1 against wall time (log-log);
                                             BASE-cost.png  tracer vs model cost against theta_v
    check_brdf reports                       BASE.png       L1 and albedo against their thresholds per theta_i,
                                                            and the worst bins

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
    if kind in ("brdf", "furnace", "table2", "check_brdf"):
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
    fig.suptitle(title + "\n" + sub, fontsize=11)


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
        from matplotlib.colors import Normalize
        fig = _figure(6.0 * len(data) + 1.0, 5.2)
        axes = fig.subplots(1, len(data), squeeze=False)[0]
        for ax, d in zip(axes, data):
            v, i, l1 = (np.asarray(d[k], dtype=float) for k in ("v", "i", "l1"))
            thr = d["max_l1"]
            marks = [x for x in (thr, d["paper"]) if x is not None and x > 0]
            vmax = max([float(l1.max())] + marks) or 1.0
            norm = Normalize(0.0, vmax)
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
            cb.set_label("L1 error of the model (fraction of the rays)")
            cb.ax.axhline(thr, color="red", lw=2)
            cb.ax.text(1.05, thr / vmax, " threshold", transform=cb.ax.transAxes, color="red", fontsize=7,
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
        ndf = c["ndf"].one_of(("ggx", "beckmann", "phong"))
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

def furnace_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    rows: Dict[Tuple[str, str], Dict[float, List[Tuple[float, float, float, float]]]] = {}
    for c in report["cases"].nonempty():
        key = (c["dimension"].one_of(("flatland", "3d")), c["ndf"].one_of(("ggx", "beckmann", "phong")))
        rows.setdefault(key, {}).setdefault(c["alpha"].number(0.0, 2.0), []).append(
            (c["theta_i_deg"].number(-90.0, 90.0), c["albedo_sim"].number(0.0, 2.0),
             c["albedo_model"].number(-1.0, 3.0), c["albedo_cook_torrance"].number(-1.0, 3.0)))
    name = safe_text(report["suite"].text())

    def draw() -> Figure:
        import matplotlib
        keys = sorted(rows)
        cols = min(3, len(keys))
        nrows = (len(keys) + cols - 1) // cols
        fig = _figure(max(4.6 * cols + 0.5, 10.0), 3.6 * nrows + 1.0)
        axes = fig.subplots(nrows, cols, squeeze=False)
        for ax in axes.flat[len(keys):]:
            ax.set_visible(False)
        cmap = matplotlib.colormaps["plasma"]
        for ax, key in zip(axes.flat, keys):
            alphas = sorted(rows[key])
            for n, a in enumerate(alphas):
                pts = sorted(rows[key][a])
                col = cmap(0.85 * n / max(1, len(alphas) - 1))
                t = [p[0] for p in pts]
                ax.plot(t, [p[3] for p in pts], color=col, lw=1.3, label=f"alpha {a:g}")
                ax.plot(t, [p[2] for p in pts], color=col, lw=0.8, ls="--")
                ax.plot(t, [p[1] for p in pts], color=col, marker="o", ms=3, ls="none")
            ax.set_title(f"{key[0]}, {key[1]}", fontsize=9)
            ax.set_xlabel("theta_i (deg)")
            ax.set_ylabel("albedo (fraction of the incident flux)")
            ax.set_ylim(0, 1.05)
            ax.legend(fontsize=6, loc="lower right")
        _suptitle(fig, f"{name}: white furnace (F = 1), albedo per alpha",
                  f"solid: Cook-Torrance (the energy it loses); dashed: the model; dots: traced. {_title_bits(report)}")
        return fig

    return [("", draw)]


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


# check_brdf -----------------------------------------------------------------------------------------

def check_brdf_figures(report: Node, base: str) -> List[Tuple[str, Drawer]]:
    cases = []
    for c in report["cases"].nonempty():
        worst = [(w["theta_o_deg"].number(-90.0, 90.0), w["phi_o_deg"].number(-180.0, 180.0), w["sim"].number(),
                  w["model"].number()) for w in c["worst_bins"].items()]
        cases.append({
            "theta_i": c["theta_i_deg"].number(-90.0, 90.0), "l1": c["l1"].number(), "l1_thr": c["l1_threshold"].number(),
            "flux": c["l1_flux"].number(), "flux_thr": c["l1_flux_threshold"].number(),
            "a_sim": c["albedo_sim"].number(), "a_model": c["albedo_model"].number(),
            "a_thr": c["albedo_threshold"].number(), "pass": c["pass"].boolean(), "worst": worst})
    name = safe_text(report["name"].text()) if report.has("name") else "check_brdf"
    inputs = report["inputs"] if report.has("inputs") else None
    what = ""
    if inputs is not None and inputs.has("ndf") and inputs.has("alpha"):
        what = f" ({safe_text(inputs['ndf'].text(), 12)}, alpha {inputs['alpha'].number():g})"

    def draw() -> Figure:
        import numpy as np
        fig = _figure(12.0, 4.2)
        a1, a2, a3 = fig.subplots(1, 3)
        t = np.array([c["theta_i"] for c in cases])
        a1.plot(t, [c["l1"] / c["l1_thr"] if c["l1_thr"] > 0 else 0 for c in cases], "o-", label="lobe shape")
        a1.plot(t, [c["flux"] / c["flux_thr"] if c["flux_thr"] > 0 else 0 for c in cases], "s-", label="flux per bin")
        a1.axhline(1.0, color="red", lw=1)
        a1.set_xlabel("theta_i (deg)")
        a1.set_ylabel("L1 / threshold (> 1 fails)")
        a1.legend(fontsize=8)
        a2.errorbar(t, [c["a_sim"] for c in cases], yerr=[c["a_thr"] for c in cases], fmt="o", capsize=3,
                    label="traced (+- threshold)")
        a2.plot(t, [c["a_model"] for c in cases], "x-", color="#d62728", label="the BRDF checked")
        a2.set_xlabel("theta_i (deg)")
        a2.set_ylabel("albedo (fraction of the incident flux)")
        a2.legend(fontsize=8)
        for c in cases:
            for w in c["worst"]:
                a3.scatter(w[1], w[0], s=12 + 4000 * abs(w[2] - w[3]), alpha=0.5,
                           color="#d62728" if w[3] > w[2] else "#1f77b4")
        a3.set_xlim(-180, 180)
        a3.set_ylim(-90, 90)
        a3.set_xlabel("phi_o (deg; 0: mirror side)")
        a3.set_ylabel("theta_o (deg)")
        a3.set_title("worst bins (red: model too high, blue: too low)", fontsize=8)
        verdict = "PASS" if all(c["pass"] for c in cases) else "FAIL"
        _suptitle(fig, f"{name}{what}: {verdict}", _title_bits(report))
        return fig

    return [("", draw)]


KINDS = {
    "single_grooves": single_groove_figures,
    "brdf": brdf_figures,
    "furnace": furnace_figures,
    "table2": table2_figures,
    "accuracy": accuracy_figures,
    "check_brdf": check_brdf_figures,
    # Report kinds still to come (sampling chi-square, nonsymmetric profiles) add a function here.
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
