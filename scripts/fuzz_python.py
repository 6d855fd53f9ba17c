#!/usr/bin/env python3
"""Fuzzes the Python module's entry points (import vgroove) under an address-space limit.

Deterministic mutation fuzzing: a corpus entry (tests/fuzz/corpus/python_entry/*.json) is one call,
{"call": NAME, "args": [...], "kwargs": {...}}, with its arguments written as JSON (arrays, surfaces,
files, callables and non-finite numbers as the tagged objects of `decode`). Each step takes an
entry and mutates one argument (a number to an edge: 0, -1, 2^63, 1e308, NaN, inf, a fraction
where an integer goes; a string to another name or a hostile one; an array to another shape, dtype,
or values; an argument removed, or one added that the function does not take), then runs the call
in a child process whose address space is limited (RLIMIT_AS, `ulimit -v`: --memory-mib, default
2048) with a time limit per call (--call-seconds, default 20).

What a call may do: return, or raise ValueError or TypeError (a bad argument: one line naming it),
or MemoryError with the module's own one-line message (an estimate refused it, or an allocation
failed under the limit). A finding is anything else: the child killed by a signal (a crash), a
call that outlives its time limit (a hang: the mutations keep every count small or invalid, so no
call is long by its arguments), another exception type, a message of several lines, or a
MemoryError that is not the module's (a bare std::bad_alloc). A finding's entry is saved as
finding-*.json in --findings and the run exits 1.

A mutant whose outcome is new (the call and the exception type with its message's numbers and
names blanked, or "returned") is added to the corpus, up to --max-corpus entries.

    scripts/fuzz_python.py [--seconds 60] [--seed 1] [--iterations N] [--corpus DIR] [--findings DIR]
    scripts/fuzz_python.py --replay [--corpus DIR]     every corpus entry once (tests/python/test_fuzz_entry_points.py)
    (Debian's /usr/bin/python3 with numpy; PYTHONPATH=build/python; scripts/fuzz.sh SECONDS python_entry)

The same seed and iteration count give the same mutants.
"""

from __future__ import annotations

import argparse
import copy
import hashlib
import json
import math
import os
import random
import re
import resource
import signal
import subprocess
import sys
import tempfile
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
CORPUS = os.path.join(ROOT, "tests", "fuzz", "corpus", "python_entry")

# Edges for numbers: every count here is small, out of its range, or a size whose memory the module
# must estimate before it allocates (10^4 bins per axis, 10^7 grooves), so a call's cost stays
# small whatever it gets (a long call is then a hang, not a legitimately long run).
NUMBERS = [0, -1, 1, 2, 3, 7, 10000, 10**7, 2**31, 2**63, -(2**63), 10**30, 0.5, -0.0, 1e-320, 1e-9, 0.01, 2.0000001, 89.9,
           89.99999999, 90, 91, 180, 181, -90.5, 1e308, -1e308, {"float": "nan"}, {"float": "inf"},
           {"float": "-inf"}, True, None, "x", [], [1, 2]]
STRINGS = ["ggx", "beckmann", "phong", "vgroove", "cook-torrance", "cook_torrance", "vgroove-nonsymmetric", "3d",
           "flatland", "vndf", "printed", "smith-vndf", "bounded-vndf", "random", "stratified", "corrected",
           "printed", "", " ", "GGX", "x" * 10000, "\x00", "\ud800", "../../etc/passwd", 0, None]
VALUES = [0.0, -0.0, 1.0, -1.0, 0.5, 1e-320, 1e308, {"float": "nan"}, {"float": "inf"}, 0.7071067811865476]
SHAPES = [[0, 3], [1, 3], [3], [2, 2], [5, 3], [1, 1, 3], [4, 5], [0], [2, 0]]
DTYPES = ["float64", "float32", "int64", "complex128", "bool", "object"]


# ------------------------------------------------------------------------------------------------
# Entries: JSON to Python arguments.

def decode(v, tmp):
    """A JSON value to the argument: {"float": "nan"} a float; {"array": {"shape", "values", "dtype"}}
    a NumPy array of that shape whose values cycle through `values`; {"unit": {"n", "theta_deg"}} n
    unit vectors; {"microsurface": {kwargs}} vgroove.microsurface(**kwargs); {"file": JSON} a file
    holding that JSON (its path); {"callable": "zeros"|"ones"|"nan"|"raise"|"shape"|"negative"} a
    check_brdf model."""
    import numpy as np
    import vgroove
    if isinstance(v, list):
        return [decode(x, tmp) for x in v]
    if not isinstance(v, dict):
        return v
    if set(v) == {"float"}:
        return float(v["float"])
    if set(v) == {"array"}:
        a = v["array"]
        shape = tuple(int(s) for s in a.get("shape", [0]))
        n = int(np.prod(shape)) if shape else 1
        vals = [decode(x, tmp) for x in a.get("values", [0.0])] or [0.0]
        dtype = a.get("dtype", "float64")
        flat = [vals[i % len(vals)] for i in range(n)]
        try:
            return np.array(flat, dtype=dtype).reshape(shape)
        except (ValueError, TypeError, OverflowError):
            return np.array(flat, dtype=object).reshape(shape)
    if set(v) == {"unit"}:
        u = v["unit"]
        return vgroove.direction(np.full(int(u.get("n", 1)), float(u.get("theta_deg", 30.0))),
                                 np.linspace(0.0, 359.0, int(u.get("n", 1))))
    if set(v) == {"microsurface"}:
        return vgroove.microsurface(**{k: decode(x, tmp) for k, x in v["microsurface"].items()})
    if set(v) == {"file"}:
        path = os.path.join(tmp, hashlib.sha1(json.dumps(v, sort_keys=True).encode()).hexdigest()[:12] + ".json")
        with open(path, "w") as f:
            json.dump(v["file"], f)
        return path
    if set(v) == {"callable"}:
        kind = v["callable"]

        def f(wi, wo):
            n = len(wi)
            if kind == "raise":
                raise ZeroDivisionError("the model's own error")
            if kind == "shape":
                return np.zeros(n + 1)
            return np.full(n, {"zeros": 0.0, "ones": 1.0, "nan": float("nan"), "negative": -1.0}.get(kind, 0.0))
        return f
    return {k: decode(x, tmp) for k, x in v.items()}


def blank(message):
    """The message with its numbers, quoted names and paths blanked: the shape of the outcome."""
    m = re.sub(r"/[\w./-]+", "PATH", message)
    m = re.sub(r"\"[^\"]*\"|'[^']*'", "NAME", m)
    m = re.sub(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?|nan|inf", "N", m)
    return m[:200]


def run_entry(entry, tmp):
    """The call's outcome: ("returned", None), ("raised", (type, message)) or ("finding", text)."""
    import vgroove
    fn = getattr(vgroove, entry["call"], None)
    if fn is None or not callable(fn):
        return "finding", f"no entry point {entry['call']!r}"
    try:
        args = decode(entry.get("args", []), tmp)
        kwargs = decode(entry.get("kwargs", {}), tmp)
    except (ValueError, TypeError, MemoryError) as e:  # a surface argument refused while building it
        return "raised", (type(e).__name__, str(e).splitlines()[0] if str(e) else "")
    except Exception as e:  # noqa: BLE001 (a tagged object the harness cannot build: not a call)
        return "raised", ("undecodable", f"{type(e).__name__}: {e}")
    try:
        fn(*args, **kwargs)
        return "returned", None
    except (ValueError, TypeError, MemoryError, ZeroDivisionError) as e:
        text = str(e)
        if type(e) is ZeroDivisionError and text != "the model's own error":
            return "finding", f"ZeroDivisionError: {text}"
        # pybind11's TypeError for an argument of the wrong type lists the signatures (Python's
        # convention for a wrong type); every other message is one line.
        pybind = type(e) is TypeError and "incompatible function arguments" in text
        if ("\n" in text and not pybind) or not text:
            return "finding", f"{type(e).__name__} without a one-line message: {text!r}"
        text = text.splitlines()[0]
        if type(e) is MemoryError and not text.startswith("out of memory") and "memory" not in text:
            return "finding", f"MemoryError that is not the module's: {text!r}"
        return "raised", (type(e).__name__, text)
    except Exception as e:  # noqa: BLE001 (any other type is the finding)
        return "finding", f"{type(e).__name__}: {e}"


# ------------------------------------------------------------------------------------------------
# The child: runs entries under the limits, one JSON line per outcome on stdout.

def child(memory_mib, call_seconds):
    resource.setrlimit(resource.RLIMIT_AS, (memory_mib << 20, memory_mib << 20))
    import warnings
    warnings.simplefilter("error")  # a warning (ComplexWarning: an input's imaginary part dropped) is raised

    def alarm(_sig, _frame):
        raise TimeoutError

    signal.signal(signal.SIGALRM, alarm)
    import numpy  # noqa: F401 (before the limit bites: the interpreter's own imports)
    import vgroove  # noqa: F401
    with tempfile.TemporaryDirectory() as tmp:
        for line in iter(sys.stdin.readline, ""):
            entry = json.loads(line)
            signal.alarm(call_seconds)
            try:
                kind, what = run_entry(entry, tmp)
            except TimeoutError:
                kind, what = "finding", f"still running after {call_seconds} s"
            finally:
                signal.alarm(0)
            print(json.dumps({"kind": kind, "what": what}), flush=True)


def run_batch(entries, memory_mib, call_seconds):
    """Runs the entries in a child, one at a time (a new child after a crash or a call that does not
    come back: the child is killed call_seconds + 10 s after the call began, should its own alarm
    not reach a loop that never returns to the interpreter); returns one outcome per entry."""
    import select
    out = []
    rest = list(entries)
    while rest:
        p = subprocess.Popen([sys.executable, os.path.abspath(__file__), "--child", "--memory-mib", str(memory_mib),
                              "--call-seconds", str(call_seconds)], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                             text=True, bufsize=1, env=dict(os.environ, OMP_NUM_THREADS="1"))
        done = 0
        for e in rest:
            try:
                p.stdin.write(json.dumps(e) + "\n")
                p.stdin.flush()
            except BrokenPipeError:
                break
            ready, _, _ = select.select([p.stdout], [], [], call_seconds + 10)
            line = p.stdout.readline() if ready else ""
            if not line:
                break
            out.append(json.loads(line))
            done += 1
        if done < len(rest):  # the child died or hung on entry `done`
            p.kill()
            code = p.wait()
            out.append({"kind": "finding", "what": f"the process died or hung (exit {code})"})
            done += 1
        else:
            p.stdin.close()
            p.wait()
        rest = rest[done:]
    return out


def signature(entry, outcome):
    if outcome["kind"] == "returned":
        return f"{entry['call']}: returned"
    if outcome["kind"] == "raised":
        return f"{entry['call']}: {outcome['what'][0]}: {blank(outcome['what'][1])}"
    return f"{entry['call']}: FINDING"


# ------------------------------------------------------------------------------------------------
# Mutations.

def places(entry):
    """(container, key) of every argument value and of the values inside tagged objects."""
    out = []

    def walk(c, k, depth=0):
        out.append((c, k))
        v = c[k]
        if depth > 4:
            return
        if isinstance(v, dict) and set(v) in ({"array"}, {"float"}, {"callable"}, {"unit"}):
            return  # mutated whole (mutate)
        if isinstance(v, dict) and set(v) in ({"microsurface"}, {"file"}):
            v = v[next(iter(v))]  # the surface's arguments, the file's JSON
        if isinstance(v, dict):
            for kk in sorted(v):
                walk(v, kk, depth + 1)
        elif isinstance(v, list):
            for i in range(len(v)):
                walk(v, i, depth + 1)
    for i in range(len(entry.get("args", []))):
        walk(entry["args"], i)
    for k in sorted(entry.get("kwargs", {})):
        walk(entry["kwargs"], k)
    return out


def mutate(entry, rng):
    e = copy.deepcopy(entry)
    e.setdefault("args", [])
    e.setdefault("kwargs", {})
    op = rng.randrange(10)
    if op == 0 and e["kwargs"]:
        del e["kwargs"][rng.choice(sorted(e["kwargs"]))]
        return e
    if op == 1:
        e["kwargs"][rng.choice(["rays", "seed", "threads", "max_k", "dim", "bogus", "theta_bins", "grooves"])] = \
            rng.choice(NUMBERS + STRINGS)
        return e
    ps = places(e)
    if not ps:
        return e
    c, k = rng.choice(ps)
    v = c[k]
    if isinstance(v, dict) and set(v) == {"array"} and rng.random() < 0.8:
        a = v["array"]
        which = rng.randrange(3)
        if which == 0:
            a["shape"] = rng.choice(SHAPES)
        elif which == 1:
            a["dtype"] = rng.choice(DTYPES)
        else:
            a["values"] = [rng.choice(VALUES) for _ in range(rng.randrange(1, 4))]
    elif isinstance(v, dict) and set(v) == {"unit"} and rng.random() < 0.8:
        u = v["unit"]
        if rng.random() < 0.5:
            u["n"] = rng.choice([0, 1, 2, 5])
        else:
            u["theta_deg"] = rng.choice([0.0, 30.0, 89.9, 89.99999, 89.99999999999999, 90.0])
    elif isinstance(v, dict) and set(v) == {"callable"} and rng.random() < 0.8:
        v["callable"] = rng.choice(["zeros", "ones", "nan", "raise", "shape", "negative"])
    elif isinstance(v, str):
        c[k] = rng.choice(STRINGS + NUMBERS)
    elif isinstance(v, (dict, list)) and rng.random() < 0.5:
        c[k] = rng.choice(NUMBERS + STRINGS)
    else:
        c[k] = rng.choice(NUMBERS)
    return e


def entry_name(entry):
    return hashlib.sha1(json.dumps(entry, sort_keys=True).encode()).hexdigest()[:16] + ".json"


def load_corpus(d):
    entries = []
    for name in sorted(os.listdir(d)):
        if name.endswith(".json"):
            with open(os.path.join(d, name)) as f:
                entries.append((name, json.load(f)))
    return entries


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seconds", type=float, default=60.0)
    ap.add_argument("--iterations", type=int, default=0)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--corpus", default=CORPUS)
    ap.add_argument("--findings", default=".")
    ap.add_argument("--max-corpus", type=int, default=400)
    ap.add_argument("--memory-mib", type=int, default=2048)
    ap.add_argument("--call-seconds", type=int, default=20)
    ap.add_argument("--batch", type=int, default=50)
    ap.add_argument("--replay", action="store_true")
    ap.add_argument("--child", action="store_true")
    a = ap.parse_args()
    if a.child:
        child(a.memory_mib, a.call_seconds)
        return 0
    corpus = load_corpus(a.corpus)
    outcomes = run_batch([e for _, e in corpus], a.memory_mib, a.call_seconds)
    findings = [(n, e, o) for (n, e), o in zip(corpus, outcomes) if o["kind"] == "finding"]
    for n, e, o in findings:
        print(f"fuzz_python: {n}: {e['call']}: {o['what']}", file=sys.stderr)
    if a.replay:
        print(f"fuzz_python: replayed {len(corpus)} entries, {len(findings)} findings", file=sys.stderr)
        return 1 if findings else 0
    seen = {signature(e, o) for (_, e), o in zip(corpus, outcomes)}
    rng = random.Random(a.seed)
    t0, it, added = time.monotonic(), 0, 0
    while (a.iterations and it < a.iterations) or (not a.iterations and time.monotonic() - t0 < a.seconds):
        mutants = [mutate(rng.choice(corpus)[1], rng) for _ in range(a.batch)]
        it += len(mutants)
        for m, o in zip(mutants, run_batch(mutants, a.memory_mib, a.call_seconds)):
            if o["kind"] == "finding":
                os.makedirs(a.findings, exist_ok=True)
                path = os.path.join(a.findings, "finding-" + entry_name(m))
                with open(path, "w") as f:
                    json.dump(m, f, indent=1)
                print(f"fuzz_python: FINDING {m['call']}: {o['what']} ({path})", file=sys.stderr)
                findings.append((path, m, o))
                continue
            s = signature(m, o)
            if s not in seen and len(corpus) < a.max_corpus:
                seen.add(s)
                name = entry_name(m)
                with open(os.path.join(a.corpus, name), "w") as f:
                    json.dump(m, f, indent=1, sort_keys=True)
                corpus.append((name, m))
                added += 1
    print(f"fuzz_python: {it} mutants, {added} new corpus entries ({len(corpus)} in all), {len(findings)} findings",
          file=sys.stderr)
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
