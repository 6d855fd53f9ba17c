#!/usr/bin/env python3
"""merge_parts_test.py VGROOVE: `vgroove merge` reads shard parts as strictly as suite files.

Real parts of every kind that shards (brdf in flatland and 3D, table2, single grooves, energy,
glass tables, simulate) are damaged one value at a time, in their tallies, their headers and their provenance: counts made negative, fractional, 1e300, 2^64, off by
one or of the wrong type; arrays cut, extended or emptied; model values of the wrong type. Each
damaged set must be refused with exit 2, one line on stderr naming the damaged part and the JSON
path of the value, and no report; only a value no check can see (timings, and counts that no sum
constrains: bounces, max_k_seen, ...) may merge, with exit 0. Never a crash. A fixed seed picks
one instance of every value's place (its JSON path with indices as #), so the set is the same
each run. The undamaged parts merge (the control).

Every number that is not a count gets "another number" too: 3333, -1, 7 and a value slightly off.
A model value (a unit's fixed part) is a fraction of the incident flux within [0, 1] whose sums
must hold (rows to their totals, Schlick's channels to the split sum, Cycles' table to itself),
so each of those is refused, but for the few values no sum constrains, which may merge when only
slightly off (SLIGHTLY_UNSEEN)."""
import concurrent.futures
import copy
import json
import os
import random
import re
import subprocess
import sys
import tempfile

VGROOVE = os.path.abspath(sys.argv[1])
T = tempfile.mkdtemp(prefix="merge_parts_")

SUITES = {
    "brdf.json": {"name": "tiny_brdf", "kind": "brdf", "ndf": ["ggx"], "alpha": [0.5], "theta_i_deg": [40],
                  "dimensions": ["flatland", "3d"], "rays": 3000, "grooves": 500, "seed": 3, "flatland_bins": 6,
                  "theta_bins": 3, "phi_bins": 4, "max_k": 3,
                  "thresholds": {"sigmas": 5, "model_tolerance": {"flatland": 1e-5, "3d": 1e-4}}},
    "table2.json": {"name": "tiny_table2", "kind": "table2", "ndf": ["ggx"], "alpha": [0.5], "percentiles": [90],
                    "rays": 2000, "grooves": 500, "seed": 1,
                    "paper": {"source": "made up for the tests", "max_bounces": [[2]]}},
    "table1.json": {"name": "tiny_table1", "kind": "table1",
                    "groove": {"type": "symmetric", "theta_v_deg": {"from": 50, "to": 90, "step": 40}},
                    "theta_i_deg": {"from": 0, "to": 30, "step": 30}, "rays": 100, "sampling": "random", "seed": 7,
                    "probe_vertices": True,
                    "thresholds": {"max_l1": 0.5, "mean_l1": 0.5, "max_theta_o_error_rad": 1e-9}},
    "scene.json": {"scene": "tiny_gold", "geometry": {"kind": "groove", "theta_v_deg": 60},
                   "light": {"theta_i_deg": [30], "rays": 2000, "sampling": "stratified", "seed": 1},
                   "effects": {"fresnel": {"kind": "conductor",
                                           "wavelengths": [{"lambda_nm": 548.6, "eta": 0.43, "kappa": 2.455}]},
                               "record": {"theta_o_histograms": {"bins": 4, "max_k": 2}, "energy_per_k": True},
                               "max_bounces": 1000}},
    "audit.json": {"name": "tiny_audit", "kind": "energy_audit", "ndf": ["ggx", "beckmann"], "alpha": [0.5],
                   "mu": [0.5, 1.0], "walk_paths": 2000, "seed": 1, "max_k": 3, "grey_F0": [0.04, 1.0],
                   "metals": ["Au"], "metalness": [0.5], "regions": {"rough_alpha": 0.5, "grazing_mu": 0.5},
                   "cycles_table": True, "thresholds": {"sigmas": 5, "vgroove_furnace": 1e-7}},
}
COMMANDS = {
    "brdf": ["validate", f"{T}/brdf.json"],
    "table2": ["validate", f"{T}/table2.json"],
    "table1": ["validate", f"{T}/table1.json"],
    "energy": ["energy", "--ndf", "ggx,beckmann", "--dim", "flatland,3d", "--mu-points", "1", "--alpha-points", "1",
               "--rays", "2000", "--max-k", "3"],
    "glass": ["energy", "--eta", "1.5", "--dim", "3d,flatland", "--alpha", "0.3", "--mu", "1", "--rays", "2000",
              "--grooves", "200", "--max-k", "3"],
    "simulate": ["simulate", f"{T}/scene.json"],
    "audit": ["validate", f"{T}/audit.json"],
}
# Values no check can see: timings, and counts that no sum or bound over the others constrains.
UNSEEN = {"thread_s", "wall_s", "model_s", "bounces", "max_k_seen", "k", "zones", "grid", "uncertified_cells",
          "threads", "input_file"}  # (the input as given: found by its absolute path when it is not there)
# Numbers in [0, 1] that no sum or recomputation ties to another value: slightly off, they merge.
# The energy table's Cook-Torrance albedo; the audit's single-scattering albedos, a conductor's
# albedo (one of the channels of *_E_F), Filament's texel, the V-groove rows (bounded by their
# total, not tied to it); a facet's figures below its case's largest.
# The audit's tally keeps each row's energy in units of 2^-32, bounded by its paths, with no sum.
# The glass tables' interactions: at least one per ray, at most max_interactions, with no sum.
UNSEEN_BY_KIND = {"audit": {"energy"}, "glass": {"interactions"}}
# The audit's headers are every kind's (damaged above): its units of one part are damaged alone.
DAMAGED = {"audit": ((0,), ("units",))}
SLIGHTLY_UNSEEN = {"cook_torrance", "E", "E_avg", "smith_E_F", "vcavity_E_F", "separable_E_F", "filament_dfg_y", "vgroove_rows",
                   "l1", "theta_o_error", "missed_bound", "narrowest_zone"}
# A single groove's facet outcome holds these counts within its rays, with no sum over them.
UNSEEN_IN_FACETS = {"vertex_hits", "bounce_limit", "wrong_first"}


def run(args):
    return subprocess.run([VGROOVE] + args, capture_output=True, text=True)


def leaves(j, path=()):
    """(path, value) of every leaf and every array, depth first."""
    if isinstance(j, dict):
        for k, v in j.items():
            yield from leaves(v, path + (k,))
    elif isinstance(j, list):
        yield path, j
        for n, v in enumerate(j):
            yield from leaves(v, path + (n,))
    else:
        yield path, j


def shape(path):
    return "/".join("#" if isinstance(p, int) else p for p in path)


def mutations(path, value, kind=""):
    """(label, new value) for a leaf; the label says whether a check must see it."""
    key = next((p for p in reversed(path) if isinstance(p, str)), "")
    seen = key not in UNSEEN and not ("facets" in path and key in UNSEEN_IN_FACETS) and \
        key not in UNSEEN_BY_KIND.get(kind, ())
    if isinstance(value, list):
        out = [("empty", [], True), ("cut", value[:-1], bool(value)), ("extended", value + [value[-1] if value else 0], True)]
        return out
    if isinstance(value, bool):
        return [("number", 1, True), ("string", "true", True)]
    if isinstance(value, int):
        return [("negative", -1, seen or value >= 0), ("fractional", value + 0.5, seen), ("1e300", 1e300, seen),
                ("2^64", 2 ** 64, seen), ("string", str(value), True), ("null", None, True),
                ("off by one", value + 1, seen)]
    if isinstance(value, float) or (isinstance(value, str) and value in ("nan", "inf", "-inf")):
        x = float(value)
        slightly = x * (1 + 1e-6) + 1e-9 if x == x else 0.5
        out = [("string", "x" + repr(value), True), ("null", None, True), ("bool", True, True)]
        # Model values, and a single groove's figures (l1 within [0, 2], the others [0, pi] or
        # [0, 1], each case's the largest of its facets').
        if seen and ("fixed" in path or key in ("l1", "theta_o_error", "missed_bound", "narrowest_zone")):
            out += [("3333", 3333.0, True), ("-1", -1.0, True), ("7", 7.0, True),
                    ("slightly off", slightly, key not in SLIGHTLY_UNSEEN)]
        return out
    if isinstance(value, str):
        return [("other string", value + "x", seen), ("null", None, True)]
    return []


def set_at(j, path, value):
    for p in path[:-1]:
        j = j[p]
    j[path[-1]] = value


def check_kind(name):
    cmd = COMMANDS[name]
    parts = [f"{T}/{name}.part{i}.json" for i in (1, 2)]
    for i, p in enumerate(parts, 1):
        r = run(cmd + ["--threads", "1", "--shard", f"{i}/2", "--out", p])
        assert r.returncode in (0, 1), f"{name}: shard {i}/2: exit {r.returncode}: {r.stderr}"
    control = run(["merge"] + parts + ["--out", f"{T}/{name}.merged.json"])
    assert control.returncode in (0, 1) and os.path.exists(f"{T}/{name}.merged.json"), \
        f"{name}: the control merge: exit {control.returncode}: {control.stderr}"
    failures, tried = [], 0
    rng = random.Random(2026)
    which, roots = DAMAGED.get(name, ((0, 1), ("units", "partial", "tool", "schema_version", "version", "git")))
    for damaged in which:
        part = json.load(open(parts[damaged]))
        by_shape = {}
        for root in roots:
            for path, value in leaves(part[root], (root,)):
                # The job's descriptor is compared whole with the other parts' and the rebuilt
                # one: its top-level values stand for the rest (a deep damage is the same check).
                if path[:2] == ("partial", "job") and len(path) > 3:
                    continue
                by_shape.setdefault(shape(path), []).append((path, value))
        for s in sorted(by_shape):
            path, value = rng.choice(by_shape[s])
            for label, new, must_refuse in mutations(path, value, name):
                if new == value and type(new) is type(value):
                    continue  # no change
                bad = copy.deepcopy(part)
                set_at(bad, path, new)
                bad_file = f"{T}/{name}.bad{damaged + 1}.json"
                out = f"{T}/{name}.out.json"
                with open(bad_file, "w") as f:
                    json.dump(bad, f)
                files = list(parts)
                files[damaged] = bad_file
                r = run(["merge"] + files + ["--out", out])
                tried += 1
                where = "/" + "/".join(str(p) for p in path)
                if r.returncode == 2:
                    problems = []
                    if os.path.exists(out):
                        problems.append("wrote a report")
                    if r.stderr.count("\n") != 1:
                        problems.append("not one line")
                    if bad_file not in r.stderr:
                        problems.append("the part is not named")
                    if path[0] in ("units", "partial") and not re.search(r"/(units|partial|job)(/|\b)", r.stderr):
                        problems.append("no JSON path")
                    if problems:
                        failures.append(f"{name}: {where} {label}: {', '.join(problems)}: {r.stderr.strip()}")
                elif r.returncode in (0, 1) and not must_refuse:
                    pass
                else:
                    failures.append(f"{name}: {where} {label} ({json.dumps(new)[:40]}): exit {r.returncode}"
                                    f"{' (crash)' if r.returncode < 0 else ''}: {r.stderr.strip()[:200]}")
                if os.path.exists(out):
                    os.remove(out)
    return name, tried, failures


def same_report(a, b):
    """tests/cluster/same_report.py: the two reports value for value, timings aside."""
    same = os.path.join(os.path.dirname(os.path.abspath(__file__)), "same_report.py")
    return subprocess.run([sys.executable, same, a, b], capture_output=True, text=True).returncode == 0


def check_paths_and_sizes():
    """Parts of one suite given by other paths (relative from its directory, absolute) merge from
    another directory, and a part past the 64 MB of a spec file (padded with whitespace) merges:
    each gives the report of the undamaged parts (timings aside)."""
    failures = []
    suite = f"{T}/table1.json"
    one = run(["validate", suite, "--threads", "1", "--out", f"{T}/paths.one.json"])
    p1 = subprocess.run([VGROOVE, "validate", "table1.json", "--threads", "1", "--shard", "1/2", "--out",
                         "paths.p1.json"], cwd=T, capture_output=True, text=True)
    p2 = run(["validate", suite, "--threads", "1", "--shard", "2/2", "--out", f"{T}/paths.p2.json"])
    if p1.returncode not in (0, 1) or p2.returncode not in (0, 1):
        return [f"paths: the shards failed: {p1.stderr} {p2.stderr}"]
    merged = subprocess.run([VGROOVE, "merge", f"{T}/paths.p1.json", f"{T}/paths.p2.json", "--out",
                             f"{T}/paths.merged.json"], cwd="/", capture_output=True, text=True)
    if merged.returncode != one.returncode:
        failures.append(f"paths: merge of a relative and an absolute part from /: exit {merged.returncode} "
                        f"(one process {one.returncode}): {merged.stderr.strip()}")
    elif not same_report(f"{T}/paths.one.json", f"{T}/paths.merged.json"):
        failures.append("paths: the merged report differs from one process's")
    with open(f"{T}/paths.p1.json", "a") as f:
        f.write(" " * (65 << 20) + "\n")
    big = run(["merge", f"{T}/paths.p1.json", f"{T}/paths.p2.json", "--out", f"{T}/paths.big.json"])
    if big.returncode != one.returncode:
        failures.append(f"sizes: a 65 MB part: exit {big.returncode}: {big.stderr.strip()}")
    elif not same_report(f"{T}/paths.big.json", f"{T}/paths.merged.json"):
        failures.append("sizes: the 65 MB part's merge differs")
    return failures


def main():
    for f, j in SUITES.items():
        with open(f"{T}/{f}", "w") as out:
            json.dump(j, out)
    failed = False
    for f in check_paths_and_sizes():
        print("  FAIL:", f)
        failed = True
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        for name, tried, failures in pool.map(check_kind, COMMANDS):
            print(f"{name}: {tried} damaged parts, {len(failures)} not refused as they must be")
            for f in failures[:40]:
                print("  FAIL:", f)
            failed = failed or bool(failures)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
