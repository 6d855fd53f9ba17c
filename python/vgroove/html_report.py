"""vgroove report: one self-contained HTML page of a run's reports, from their JSON and plots alone.

    python3 -m vgroove.html_report [--out PAGE.html] [--force] DIR
    vgroove report DIR [--out PAGE.html] [--force]        (runs this file)

Every report JSON in DIR (not its subdirectories) gets a section: its verdict, the paper's figures
beside ours where the report has them, its cases, thresholds, summary, wall time, version, git
revision and seeds, its worst cases and its plots. The plots are the PNGs `vgroove plot` writes
beside the report (REPORT.png, REPORT-SUFFIX.png); one that is missing, older than its report or
damaged is drawn again for the page in memory by the same code (plot.py), nothing written beside
the report. Files that are not vgroove reports (damaged JSON, another tool's JSON, shard parts)
are listed with the reason they were skipped.

The page is one file: the images are embedded as data: URIs, the style is inline, there is no
script and nothing is loaded from the network (its Content-Security-Policy forbids it), so it opens
from disk or from a CI artifact page and reads without JavaScript. Every text taken from a report
or a file name is HTML-escaped, with control, format and bidirectional characters, lone
surrogates and bytes that are not UTF-8 shown as escapes. The same directory gives the same bytes.

Bad input (a DIR that is missing, empty or holds no report; an --out that exists without --force,
is a directory, lies in a missing directory or is one of the reports) is a one-line error
(ReportError, a ValueError; the command exits 2) and nothing is written: the page is written to a
temporary file beside its target (.NAME.tmp.PID) and renamed into place, and removed on any error or
interruption (exit 130).

This file imports only the standard library (and plot.py, which imports matplotlib only to draw),
so it runs wherever Debian's python3 does.
"""

from __future__ import annotations

import argparse
import base64
import heapq
import html
import io
import json
import math
import os
import stat
import struct
import sys
import zlib
from typing import Any, Dict, Iterable, List, Optional, Sequence, Tuple

try:  # as vgroove.html_report
    from . import plot as _plot
except ImportError:  # as a script beside plot.py (vgroove report runs it so)
    import plot as _plot  # type: ignore[no-redef]

ReportError = _plot.ReportError

#: Reports larger than this are skipped (a reason is given): the page reads each report whole.
MAX_REPORT_BYTES = 1 << 30
#: Worst cases listed per report (every failing case is listed, up to MAX_FAILING_ROWS).
WORST_ROWS = 10
MAX_FAILING_ROWS = 50
#: Characters of one text shown before it is cut ("...").
TEXT_LIMIT = 200


# ----------------------------------------------------------------------------------------------
# Text: every string that reaches the page goes through text() (num() for values).

_FORMAT_CHARS = set(range(0x200B, 0x2010)) | set(range(0x202A, 0x202F)) | set(range(0x2060, 0x2070)) | {
    0x061C, 0xFEFF, 0x00AD, 0xFFFE, 0xFFFF} | set(range(0xFDD0, 0xFDF0))


def printable(s: Any, limit: int = TEXT_LIMIT, path: bool = False) -> str:
    """s as one line of visible text: control, format and bidirectional characters and lone
    surrogates as \\uXXXX; with path=True, the bytes of a file name that are not UTF-8 (Python's
    surrogateescape, U+DC80..U+DCFF) as \\xNN. At most `limit` characters (then "...")."""
    out = []
    for ch in str(s):
        o = ord(ch)
        if path and 0xDC80 <= o <= 0xDCFF:
            out.append(f"\\x{o - 0xDC00:02x}")
        elif o < 0x20 or o == 0x7F or 0x80 <= o < 0xA0 or 0xD800 <= o < 0xE000 or o in _FORMAT_CHARS:
            out.append(f"\\u{o:04x}")
        else:
            out.append(ch)
    t = "".join(out)
    return t if len(t) <= limit else t[: limit - 3] + "..."


def text(s: Any, limit: int = TEXT_LIMIT, path: bool = False) -> str:
    """s as HTML text (element content or a quoted attribute value)."""
    return html.escape(printable(s, limit, path), quote=True)


def num(x: Any) -> str:
    """A report's value as short HTML text: numbers to 4 significant digits, booleans yes/no,
    short lists of scalars joined, anything else escaped."""
    if x is None:
        return "&mdash;"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, int):
        return str(x)
    if isinstance(x, float):
        if not math.isfinite(x):
            return text(repr(x))
        return f"{x:.4g}"
    if isinstance(x, list):
        if len(x) <= 8 and all(isinstance(v, (int, float, str, bool)) or v is None for v in x):
            return ", ".join(num(v) for v in x) if x else "(none)"
        return f"[{len(x)} values]"
    if isinstance(x, dict):
        return f"{{{len(x)} fields}}"
    return text(x)


def get(obj: Any, *path: Any, default: Any = None) -> Any:
    """obj[path[0]][path[1]]... or default when any step is missing or of another type."""
    for p in path:
        if isinstance(p, str) and isinstance(obj, dict) and p in obj:
            obj = obj[p]
        elif isinstance(p, int) and isinstance(obj, list) and -len(obj) <= p < len(obj):
            obj = obj[p]
        else:
            return default
    return obj


def number(x: Any) -> Optional[float]:
    """x as a finite float, or None (missing, another type, or not finite)."""
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        return None
    try:
        f = float(x)
    except OverflowError:
        return None
    return f if math.isfinite(f) else None


def ratio(a: Any, b: Any) -> Optional[float]:
    a, b = number(a), number(b)
    if a is None or b is None or b <= 0:
        return None
    return a / b


# ----------------------------------------------------------------------------------------------
# PNG: every image is checked (chunks, CRCs, the whole pixel stream) before it is embedded.

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
MAX_PIXELS = 100_000_000


def png_problem(data: bytes) -> Optional[str]:
    """None when data is a PNG a browser can decode (every chunk's CRC right, IHDR first, the
    image data inflating to exactly the rows IHDR announces, IEND last); otherwise what is wrong."""
    if not data.startswith(PNG_SIGNATURE):
        return "not a PNG (no PNG signature)"
    pos, idat, ihdr, ended = len(PNG_SIGNATURE), [], None, False
    while pos < len(data):
        if pos + 12 > len(data):
            return f"truncated at byte {pos}"
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        if len(body) != length or pos + 12 + length > len(data):
            return f"truncated inside the {printable(kind.decode('latin-1'))} chunk at byte {pos}"
        (crc,) = struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])
        if zlib.crc32(kind + body) != crc:
            return f"{printable(kind.decode('latin-1'))} chunk at byte {pos}: CRC mismatch"
        if ihdr is None and kind != b"IHDR":
            return "the first chunk is not IHDR"
        if kind == b"IHDR":
            if length != 13:
                return "IHDR of the wrong length"
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            ended = True
            break
        pos += 12 + length
    if ihdr is None or not ended:
        return "no IEND chunk (truncated)"
    width, height, depth, color, _, _, interlace = ihdr
    channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}.get(color)
    if channels is None or depth not in (1, 2, 4, 8, 16) or width == 0 or height == 0:
        return f"IHDR: {width} x {height}, colour type {color}, bit depth {depth} is not a valid image"
    if width * height > MAX_PIXELS:
        return f"{width} x {height} pixels: larger than {MAX_PIXELS} pixels"
    if interlace == 0:
        expected = height * (1 + (width * channels * depth + 7) // 8)
    else:  # Adam7: seven reduced images, each row with its filter byte
        expected = 0
        for x0, y0, dx, dy in ((0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2),
                               (0, 1, 1, 2)):
            w, h = (width - x0 + dx - 1) // dx, (height - y0 + dy - 1) // dy
            if w and h:
                expected += h * (1 + (w * channels * depth + 7) // 8)
    z = zlib.decompressobj()
    try:
        pixels = z.decompress(b"".join(idat), expected + 1)
    except zlib.error as e:
        return f"image data does not inflate ({e})"
    if len(pixels) != expected or not z.eof:
        return f"image data holds {len(pixels)} bytes, not the {expected} of {width} x {height} pixels"
    if interlace == 0:
        row = 1 + (width * channels * depth + 7) // 8
        if any(pixels[r * row] > 4 for r in range(height)):
            return "a row with an unknown filter type"
    return None


def png_size(data: bytes) -> Tuple[int, int]:
    return struct.unpack(">II", data[16:24])


# ----------------------------------------------------------------------------------------------
# Reading the directory.

class Entry:
    """One .json file of the directory: a report (data) or a skipped file (reason)."""

    def __init__(self, name: str, path: str) -> None:
        self.name, self.path = name, path
        self.data: Any = None
        self.reason: Optional[str] = None
        self.kind = ""  # plot.py's kind, or a label for reports it does not draw
        self.mtime = 0.0


def read_entry(directory: str, name: str) -> Entry:
    e = Entry(name, os.path.join(directory, name))
    try:
        st = os.stat(e.path)
    except OSError as err:
        e.reason = f"cannot read: {err.strerror or err}"
        return e
    if not stat.S_ISREG(st.st_mode):
        e.reason = "not a regular file"
        return e
    if st.st_size > MAX_REPORT_BYTES:
        e.reason = f"{st.st_size} bytes: larger than the {MAX_REPORT_BYTES >> 20} MB a page reads"
        return e
    e.mtime = st.st_mtime
    try:
        data = _plot.load_report(e.path)
    except ReportError as err:
        # load_report names the path first; the page names the file in its own column.
        msg = str(err)
        e.reason = msg[len(e.path) + 2:] if msg.startswith(e.path + ": ") else msg
        return e
    if not isinstance(data, dict):
        e.reason = f"JSON {_plot._kind(data)}, not a vgroove report (a JSON object with \"tool\": \"vgroove\")"
        return e
    if data.get("tool") != "vgroove":
        if "tool" not in data and "name" in data and any(k in data for k in ("kind", "suites", "thresholds", "groove")):
            e.reason = "a suite, not a report (vgroove validate FILE --out REPORT.json runs it)"
        elif "tool" not in data and "geometry" in data and "light" in data:
            e.reason = "a scene, not a result (vgroove simulate FILE --out RESULT.json runs it)"
        else:
            e.reason = "not a vgroove report (no \"tool\": \"vgroove\")"
        return e
    if "partial" in data:
        i, n = get(data, "partial", "shard", "index"), get(data, "partial", "shard", "count")
        which = f" (shard {num(i)} of {num(n)})" if number(i) is not None and number(n) is not None else ""
        e.reason = f"a partial report{which}: join the parts with vgroove merge, then report the merged file"
        return e
    e.data = data
    try:
        e.kind = _plot.report_kind(_plot.Node(data, e.path))
    except ReportError:
        e.kind = data.get("command") if isinstance(data.get("command"), str) else (
            "simulate" if "scene" in data else "other")
    return e


def list_json(directory: str) -> List[str]:
    try:
        names = os.listdir(directory)
    except FileNotFoundError:
        raise ReportError(f"{printable(directory, path=True)}: no such directory") from None
    except NotADirectoryError:
        raise ReportError(f"{printable(directory, path=True)}: is not a directory (give the directory of the "
                          "reports, e.g. results/)") from None
    except OSError as e:
        raise ReportError(f"{printable(directory, path=True)}: cannot list: {e.strerror or e}") from None
    return sorted(n for n in names if n.endswith(".json") and not n.startswith("."))


# ----------------------------------------------------------------------------------------------
# Plots.

class Plot:
    def __init__(self, name: str, png: Optional[bytes], note: str) -> None:
        self.name, self.png, self.note = name, png, note


def plots_for(e: Entry, directory: str, draw_missing: bool) -> Tuple[List[Plot], str]:
    """The report's figures (those `vgroove plot` writes), each from its PNG beside the report or
    drawn for the page; and a note when the report has none."""
    try:
        figs = _plot.figures_for(e.data, e.path)
    except ReportError as err:
        msg = str(err)
        msg = msg[len(e.path) + 2:] if msg.startswith(e.path + ": ") else msg
        return [], f"no plots: {msg}"
    base = e.name[:-5]
    out = []
    for suffix, draw in figs:
        name = f"{base}{suffix}.png"
        path = os.path.join(directory, name)
        why = ""
        try:
            st = os.stat(path)
            if not stat.S_ISREG(st.st_mode):
                why = f"{name} is not a regular file"
            elif st.st_mtime < e.mtime:
                why = f"{name} is older than its report"
            else:
                with open(path, "rb") as f:
                    data = f.read()
                problem = png_problem(data)
                if problem is None:
                    out.append(Plot(name, data, ""))
                    continue
                why = f"{name} is damaged ({problem})"
        except FileNotFoundError:
            why = f"no {name} beside the report"
        except OSError as err:
            why = f"{name}: cannot read: {err.strerror or err}"
        if not draw_missing:
            out.append(Plot(name, None, f"{why}; not drawn (vgroove plot {base}.json --force draws it)"))
            continue
        png, problem = draw_png(draw)
        if png is None:
            out.append(Plot(name, None, f"{why}; not drawn: {problem}"))
        else:
            out.append(Plot(name, png, f"drawn for this page: {why} (vgroove plot {base}.json --force writes it)"))
    return out, ""


def draw_png(draw: Any) -> Tuple[Optional[bytes], str]:
    try:
        import matplotlib
        matplotlib.use("Agg")
    except ImportError:
        return None, "matplotlib is not installed (apt-get install python3-matplotlib)"
    try:
        fig = draw()
        buf = io.BytesIO()
        fig.savefig(buf, format="png", metadata=_plot._metadata("png"))
    except ReportError as err:
        return None, str(err)
    except Exception as err:  # a report plot.py accepted but matplotlib cannot draw: the page goes on
        return None, f"matplotlib could not draw it ({type(err).__name__}: {printable(err, 200)})"
    data = buf.getvalue()
    problem = png_problem(data)
    return (data, "") if problem is None else (None, f"matplotlib wrote a damaged PNG ({problem})")


# ----------------------------------------------------------------------------------------------
# What each kind of report shows: (title, columns, rows) tables, worst cases first.

Table = Tuple[str, List[str], List[List[str]]]


def verdict(v: Any) -> str:
    if v is True:
        return '<span class="pass">PASS</span>'
    if v is False:
        return '<span class="fail">FAIL</span>'
    return '<span class="none">no verdict</span>'


def case_pass(c: Any) -> Optional[bool]:
    v = get(c, "pass")
    return v if isinstance(v, bool) else None


def worst_first(cases: Sequence[Any], badness: Any, failed: Any = None) -> Tuple[List[Any], str]:
    """The cases to list: the failing ones (`failed`, default: "pass" false), worst first, up to
    MAX_FAILING_ROWS, then the worst passing ones by `badness` (larger is worse) up to WORST_ROWS in
    all, ties in the report's order; and a line saying how many there are."""
    is_failed = failed or (lambda c: case_pass(c) is False)
    failing, passing = [], []
    for n, c in enumerate(cases):
        if isinstance(c, dict):
            b = badness(c)
            (failing if is_failed(c) else passing).append((-b if b is not None else math.inf, n, c))
    shown = [c for _, _, c in heapq.nsmallest(MAX_FAILING_ROWS, failing)]
    shown += [c for _, _, c in heapq.nsmallest(max(0, WORST_ROWS - len(shown)), passing)]
    line = f"{len(failing) + len(passing)} cases"
    if failing:
        line += f", {len(failing)} failing" + (f" (the first {MAX_FAILING_ROWS} listed)"
                                                if len(failing) > MAX_FAILING_ROWS else "")
    else:
        line += ", none failing"
    return shown, line


def groove_of(c: Any) -> str:
    if "theta_l_deg" in c and "theta_r_deg" in c:
        return f"{num(get(c, 'theta_l_deg'))} / {num(get(c, 'theta_r_deg'))}"
    return num(get(c, "theta_v_deg"))


def single_groove_tables(r: Dict[str, Any]) -> Tuple[List[Table], List[Table]]:
    suites = r["suites"] if isinstance(r.get("suites"), list) else [r]
    paper_rows, worst = [], []
    for s in suites:
        if not isinstance(s, dict):
            continue
        name = text(get(s, "suite", default="?"))
        sm, th, pp = get(s, "summary", default={}), get(s, "thresholds", default={}), get(s, "paper", default={})
        paper_rows.append([name, num(get(pp, "max_l1")), num(get(sm, "max_l1")), num(get(th, "max_l1")),
                           num(get(pp, "mean_l1")), num(get(sm, "mean_l1")), num(get(th, "mean_l1")),
                           num(get(sm, "max_theta_o_error_rad")), num(get(th, "max_theta_o_error_rad")),
                           num(get(sm, "cases")), num(get(s, "rays_per_facet")), num(get(s, "sampling")),
                           num(get(s, "seed")), num(get(sm, "wall_s")), verdict(get(s, "pass"))])
        cases = get(s, "cases", default=[])
        cases = cases if isinstance(cases, list) else []
        thr, err_thr = number(get(th, "max_l1")), number(get(th, "max_theta_o_error_rad"))

        def over(c: Any) -> bool:  # a case beyond the suite's thresholds (its cases carry no verdict)
            l1, err = number(get(c, "l1")), number(get(c, "theta_o_error_rad"))
            return (thr is not None and l1 is not None and l1 > thr) or (
                err_thr is not None and err is not None and err > err_thr)

        shown, line = worst_first([c for c in cases if isinstance(c, dict) and "degenerate" not in c],
                                  lambda c: number(get(c, "l1")), over)
        rows = [[groove_of(c), num(get(c, "theta_i_deg")), num(get(c, "l1")),
                 num(ratio(get(c, "l1"), thr)), num(get(c, "theta_o_error_rad")), num(get(c, "rays")),
                 num(get(c, "bounces"))] for c in shown]
        worst.append((f"{name}: largest L1 ({line}; threshold max L1 {num(thr)})",
                      ["theta_v (or theta_l / theta_r) deg", "theta_i deg", "L1", "L1 / threshold",
                       "exit-angle error rad", "rays", "bounces"], rows))
    source = "; ".join(printable(get(s, "paper", "source")) for s in suites
                       if isinstance(get(s, "paper", "source"), str))
    paper = [(f"The paper's figures beside ours{(' (' + html.escape(source) + ')') if source else ''}",
              ["suite", "paper max L1", "ours max L1", "threshold", "paper mean L1", "ours mean L1", "threshold",
               "max exit-angle error rad", "threshold", "cases", "rays per facet", "sampling", "seed", "wall s",
               "verdict"], paper_rows)]
    return paper, worst


def lobe_tables(r: Dict[str, Any]) -> Tuple[List[Table], List[Table]]:
    """brdf (Fig. 11) and nonsymmetric_brdf: per (dimension, NDF) as the README's table; worst
    cases by L1 / threshold."""
    cases = [c for c in get(r, "cases", default=[]) if isinstance(c, dict)] if isinstance(r.get("cases"), list) else []
    groups: Dict[Tuple[str, str], List[Dict[str, Any]]] = {}
    for c in cases:
        groups.setdefault((str(get(c, "dimension", default="?")), str(get(c, "ndf", default="?"))), []).append(c)

    def worst_ratio(c: Any) -> Optional[float]:
        rs = [x for x in (ratio(get(c, "l1"), get(c, "l1_threshold")),
                          ratio(get(c, "l1_by_k"), get(c, "l1_by_k_threshold"))) if x is not None]
        return max(rs) if rs else None

    rows = []
    for (dim, ndf), cs in sorted(groups.items()):
        l1 = [x for x in (number(get(c, "l1")) for c in cs) if x is not None]
        thr = [x for x in (number(get(c, "l1_threshold")) for c in cs) if x is not None]
        wr = [x for x in (worst_ratio(c) for c in cs) if x is not None]
        ad = [abs(a - b) for a, b in ((number(get(c, "albedo_sim")), number(get(c, "albedo_model"))) for c in cs)
              if a is not None and b is not None]
        wall = [sum(x for x in (number(get(c, "sim_wall_s")), number(get(c, "model_wall_s"))) if x is not None)
                for c in cs]
        rows.append([text(dim), text(ndf), str(len(cs)), str(sum(case_pass(c) is True for c in cs)),
                     num(max(l1) if l1 else None), num(sum(l1) / len(l1) if l1 else None),
                     num(sum(thr) / len(thr) if thr else None), num(max(wr) if wr else None),
                     num(max(ad) if ad else None), num(sum(wall) / len(wall) if wall else None)])
    summary = [("Per dimension and NDF (the model against the traced surfaces)",
                ["dimension", "NDF", "cases", "pass", "max L1", "mean L1", "mean threshold",
                 "worst L1 / threshold (all k; joint k x bin)", "largest |albedo sim - model|",
                 "mean wall per case s (trace + model)"], rows)]
    shown, line = worst_first(cases, worst_ratio)
    alpha = "alpha_x" if any("alpha_x" in c for c in cases) else "alpha"
    wrows = [[text(get(c, "ndf", default="?")), num(get(c, alpha)) + (
        f" / {num(get(c, 'alpha_y'))}" if alpha == "alpha_x" else ""), num(get(c, "theta_i_deg")),
              text(get(c, "dimension", default="?")), num(get(c, "l1")), num(get(c, "l1_threshold")),
              num(get(c, "l1_by_k")), num(get(c, "l1_by_k_threshold")), num(worst_ratio(c)),
              num(get(c, "albedo_sim")), num(get(c, "albedo_model")), verdict(case_pass(c))] for c in shown]
    worst = [(f"Worst cases by L1 / threshold ({line})",
              ["NDF", "alpha" if alpha == "alpha" else "alpha_x / alpha_y", "theta_i deg", "dimension", "L1 (all k)",
               "threshold", "L1 (k x bin)", "threshold", "worst ratio", "albedo sim", "albedo model", "verdict"],
              wrows)]
    return summary, worst


def furnace_rows(cases: Sequence[Any]) -> Tuple[List[List[str]], str]:
    def bad(c: Any) -> Optional[float]:
        e = number(get(c, "energy_error"))
        return abs(e) if e is not None else None

    shown, line = worst_first(cases, bad)
    rows = [[text(get(c, "ndf", default="?")), num(get(c, "alpha")), num(get(c, "theta_i_deg")),
             text(get(c, "dimension", default="?")), num(get(c, "albedo_quadrature")), num(get(c, "flux_beyond_max_k")),
             num(get(c, "energy_error")), num(get(c, "albedo_estimate")), num(get(c, "standard_error")),
             num(get(c, "cook_torrance_quadrature")), verdict(case_pass(c))] for c in shown]
    return rows, line


FURNACE_COLUMNS = ["NDF", "alpha", "theta_i deg", "dimension", "albedo (quadrature)", "beyond max_k",
                   "energy error", "albedo (sampled)", "standard error", "Cook-Torrance albedo", "verdict"]


def furnace_tables(r: Dict[str, Any]) -> Tuple[List[Table], List[Table]]:
    cases = get(r, "cases", default=[])
    rows, line = furnace_rows(cases if isinstance(cases, list) else [])
    return [], [(f"Worst cases by |energy error| ({line})", FURNACE_COLUMNS, rows)]


def sampling_tables(r: Dict[str, Any]) -> Tuple[List[Table], List[Table]]:
    chi = get(r, "chi_square", default=[])
    chi = chi if isinstance(chi, list) else []

    def low_p(c: Any) -> Optional[float]:
        p = number(get(c, "p_value"))
        return -p if p is not None else None

    shown, line = worst_first(chi, low_p)
    crows = [[text(get(c, "dimension", default="?")), text(get(c, "ndf", default="?")), num(get(c, "alpha")),
              num(get(c, "theta_i_deg")), text(get(c, "strategy", default="?")), text(get(c, "model", default="?")),
              num(get(c, "samples")), num(get(c, "statistic")), num(get(c, "dof")), num(get(c, "p_value")),
              num(get(c, "level")), num(get(c, "normalization_error")), verdict(case_pass(c))] for c in shown]
    var = get(r, "variance", default=[])
    vrows = [[text(get(v, "dimension", default="?")), text(get(v, "ndf", default="?")), num(get(v, "alpha")),
              num(get(v, "theta_i_deg")), text(get(v, "fresnel", default="?")), num(get(v, "samples")),
              text(get(v, "lowest_variance", default="?")), text(get(v, "timing", "most_efficient", default="?"))]
             for v in (var if isinstance(var, list) else []) if isinstance(v, dict)]
    fcases = get(r, "furnace", "cases", default=[])
    frows, fline = furnace_rows(fcases if isinstance(fcases, list) else [])
    return ([("Variance of the weight per strategy",
              ["dimension", "NDF", "alpha", "theta_i deg", "Fresnel", "samples", "lowest variance", "most efficient"],
              vrows)],
            [(f"Chi-square cases, lowest p first ({line})",
              ["dimension", "NDF", "alpha", "theta_i deg", "strategy", "model", "samples", "statistic", "dof", "p",
               "level", "normalization error", "verdict"], crows),
             (f"Its furnace, worst cases by |energy error| ({fline})", FURNACE_COLUMNS, frows)])


def table2_tables(r: Dict[str, Any]) -> Tuple[List[Table], List[Table]]:
    entries = [e for e in get(r, "entries", default=[]) if isinstance(e, dict)] \
        if isinstance(r.get("entries"), list) else []
    cols: List[Tuple[str, Any]] = []
    for e in entries:
        k = (str(get(e, "ndf", default="?")), get(e, "alpha"))
        if k not in cols:
            cols.append(k)
    pcts: List[Any] = []
    for e in entries:
        if get(e, "percentile") not in pcts:
            pcts.append(get(e, "percentile"))
    rows = []
    for p in pcts:
        row = [num(p) + " %"]
        for ndf, a in cols:
            cell = "&mdash;"
            for e in entries:
                if get(e, "percentile") == p and str(get(e, "ndf", default="?")) == ndf and get(e, "alpha") == a:
                    v = f"{num(get(e, 'paper'))} / {num(get(e, 'ours'))} / {num(get(e, 'traced_percentile_k'))}"
                    cell = v if get(e, "agree") is True else f'<span class="fail">{v}</span>'
            row.append(cell)
        rows.append(row)
    paper = [(f"The paper's figures beside ours: paper / ours / traced ({text(get(r, 'source', default=''))})",
              ["percentile"] + [f"{text(n)} {num(a)}" for n, a in cols], rows)]
    assumptions = get(r, "assumptions", default={})
    if isinstance(assumptions, dict) and assumptions:
        paper.append(("The reading of the paper these figures assume", ["", ""],
                      [[text(k), text(v, 400)] for k, v in sorted(assumptions.items())]))
    bad = [e for e in entries if get(e, "agree") is not True]
    worst = [(f"Entries that disagree ({len(bad)} of {len(entries)})",
              ["NDF", "alpha", "percentile", "paper", "ours", "traced"],
              [[text(get(e, "ndf", default="?")), num(get(e, "alpha")), num(get(e, "percentile")),
                num(get(e, "paper")), num(get(e, "ours")), num(get(e, "traced_percentile_k"))] for e in bad])]
    return paper, worst


def accuracy_tables(r: Dict[str, Any]) -> Tuple[List[Table], List[Table]]:
    runs = [x for x in get(r, "runs", default=[]) if isinstance(x, dict)] if isinstance(r.get("runs"), list) else []
    rows = [[text(get(x, "sampling", default="?")), num(get(x, "rays_per_facet")), num(get(x, "max_l1")),
             num(get(x, "mean_l1")), num(get(x, "max_theta_o_error_rad")), num(get(x, "rays")), num(get(x, "wall_s")),
             verdict(get(x, "pass"))] for x in runs]
    return [(f"Accuracy against rays (soonest to the thresholds: {text(get(r, 'soonest_to_thresholds', default='?'))})",
             ["sampling", "rays per facet", "max L1", "mean L1", "max exit-angle error rad", "rays traced", "wall s",
              "within thresholds"], rows)], []


def profiles_tables(r: Dict[str, Any]) -> Tuple[List[Table], List[Table]]:
    cases = get(r, "cases", default=[])
    cases = cases if isinstance(cases, list) else []

    def z(c: Any) -> Optional[float]:
        zs = [abs(x) for x in (number(get(s, "lobe", "distance", "vgroove_model", "z"))
                               for s in get(c, "surfaces", default=[]) if isinstance(s, dict)) if x is not None]
        return max(zs) if zs else None

    shown, line = worst_first(cases, z)
    rows = []
    for c in shown:
        for s in get(c, "surfaces", default=[]):
            if not isinstance(s, dict):
                continue
            rows.append([text(get(c, "ndf", default="?")), num(get(c, "alpha")), num(get(c, "theta_deg")),
                         text(get(s, "surface", default=get(s, "kind", default="?"))),
                         num(get(s, "g1", "distance", "smith", "noise")),
                         num(get(s, "g1", "distance", "smith", "mean_abs")),
                         num(get(s, "g1", "distance", "vcavity", "mean_abs")),
                         num(get(s, "lobe", "distance", "walk", "z")),
                         num(get(s, "lobe", "distance", "vgroove_model", "z")), verdict(case_pass(c))])
    return [], [(f"Cases, the largest V-groove model lobe |z| first ({line})",
                 ["NDF", "alpha", "theta deg", "surface", "G1 noise", "G1 |traced - Smith|",
                  "G1 |traced - V-cavity|", "lobe z: Smith walk", "lobe z: V-groove model", "verdict"], rows)]


def check_brdf_tables(r: Dict[str, Any]) -> Tuple[List[Table], List[Table]]:
    cases = get(r, "cases", default=[])

    def worst_ratio(c: Any) -> Optional[float]:
        rs = [x for x in (ratio(get(c, "l1"), get(c, "l1_threshold")),
                          ratio(get(c, "l1_flux"), get(c, "l1_flux_threshold"))) if x is not None]
        return max(rs) if rs else None

    shown, line = worst_first(cases if isinstance(cases, list) else [], worst_ratio)
    rows = [[num(get(c, "theta_i_deg")), num(get(c, "l1")), num(get(c, "l1_threshold")), num(get(c, "l1_flux")),
             num(get(c, "l1_flux_threshold")), num(get(c, "albedo_sim")), num(get(c, "albedo_model")),
             num(get(c, "albedo_threshold")), verdict(case_pass(c))] for c in shown]
    return [], [(f"Worst cases by L1 / threshold ({line})",
                 ["theta_i deg", "L1 (shape)", "threshold", "L1 (flux)", "threshold", "albedo traced", "albedo model",
                  "threshold", "verdict"], rows)]


def heightfield_tables(r: Dict[str, Any]) -> Tuple[List[Table], List[Table]]:
    cases = get(r, "cases", default=[])
    rows = []
    for c in cases if isinstance(cases, list) else []:
        if not isinstance(c, dict):
            continue
        within = [("yes" if get(c, m, "against_traced", "within_noise") else "no")
                  for m in ("smith_walk", "cook_torrance_smith", "vgroove")]
        rows.append([text(get(c, "ndf", default="?")), num(get(c, "alpha")), num(get(c, "theta_i_deg")),
                     num(get(c, "rays")), num(get(c, "lost")), num(get(c, "traced", "albedo"))] + within +
                    [verdict(case_pass(c))])
    return [], [("Cases: which model is within noise of the traced heightfields",
                 ["NDF", "alpha", "theta_i deg", "rays", "lost", "albedo", "Smith walk", "Cook-Torrance (Smith G)",
                  "V-groove", "verdict"], rows)]


def generic_tables(r: Dict[str, Any]) -> Tuple[List[Table], List[Table]]:
    cases = get(r, "cases", default=None)
    if not isinstance(cases, list) or not any(isinstance(c, dict) and "pass" in c for c in cases):
        return [], []
    shown, line = worst_first(cases, lambda c: None)
    keys = sorted({k for c in shown for k, v in c.items() if not isinstance(v, (list, dict))})[:12]
    return [], [(f"Failing cases first ({line})", [text(k) for k in keys],
                 [[num(c.get(k)) for k in keys] for c in shown])]


TABLES = {
    "single_grooves": single_groove_tables, "brdf": lobe_tables, "nonsymmetric_brdf": lobe_tables,
    "furnace": furnace_tables, "sampling": sampling_tables, "table2": table2_tables, "accuracy": accuracy_tables,
    "profiles": profiles_tables, "check_brdf": check_brdf_tables, "heightfield": heightfield_tables,
}

KIND_TITLES = {
    "single_grooves": "single grooves (Table 1, stress)", "brdf": "BRDF against traced surfaces (Fig. 11)",
    "nonsymmetric_brdf": "nonsymmetric BRDF and anisotropy (Eq. 23, Fig. 7)",
    "furnace": "white furnace of the BRDF", "sampling": "importance sampling (Sec. 6)",
    "table2": "bounce counts at percentiles of D (Table 2)", "accuracy": "accuracy against time (bench accuracy)",
    "profiles": "random height profiles: Smith against V-cavity", "check_brdf": "check_brdf",
    "heightfield": "random heightfields in 3D: Smith, Cook-Torrance and the V-groove model",
    "simulate": "scene (vgroove simulate)", "sample": "importance sampling of one case (vgroove sample)",
    "energy": "energy tables (vgroove energy)",
    "model_table": "a model's table against traced lobes (validate --model-table)",
}


# ----------------------------------------------------------------------------------------------
# The page.

def report_name(e: Entry) -> str:
    for k in ("suite", "scene", "name"):
        if isinstance(e.data.get(k), str):
            return e.data[k]
    return e.name[:-5]


def report_pass(e: Entry) -> Optional[bool]:
    v = e.data.get("pass")
    if isinstance(v, bool):
        return v
    v = get(e.data, "result", "pass")
    return v if isinstance(v, bool) else None


def seeds_of(r: Dict[str, Any]) -> List[Any]:
    """The seeds a report was run with: its own and its suites' (a set of suites), each once."""
    parts = [r] + ([s for s in r["suites"] if isinstance(s, dict)] if isinstance(r.get("suites"), list) else [])
    out: List[Any] = []
    for s in parts:
        for v in (get(s, "seed"), get(s, "inputs", "seed"), get(s, "result", "seed")):
            if isinstance(v, int) and not isinstance(v, bool) and v not in out:
                out.append(v)
    return out


def cases_line(e: Entry) -> str:
    r, sm = e.data, get(e.data, "summary", default={})
    passed, total = number(get(sm, "passed")), number(get(sm, "cases"))
    if e.kind == "single_grooves":
        subs = r["suites"] if isinstance(r.get("suites"), list) else [r]
        n = [number(get(s, "summary", "cases")) for s in subs]
        return f"{num(int(sum(x for x in n if x is not None)))} cases"
    if e.kind == "table2":
        return f"{num(get(sm, 'agree'))} of {num(get(sm, 'entries'))} agree"
    if e.kind == "sampling":
        return (f"chi-square {num(get(sm, 'chi_square_passed'))} of {num(get(sm, 'chi_square_cases'))}, "
                f"furnace {num(get(sm, 'furnace_passed'))} of {num(get(sm, 'furnace_cases'))}")
    if e.kind == "accuracy":
        runs = r.get("runs")
        return f"{len(runs)} runs" if isinstance(runs, list) else "&mdash;"
    if passed is not None and total is not None:
        return f"{num(int(passed))} of {num(int(total))} pass"
    cases = r.get("cases")
    if isinstance(cases, list):
        p = sum(1 for c in cases if case_pass(c) is True)
        return f"{p} of {len(cases)} pass"
    return "&mdash;"


def wall_of(r: Dict[str, Any]) -> Optional[float]:
    for v in (get(r, "wall_s"), get(r, "summary", "wall_s"), get(r, "result", "wall_s")):
        if number(v) is not None:
            return number(v)
    runs = r.get("runs")
    if isinstance(runs, list):
        w = [number(get(x, "wall_s")) for x in runs]
        return sum(x for x in w if x is not None)
    return None


def html_table(t: Table, cls: str = "") -> str:
    title, cols, rows = t
    out = [f'<table{(" class=" + chr(34) + cls + chr(34)) if cls else ""}><caption>{title}</caption>']
    if any(cols):
        out.append("<thead><tr>" + "".join(f'<th scope="col">{c}</th>' for c in cols) + "</tr></thead>")
    out.append("<tbody>")
    if not rows:
        out.append(f'<tr><td colspan="{max(1, len(cols))}">(none)</td></tr>')
    for row in rows:
        out.append("<tr>" + "".join(f"<td>{c}</td>" for c in row) + "</tr>")
    out.append("</tbody></table>")
    return "\n".join(out)


def flat_items(d: Any, prefix: str = "", depth: int = 0) -> List[Tuple[str, Any]]:
    """A summary or thresholds object as (dotted key, value) pairs, nested objects two levels deep."""
    out: List[Tuple[str, Any]] = []
    if not isinstance(d, dict):
        return out
    for k in sorted(d):
        v = d[k]
        if isinstance(v, dict) and depth < 2:
            out += flat_items(v, f"{prefix}{k}.", depth + 1)
        else:
            out.append((f"{prefix}{k}", v))
    return out


def key_values(title: str, d: Any) -> str:
    items = flat_items(d)
    if not items:
        return ""
    rows = "".join(f"<tr><th scope=\"row\">{text(k)}</th><td>{num(v) if not isinstance(v, str) else text(v, 400)}</td>"
                   "</tr>" for k, v in items)
    return f'<table class="kv"><caption>{title}</caption><tbody>{rows}</tbody></table>'


META = (("suite_file", "suite file"), ("scene_file", "scene file"), ("command", "command"),
        ("description", "description"), ("version", "vgroove version"), ("git", "git revision"),
        ("threads", "threads"), ("sampling", "sampling"), ("rays", "rays"), ("eq6_form", "Eq. 6 form"))


def section(n: int, e: Entry, directory: str, draw_missing: bool) -> Tuple[str, int]:
    r = e.data
    meta = [(label, r[k]) for k, label in META if k in r and not isinstance(r[k], (dict, list))]
    meta.insert(0, ("file", None))
    meta.append(("seeds", ", ".join(num(s) for s in seeds_of(r)) or None))
    meta.append(("wall time s", wall_of(r)))
    rows = []
    for label, v in meta:
        if label == "file":
            cell = f"<code>{text(e.name, path=True)}</code>"
        elif label == "seeds":
            cell = v if v else "&mdash;"
        else:
            cell = text(v, 400) if isinstance(v, str) else num(v)
        rows.append(f'<tr><th scope="row">{text(label)}</th><td>{cell}</td></tr>')
    out = [f'<section id="r{n}">',
           f"<h2>{text(report_name(e))} {verdict(report_pass(e))}</h2>",
           f'<p class="kind">{text(KIND_TITLES.get(e.kind, e.kind))}; {cases_line(e)}</p>',
           f'<table class="kv"><caption>Run</caption><tbody>{"".join(rows)}</tbody></table>']
    paper, worst = TABLES.get(e.kind, generic_tables)(r)
    out += [html_table(t, "wide") for t in paper]
    out += [html_table(t, "wide worst") for t in worst]
    if e.kind == "single_grooves" and isinstance(r.get("suites"), list):
        for s in r["suites"]:
            if isinstance(s, dict):
                out.append(key_values(f"Thresholds of {text(get(s, 'suite', default='?'))}", get(s, "thresholds")))
    else:
        out.append(key_values("Thresholds", r.get("thresholds")))
    summary = r.get("summary")
    if e.kind == "single_grooves" and isinstance(r.get("suites"), list):
        for s in r["suites"]:
            if isinstance(s, dict):
                out.append(key_values(f"Summary of {text(get(s, 'suite', default='?'))}", get(s, "summary")))
    elif isinstance(summary, dict):
        out.append(key_values("Summary", summary))
    elif isinstance(r.get("result"), dict):
        out.append(key_values("Result", {k: v for k, v in r["result"].items() if not isinstance(v, (list, dict))}))
    drawn = 0
    if e.kind in _plot.KINDS:
        plots, note = plots_for(e, directory, draw_missing)
        if note:
            out.append(f'<p class="note">{text(note, 400)}</p>')
        for p in plots:
            if p.png is None:
                out.append(f'<p class="note">{text(p.name, path=True)}: {text(p.note, 400)}</p>')
                continue
            w, h = png_size(p.png)
            uri = "data:image/png;base64," + base64.b64encode(p.png).decode("ascii")
            caption = text(p.name, path=True) + (f" &mdash; {text(p.note, 400)}" if p.note else "")
            out.append(f'<figure><img src="{uri}" width="{w}" height="{h}" alt="{text(p.name, path=True)}">'
                       f"<figcaption>{caption}</figcaption></figure>")
            drawn += 1
    else:
        out.append('<p class="note">no plots: vgroove plot draws validate, bench accuracy and check_brdf reports</p>')
    out.append('<p class="top"><a href="#top">back to the overview</a></p></section>')
    return "\n".join(out), drawn


STYLE = """
body{font:14px/1.4 system-ui,sans-serif;margin:1.5em auto;max-width:1400px;padding:0 1em;color:#111;background:#fff}
h1{font-size:1.5em}h2{font-size:1.25em;border-top:2px solid #ccc;padding-top:.8em;margin-top:2em}
table{border-collapse:collapse;margin:.6em 0 1.2em;font-size:13px}
caption{text-align:left;font-weight:600;padding:.2em 0}
th,td{border:1px solid #ccc;padding:.2em .5em;text-align:left;vertical-align:top}
thead th{background:#f2f2f2}table.kv th{background:#f7f7f7;font-weight:normal}table.kv caption{white-space:nowrap}
td{font-variant-numeric:tabular-nums;overflow-wrap:anywhere}
.pass,.fail,.none{font-weight:700;padding:0 .4em;border-radius:3px}
.pass{color:#0a5d1e;background:#d9f2df}.fail{color:#8a0c0c;background:#fadcdc}.none{color:#555;background:#eee}
figure{margin:1em 0}img{max-width:100%;height:auto;border:1px solid #ddd}
figcaption,.note,.kind{color:#444;font-size:13px}.note{font-style:italic}
code{font-size:12px}
"""


def render(directory: str, draw_missing: bool = True) -> Tuple[str, Dict[str, Any]]:
    """The page for the reports in `directory`, and what it holds: {"reports": [file names],
    "skipped": [(file name, reason)], "plots": count}. ReportError when the directory is missing or
    holds no vgroove report."""
    names = list_json(directory)
    if not names:
        raise ReportError(f"{printable(directory, path=True)}: holds no report (*.json); vgroove validate SUITE "
                          f"--out {printable(directory, path=True).rstrip('/')}/NAME.json writes one")
    entries = [read_entry(directory, n) for n in names]
    reports = [e for e in entries if e.data is not None]
    skipped = [e for e in entries if e.data is None]
    sections, plots, readable = [], 0, []
    for e in reports:
        # A report whose fields are of unexpected types (damaged by hand, or of another version) is
        # skipped with the reason rather than ending the page.
        try:
            s, k = section(len(readable) + 1, e, directory, draw_missing)
        except (TypeError, ValueError, KeyError, AttributeError, IndexError, OverflowError) as err:
            e.reason = f"its fields cannot be read ({type(err).__name__}: {printable(err, 200)})"
            e.data = None
            skipped.append(e)
            continue
        readable.append(e)
        sections.append(s)
        plots += k
    skipped.sort(key=lambda e: e.name)
    reports = readable
    if not reports:
        first = skipped[0]
        raise ReportError(f"{printable(directory, path=True)}: none of its {len(entries)} .json files is a vgroove "
                          f"report ({printable(first.name, path=True)}: {printable(first.reason, 300)})")
    verdicts = [report_pass(e) for e in reports]
    failing = sum(v is False for v in verdicts)
    versions = sorted({f"{printable(e.data.get('version', '?'), 40)} (git {printable(e.data.get('git', '?'), 40)})"
                       for e in reports})
    walls = [w for w in (wall_of(e.data) for e in reports) if w is not None]
    title = f"vgroove run: {printable(os.path.abspath(directory), path=True)}"
    overview = [[f'<a href="#r{n}">{text(report_name(e))}</a>', text(e.kind), verdict(report_pass(e)), cases_line(e),
                 num(wall_of(e.data)), text(e.data.get("version", "?"), 40), text(e.data.get("git", "?"), 40),
                 ", ".join(num(s) for s in seeds_of(e.data)) or "&mdash;", f"<code>{text(e.name, path=True)}</code>"]
                for n, e in enumerate(reports, 1)]
    head = [
        "<!DOCTYPE html>", '<html lang="en">', "<head>", '<meta charset="utf-8">',
        "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; "
        "style-src 'unsafe-inline'\">",
        '<meta name="viewport" content="width=device-width, initial-scale=1">',
        f"<title>{html.escape(printable(title, 300))}</title>", f"<style>{STYLE}</style>", "</head>", "<body>",
        f'<h1 id="top">{html.escape(printable(title, 300))}</h1>',
        f"<p>{len(reports)} reports: "
        + (f'<span class="fail">{failing} failing</span>' if failing else '<span class="pass">all pass</span>'
           if all(v is True for v in verdicts) else "none failing")
        + f"; {plots} plots; wall time {num(sum(walls))} s in all; "
        + ("versions " if len(versions) > 1 else "version ") + html.escape("; ".join(versions)) + ".</p>",
        html_table(("Reports", ["suite", "kind", "verdict", "cases", "wall s", "version", "git", "seeds", "file"],
                    overview), "wide"),
    ]
    if skipped:
        head.append(html_table(("Files skipped", ["file", "reason"],
                                [[f"<code>{text(e.name, path=True)}</code>", text(e.reason, 400)] for e in skipped]),
                               "wide"))
    page = "\n".join(head + sections + ["<p class=\"note\">Written by vgroove report from the JSON reports and "
                                        "plots of this directory.</p>", "</body>", "</html>", ""])
    return page, {"reports": [e.name for e in reports], "skipped": [(e.name, e.reason) for e in skipped],
                  "plots": plots}


# ----------------------------------------------------------------------------------------------
# Output: whole or absent.

def check_output(out: str, directory: str, inputs: Iterable[str], force: bool) -> None:
    shown = printable(out, path=True)
    if out == "-":
        raise ReportError("--out = \"-\": the page goes to a file; give a file name, or ./- for a file named \"-\"")
    parent = os.path.dirname(out) or "."
    if not os.path.isdir(parent):
        raise ReportError(f"{shown}: the directory {printable(parent, path=True)} does not exist")
    if os.path.isdir(out):
        raise ReportError(f"{shown}: is a directory")
    for name in inputs:
        p = os.path.join(directory, name)
        if os.path.exists(out) and os.path.exists(p) and os.path.samefile(out, p):
            raise ReportError(f"{shown}: is the input file {printable(p, path=True)}; the page would replace it "
                              "(choose another name)")
    if os.path.lexists(out) and not force:
        raise ReportError(f"{shown}: exists already; pass --force to overwrite it, or choose another name")


def write(directory: str, out: Optional[str] = None, force: bool = False,
          draw_missing: bool = True) -> Dict[str, Any]:
    """Writes the page of the reports in `directory` to `out` (default DIRECTORY/index.html),
    whole or not at all; returns what it holds (render()) with "out". ReportError (ValueError) on
    bad input, naming it."""
    out = out if out else os.path.join(directory, "index.html")
    names = list_json(directory)
    check_output(out, directory, names, force)
    page, info = render(directory, draw_missing)
    tmp = os.path.join(os.path.dirname(out) or ".", f".{os.path.basename(out)}.tmp.{os.getpid()}")
    try:
        with open(tmp, "w", encoding="utf-8", newline="\n") as f:
            f.write(page)
        os.replace(tmp, out)
    except OSError as e:
        _unlink(tmp)
        raise ReportError(f"{printable(out, path=True)}: cannot write: {e.strerror or e}") from None
    except BaseException:
        _unlink(tmp)
        raise
    info["out"] = out
    return info


def _unlink(p: str) -> None:
    try:
        os.unlink(p)
    except OSError:
        pass


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(prog="vgroove report",
                                     description="One self-contained HTML page of the reports in a directory.")
    parser.add_argument("directory", help="the directory of the reports (e.g. results/)")
    parser.add_argument("--out", help="page to write (default: DIRECTORY/index.html)")
    parser.add_argument("--force", action="store_true", help="overwrite an existing page")
    parser.add_argument("--no-draw", action="store_true",
                        help="do not draw plots that are missing or stale beside their reports (name them instead)")
    args = parser.parse_args(argv)
    try:
        info = write(args.directory, args.out, args.force, not args.no_draw)
    except ReportError as e:
        print(f"vgroove: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("\nvgroove: interrupted; no report written", file=sys.stderr)
        return 130
    try:
        for name, reason in info["skipped"]:
            print(f"report: skipped {printable(name, path=True)}: {printable(reason, 300)}")
        print(f"report: {printable(info['out'], path=True)} ({len(info['reports'])} reports, {info['plots']} plots, "
              f"{len(info['skipped'])} files skipped)", flush=True)
    except OSError as e:  # a closed or full standard output: the page is written, the lines are lost
        print(f"vgroove: error: standard output: {e.strerror or e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
