#!/usr/bin/env python3
"""same_report.py A B: exit 0 when the two report JSON files are equal value for value (floats bit for
bit) once the timings are set aside: keys named threads or timing (what a report derives from wall
time: rates, a sampling strategy's efficiency = 1 / (variance x time), the strategy it favours), or
ending in _s (a duration in seconds: wall_s, sim_s, sample_s, ...), or holding a rate (*_per_s,
*ns_per_*, *_per_hour), and what is chosen by wall time (bench accuracy's soonest_to_thresholds:
the placement that reaches the thresholds first). Otherwise print the first difference (its JSON
path) and exit 1.
With --provenance-aside the version and git revision that made each report are set aside too (two builds
compared: scripts/compare_reports.sh)."""
import json
import sys


PROVENANCE = set()


def timing(key):
    return key in PROVENANCE or key in ("threads", "timing", "soonest_to_thresholds") \
        or key.endswith("_s") or "ns_per" in key or key.endswith("_per_hour")


def first_difference(a, b, path="$"):
    if isinstance(a, dict) and isinstance(b, dict):
        keys_a = {k for k in a if not timing(k)}
        keys_b = {k for k in b if not timing(k)}
        if keys_a != keys_b:
            return f"{path}: keys differ: {sorted(keys_a ^ keys_b)}"
        for k in sorted(keys_a):
            d = first_difference(a[k], b[k], f"{path}.{k}")
            if d:
                return d
        return None
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return f"{path}: {len(a)} against {len(b)} entries"
        for i, (x, y) in enumerate(zip(a, b)):
            d = first_difference(x, y, f"{path}[{i}]")
            if d:
                return d
        return None
    # Floats compare by their exact value (the JSON holds the shortest round-trip text).
    if type(a) is not type(b) or a != b:
        return f"{path}: {a!r} against {b!r}"
    return None


def main():
    args = sys.argv[1:]
    if args[:1] == ["--provenance-aside"]:
        PROVENANCE.update(("version", "git"))
        args = args[1:]
    if len(args) != 2:
        sys.exit("usage: same_report.py [--provenance-aside] A.json B.json")
    sys.argv[1:] = args
    with open(sys.argv[1]) as fa, open(sys.argv[2]) as fb:
        a, b = json.load(fa), json.load(fb)
    d = first_difference(a, b)
    if d:
        print(f"{sys.argv[1]} and {sys.argv[2]} differ at {d}")
        sys.exit(1)


if __name__ == "__main__":
    main()
