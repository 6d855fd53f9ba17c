"""Shared set-up of the Python tests (run by ctest: tests/python/CMakeLists via tests/CMakeLists.txt).

Environment (set by ctest): VGROOVE_BIN (the command line), VGROOVE_SOURCE_DIR, VGROOVE_PLOT (the
plot script in the build tree), VGROOVE_PYTHON_MODULE (1 when the extension module was built:
then `import vgroove` must work; 0 in sanitizer builds, where the tests that need it are
skipped), PYTHONPATH (build/python).
"""

import json
import os
import subprocess
import sys

import pytest

SOURCE = os.environ.get("VGROOVE_SOURCE_DIR", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
BIN = os.environ.get("VGROOVE_BIN", os.path.join(SOURCE, "build", "vgroove"))
PLOT = os.environ.get("VGROOVE_PLOT", os.path.join(SOURCE, "python", "vgroove", "plot.py"))
HAVE_MODULE = os.environ.get("VGROOVE_PYTHON_MODULE", "1") == "1"

# Fields that differ between two runs of the same inputs (wall times, the thread count used).
TIMING_KEYS = {"wall_s", "sim_wall_s", "model_wall_s", "bounces_per_s", "quadrature_s", "estimate_s", "sim_s",
               "sample_s", "integrate_s", "timing"}


def strip_timing(j):
    if isinstance(j, dict):
        return {k: strip_timing(v) for k, v in j.items() if k not in TIMING_KEYS}
    if isinstance(j, list):
        return [strip_timing(v) for v in j]
    return j


def cli(*args, check=True, **kw):
    """Runs the vgroove command line; returns the CompletedProcess (text)."""
    r = subprocess.run([BIN, *map(str, args)], capture_output=True, text=True, **kw)
    if check and r.returncode not in (0, 1):
        raise AssertionError(f"vgroove {' '.join(map(str, args))}: exit {r.returncode}: {r.stderr}")
    return r


def cli_json(*args):
    return json.loads(cli(*args).stdout)


def cli_error(*args):
    """The one-line message of a command that must fail with exit 2 (without 'vgroove: error: ')."""
    r = cli(*args, check=False)
    assert r.returncode == 2, (r.returncode, r.stdout, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, r.stderr
    assert lines[0].startswith("vgroove: error: "), lines[0]
    return lines[0][len("vgroove: error: "):]


def write_json(path, obj):
    with open(path, "w") as f:
        f.write(json.dumps(obj))
    return str(path)


@pytest.fixture(scope="session")
def vg():
    if not HAVE_MODULE:
        pytest.skip("built without the Python module (VGROOVE_PYTHON off, or a sanitizer build)")
    import vgroove
    return vgroove


# Small suites of each kind, and the reports the command line writes for them (once per session).
TINY_BRDF = {
    "name": "tiny_brdf", "kind": "brdf", "description": "a small Fig. 11 suite for the tests",
    "ndf": ["ggx"], "alpha": [0.5], "theta_i_deg": [0, 40], "dimensions": ["flatland", "3d"],
    "rays": 20000, "grooves": 5000, "seed": 3, "flatland_bins": 30, "theta_bins": 10, "phi_bins": 8, "max_k": 8,
    "thresholds": {"sigmas": 5, "model_tolerance": {"flatland": 1e-5, "3d": 1e-4}},
}
TINY_FURNACE = {
    "name": "tiny_furnace", "kind": "furnace", "description": "a small white furnace for the tests",
    "ndf": ["ggx"], "alpha": [0.3, 1.0], "theta_i_deg": [0, 60], "dimensions": ["flatland", "3d"], "max_k": 64,
    "samples": 2000, "strategy": "vndf", "rays": 2000, "grooves": 1000, "seed": 1,
    "thresholds": {"sigmas": 5, "quadrature_tolerance": {"flatland": 1e-9, "3d": 1e-5}},
}
TINY_SAMPLING = {
    "name": "tiny_sampling", "kind": "sampling", "description": "a small sampling suite for the tests", "seed": 1,
    "max_k": 64,
    "chi_square": {
        "level": 0.01, "samples": {"3d": 5000, "flatland": 5000}, "cos_bins": 4, "phi_bins": 8, "theta_bins": 18,
        "cases": [{"dimension": "3d", "ndf": "ggx", "alpha": 0.5, "theta_i_deg": 30, "strategy": "vndf"},
                  {"dimension": "flatland", "ndf": "ggx", "alpha": 0.5, "theta_i_deg": 30, "strategy": "printed"}],
    },
    "variance": {
        "samples": 2000, "schlick_f0": [1.0, 0.5],
        "cases": [{"dimension": "3d", "ndf": "ggx", "alpha": 0.5, "theta_i_deg": 30},
                  {"dimension": "flatland", "ndf": "beckmann", "alpha": 1.0, "theta_i_deg": 60}],
    },
    "furnace": {
        "max_k": 16, "samples": 2000, "strategy": "vndf", "rays": 1000, "grooves": 1000, "sigmas": 5,
        "quadrature_tolerance": {"flatland": 1e-9, "3d": 1e-5},
        "cases": [{"dimension": "flatland", "ndf": "ggx", "alpha": 0.5, "theta_i_deg": 30}],
    },
}
TINY_NONSYMMETRIC_BRDF = {
    "name": "tiny_nonsymmetric_brdf", "kind": "nonsymmetric_brdf", "description": "a small Eq. 23 suite",
    "ndf": ["ggx"], "alpha": [0.5], "theta_i_deg": [0, 40], "dimensions": ["flatland", "3d"],
    "anisotropic": {"ndf": ["ggx"], "alpha_x": [0.1], "alpha_y": [0.3], "theta_i_deg": [40], "phi_i_deg": [0, 90],
                    "partners": ["independent", "symmetric"]},
    "rays": 5000, "grooves": 2000, "seed": 1, "flatland_bins": 30, "theta_bins": 6, "phi_bins": 8, "max_k": 8,
    "plane_k": 2, "reciprocity_pairs": 5,
    "thresholds": {"sigmas": 5, "model_tolerance": {"flatland": 1e-3, "3d": 3e-3}},
}
TINY_PROFILES = {
    "name": "tiny_profiles", "kind": "profiles", "description": "a small profiles suite for the tests",
    "ndf": ["ggx"], "alpha": [0.5], "theta_deg": [0, 60], "surfaces": ["random", "vgroove"], "realizations": 2,
    "segments": 4096, "samples_per_length": 8, "rays": 5000, "walk_paths": 5000, "normal_bins": 9,
    "lobe_bins": 30, "max_k": 4, "seed": 1, "thresholds": {"p_min": 1e-3, "sigmas": 5, "model_tolerance": 1e-5},
}
TINY_TABLE2 = {
    "name": "tiny_table2", "kind": "table2", "ndf": ["ggx"], "alpha": [0.5, 1.0], "percentiles": [90, 99],
    "rays": 5000, "grooves": 2000, "seed": 1,
    "paper": {"source": "made up for the tests", "max_bounces": [[2, 3], [3, 16]]},
}
TINY_TABLE1 = {
    "name": "tiny_table1", "kind": "table1", "description": "a small Table 1 suite for the tests",
    "groove": {"type": "symmetric", "theta_v_deg": {"from": 10, "to": 170, "step": 40}},
    "theta_i_deg": {"from": -80, "to": 80, "step": 20}, "rays": 300, "sampling": "random", "seed": 7,
    "thresholds": {"max_l1": 0.5, "mean_l1": 0.5, "max_theta_o_error_rad": 1e-9},
    "paper": {"source": "made up", "max_l1": 0.003, "mean_l1": 0.0005},
}


TINY_NONSYMMETRIC = {
    "name": "tiny_nonsymmetric", "kind": "table1",
    "groove": {"type": "nonsymmetric", "theta_l_deg": {"from": -90, "to": -10, "step": 40},
               "theta_r_deg": {"from": 10, "to": 90, "step": 40}},
    "theta_i_deg": {"from": -75, "to": 75, "step": 25}, "rays": 200, "sampling": "stratified", "seed": 2018,
    "thresholds": {"max_l1": 0.004, "mean_l1": 0.0005, "max_theta_o_error_rad": 1e-9},
}
TINY_SET = {"name": "tiny_set", "description": "both columns of a small Table 1",
            "suites": ["tiny_table1.json", "tiny_nonsymmetric.json"]}


# Every suite kind `vgroove validate` runs, in the order the reports are made.
SUITE_KINDS = ("brdf", "furnace", "table2", "table1", "table1_set", "sampling", "nonsymmetric_brdf", "profiles")


def make_suites(d):
    """Writes the small suites into directory d; returns their paths by kind."""
    write_json(os.path.join(d, "tiny_nonsymmetric.json"), TINY_NONSYMMETRIC)
    return {
        "brdf": write_json(os.path.join(d, "tiny_brdf.json"), TINY_BRDF),
        "furnace": write_json(os.path.join(d, "tiny_furnace.json"), TINY_FURNACE),
        "table2": write_json(os.path.join(d, "tiny_table2.json"), TINY_TABLE2),
        "table1": write_json(os.path.join(d, "tiny_table1.json"), TINY_TABLE1),
        "table1_set": write_json(os.path.join(d, "tiny_set.json"), TINY_SET),
        "sampling": write_json(os.path.join(d, "tiny_sampling.json"), TINY_SAMPLING),
        "nonsymmetric_brdf": write_json(os.path.join(d, "tiny_nonsymmetric_brdf.json"), TINY_NONSYMMETRIC_BRDF),
        "profiles": write_json(os.path.join(d, "tiny_profiles.json"), TINY_PROFILES),
    }


def make_reports(d, suites):
    """The command line's reports for the small suites (and a `bench accuracy` report), written
    with --out into directory d; returns their paths by kind."""
    out = {}
    for kind in SUITE_KINDS:
        out[kind] = os.path.join(d, f"{kind}.json")
        cli("validate", suites[kind], "--out", out[kind], "--threads", 2, "--force")
    # A model table (every bin 0.9 / bins: a flat lobe, which fails) against the brdf suite.
    layout = os.path.join(d, "layout.json")
    cli("bins", suites["brdf"], "--out", layout, "--force")
    with open(layout) as f:
        cases = [{k: c[k] for k in ("case", "ndf", "alpha", "theta_i_deg", "dimension")} |
                 {"flux": [0.9 / c["bins"]] * c["bins"]} for c in json.load(f)["cases"]]
    table = write_json(os.path.join(d, "model_table_input.json"),
                       {"kind": "model_table", "suite": TINY_BRDF["name"], "model": "flat", "cases": cases})
    out["model_table"] = os.path.join(d, "model_table.json")
    cli("validate", suites["brdf"], "--model-table", table, "--out", out["model_table"], "--threads", 2, "--force")
    out["accuracy"] = os.path.join(d, "accuracy.json")
    cli("bench", "accuracy", suites["table1"], "--rays", "100,300", "--out", out["accuracy"], "--threads", 2,
        "--force")
    return out


# ctest makes the suites and reports once (python.reports, tests/python/make_reports.py) into
# VGROOVE_TEST_REPORTS; a pytest run of its own makes them in a temporary directory.
SHARED = os.environ.get("VGROOVE_TEST_REPORTS")


@pytest.fixture(scope="session")
def suites(tmp_path_factory):
    if SHARED and os.path.exists(os.path.join(SHARED, "done")):
        return make_suites(SHARED)  # the same content: rewriting it is harmless
    return make_suites(str(tmp_path_factory.mktemp("suites")))


@pytest.fixture(scope="session")
def reports(suites, tmp_path_factory):
    if SHARED and os.path.exists(os.path.join(SHARED, "done")):
        return {k: os.path.join(SHARED, f"{k}.json") for k in list(suites) + ["accuracy", "model_table"]}
    return make_reports(str(tmp_path_factory.mktemp("reports")), suites)


def interrupted_after(code, delay=1.0):
    """Runs `code` (Python, printing nothing) in a child with Python's default SIGINT handler, sends
    SIGINT `delay` seconds after it starts the call and returns (what it printed: "interrupted" when
    the call raised KeyboardInterrupt, "finished" when it returned first; the seconds from the
    signal to the child's exit)."""
    import signal
    import time
    prog = ("import signal, numpy as np, vgroove\n"
            "signal.signal(signal.SIGINT, signal.default_int_handler)\n"
            "print('started', flush=True)\n"
            "try:\n" + "".join("    " + line + "\n" for line in code.splitlines()) +
            "    print('finished', flush=True)\n"
            "except KeyboardInterrupt:\n"
            "    print('interrupted', flush=True)\n")
    p = subprocess.Popen([sys.executable, "-c", prog], stdout=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "started"
    time.sleep(delay)
    t0 = time.monotonic()
    p.send_signal(signal.SIGINT)
    try:
        out, _ = p.communicate(timeout=120)
    except subprocess.TimeoutExpired:  # still running: the signal was ignored
        p.kill()
        p.communicate()
        return "still running 120 s after SIGINT", time.monotonic() - t0
    return out.strip(), time.monotonic() - t0
