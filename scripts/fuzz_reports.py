#!/usr/bin/env python3
"""Fuzzes `vgroove plot`'s input: report JSON files, read by python/vgroove/plot.py.

Deterministic mutation fuzzing: starting from the corpus (tests/fuzz/corpus/report_plot/: small
reports of every kind), each step takes a corpus entry and mutates it (structurally: a value
replaced by null, a wrong type, an empty/short/long list, a huge or negative number, a hostile
string, a key deleted or added, deep nesting; or as bytes: truncated, a byte changed or
inserted), then runs what `vgroove plot` runs: load_report + figures_for (the validation), and for
reports that pass it, every figure rendered (PNG, in memory). The only exception allowed is
ReportError (a ValueError: the one-line "cannot draw" message, exit 2); anything else is a
finding: the input is saved as finding-*.json in --findings and the run exits 1.

A mutant whose outcome is new (the report kind and the error message with its numbers and
names blanked, or "drawn" per kind) is added to the corpus, up to --max-corpus files, so the
corpus stays small and each file stands for one path through the checks.

    scripts/fuzz_reports.py [--seconds 60] [--seed 1] [--iterations N] [--corpus DIR] [--findings DIR]
    (Debian's /usr/bin/python3, with python3-matplotlib; scripts/fuzz.sh SECONDS report_plot runs it)

The same seed and iteration count give the same mutants. tests/python/test_plot.py replays the
corpus on every test run.
"""

from __future__ import annotations

import argparse
import copy
import hashlib
import importlib.util
import io
import json
import os
import random
import re
import sys
import time
import traceback

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
HOSTILE = ['<R&D> "quotes"', "<script>alert(1)</script>", "$\\frac{1}{$", "\x00\x1b[2J", "\u202e\ud800",
           "x" * 10000, "../../x", "", " ", "%s%n", "NaN", "1e400"]
NUMBERS = [0, -1, 1, -0.0, 1e-320, 1e308, -1e308, 10**30, -(10**30), 2**63, 0.5, 90, 180, 91, -91, 1e400, -1e400]


def load_plot():
    path = os.path.join(ROOT, "python", "vgroove", "plot.py")
    spec = importlib.util.spec_from_file_location("vgroove_plot_fuzzed", path)
    m = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(m)
    return m


def paths(v, max_depth=64):
    """Every path to a value in the JSON tree (the root included), down to max_depth."""
    out, stack = [], [((), v)]
    while stack:
        prefix, x = stack.pop()
        out.append(prefix)
        if len(prefix) >= max_depth:
            continue
        if isinstance(x, dict):
            stack += [(prefix + (k,), y) for k, y in x.items()]
        elif isinstance(x, list):
            stack += [(prefix + (n,), y) for n, y in enumerate(x)]
    out.sort(key=lambda p: [str(q) for q in p])  # the same order whatever the traversal
    return out


def get(v, path):
    for p in path:
        v = v[p]
    return v


def put(root, path, value):
    if not path:
        return value
    get(root, path[:-1])[path[-1]] = value
    return root


def mutate_value(rng, v):
    choice = rng.randrange(14)
    if choice == 0:
        return None
    if choice == 1:
        return rng.choice(NUMBERS)
    if choice == 2:
        return rng.choice(HOSTILE)
    if choice == 3:
        return []
    if choice == 4:
        return {}
    if choice == 5:
        return [v]
    if choice == 6:
        return rng.choice([True, False])
    if choice == 7 and isinstance(v, list) and v:
        return v[: rng.randrange(len(v))]  # short
    if choice == 8 and isinstance(v, list) and v:
        return v + [copy.deepcopy(rng.choice(v)) for _ in range(rng.randrange(1, 4))]  # long
    if choice == 9 and isinstance(v, (int, float)) and not isinstance(v, bool):
        return v * rng.choice([-1, 0, 2, 1e10, 1e-10, 1e300])
    if choice == 10 and isinstance(v, dict) and v:
        v = dict(v)
        v.pop(rng.choice(sorted(v)))
        return v
    if choice == 11 and isinstance(v, dict):
        v = dict(v)
        v[rng.choice(["plane", "cases", "suites", "runs", "kind", "x"])] = rng.choice([None, [], {}, 1, "brdf"])
        return v
    if choice == 12:
        depth = rng.choice([10, 100, 1000, 50000])
        for _ in range(depth):
            v = [v]
        return v
    if isinstance(v, str):
        return rng.choice(["brdf", "furnace", "table2", "check_brdf", "ggx", "3d", "flatland", "phong"])
    return rng.choice(NUMBERS)


def mutate(rng, data: bytes) -> bytes:
    try:
        doc = json.loads(data)
    except (ValueError, RecursionError):
        doc = None
    if doc is not None and rng.random() < 0.85:
        for _ in range(rng.choice([1, 1, 1, 2, 3, 5])):
            ps = paths(doc)
            path = rng.choice(ps)
            try:
                doc = put(doc, path, mutate_value(rng, copy.deepcopy(get(doc, path))))
            except RecursionError:
                return data
        try:
            return json.dumps(doc, allow_nan=True).encode()
        except (ValueError, RecursionError):
            return data
    b = bytearray(data)
    op = rng.randrange(3)
    if op == 0 and b:
        del b[rng.randrange(len(b)):]
    elif op == 1 and b:
        b[rng.randrange(len(b))] = rng.randrange(256)
    else:
        pos = rng.randrange(len(b) + 1)
        b[pos:pos] = rng.choice([b"null", b"[", b"{", b"\"", b"1e999", b"NaN", b"-", b"\\u0000", b"\xff"])
    return bytes(b)


def signature(plot, data: bytes, render: bool):
    """What happens to the input, as a short outcome string; raises on a finding."""
    path = "/fuzz/report.json"
    try:
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError:
            raise plot.ReportError(f"{path}: not UTF-8")

        def constant(name):
            raise plot.ReportError(f"{path}: {name} is not JSON")

        try:
            doc = json.loads(text, parse_constant=constant)
        except json.JSONDecodeError:
            raise plot.ReportError(f"{path}: not JSON")
        except RecursionError:
            raise plot.ReportError(f"{path}: nested too deeply")
        figs = plot.figures_for(doc, path)
    except plot.ReportError as e:
        msg = re.sub(r"\"[^\"]*\"", "S", str(e))
        msg = re.sub(r"/\d+", "/N", msg)
        msg = re.sub(r"-?\d+(\.\d+)?(e[-+]?\d+)?", "N", msg)
        return "error: " + msg[:160]
    kind = plot.report_kind(plot.Node(doc, path))
    if render:
        for _, draw in figs:
            fig = draw()
            fig.savefig(io.BytesIO(), format="png", dpi=20)
    return f"drawn: {kind} x{len(figs)}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seconds", type=float, default=60.0)
    ap.add_argument("--iterations", type=int, default=0, help="stop after this many mutants (0: by time)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--corpus", default=os.path.join(ROOT, "tests", "fuzz", "corpus", "report_plot"))
    ap.add_argument("--findings", default=os.path.join(ROOT, "build-fuzz", "report_plot"))
    ap.add_argument("--max-corpus", type=int, default=64)
    ap.add_argument("--render-every", type=int, default=8, help="render the figures of 1 in N drawable mutants")
    args = ap.parse_args()

    import matplotlib
    matplotlib.use("Agg")
    plot = load_plot()
    rng = random.Random(args.seed)
    names = sorted(os.listdir(args.corpus))
    corpus = [open(os.path.join(args.corpus, n), "rb").read() for n in names]
    if not corpus:
        sys.exit(f"fuzz_reports: empty corpus {args.corpus}")
    seen = set()
    for data in corpus:
        seen.add(signature(plot, data, render=True))
    start = time.monotonic()
    n = drawn = added = 0
    while True:
        if args.iterations and n >= args.iterations:
            break
        if not args.iterations and time.monotonic() - start >= args.seconds:
            break
        n += 1
        data = mutate(rng, rng.choice(corpus))
        try:
            sig = signature(plot, data, render=(n % args.render_every == 0))
        except Exception:  # a finding: anything but ReportError
            os.makedirs(args.findings, exist_ok=True)
            name = os.path.join(args.findings, "finding-" + hashlib.sha1(data).hexdigest() + ".json")
            with open(name, "wb") as f:
                f.write(data)
            traceback.print_exc()
            print(f"fuzz_reports: FINDING after {n} mutants: {name}", file=sys.stderr)
            return 1
        drawn += sig.startswith("drawn")
        if sig not in seen and len(corpus) < args.max_corpus and len(data) <= 64 * 1024:
            seen.add(sig)
            corpus.append(data)
            added += 1
            with open(os.path.join(args.corpus, hashlib.sha1(data).hexdigest()), "wb") as f:
                f.write(data)
    elapsed = time.monotonic() - start
    print(f"fuzz_reports: {n} mutants in {elapsed:.0f} s ({n / max(elapsed, 1e-9):.0f}/s), {drawn} drawable, "
          f"{len(seen)} outcomes, {added} added to the corpus ({len(corpus)} files), no finding")
    return 0


if __name__ == "__main__":
    sys.exit(main())
