#!/usr/bin/env python3
"""Times the Python module's calls on 10^6 rays or directions, one thread, against the same library
calls in C++ (vgroove_bench --benchmark_filter=BM_baseline_, bench/bindings_baseline_bench.cpp),
alternating the two ROUNDS times (the host may be shared: medians of alternated runs). The
functions (trace, brdf, kaleidoscope, sample, pdf) and vgroove.BRDF's methods (eval at the model's
default max_k, sample and pdf with one light direction) are each compared with the C++ loop that
makes their library calls. Both wall time and the process's CPU time are reported (on a shared
host CPU time is the steadier measure of a one-thread call).

    PYTHONPATH=build/python /usr/bin/python3 scripts/bench_python.py [ROUNDS] [BUILD_DIR]
"""

import json
import os
import statistics
import subprocess
import sys
import time

import numpy as np

import vgroove as vg

N = 10**6


def hemisphere(rng):
    z = rng.uniform(size=N)
    phi = 2 * np.pi * rng.uniform(size=N)
    s = np.sqrt(1 - z * z)
    return np.stack([s * np.cos(phi), s * np.sin(phi), z], -1)


def main():
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    build = sys.argv[2] if len(sys.argv) > 2 else "build"
    rng = np.random.default_rng(1)
    wi, wo = hemisphere(rng), hemisphere(rng)
    ti = rng.uniform(-89, 89, N)
    u = rng.uniform(size=(N, 4))
    f = vg.BRDF("vgroove", "ggx", 0.5)
    light = vg.direction(30.0, 180.0)
    # Python call -> (its function, the C++ baseline it is held to).
    calls = {
        "trace": (lambda: vg.trace(30.0, N, 60.0), "trace"),
        "brdf": (lambda: vg.brdf("vgroove", "ggx", 0.5, wi, wo, max_k=16, threads=1), "brdf"),
        "kaleidoscope": (lambda: vg.kaleidoscope(ti, 60.0), "kaleidoscope"),
        "sample": (lambda: vg.sample("ggx", 0.5, u, theta_i_deg=30.0, threads=1), "sample"),
        "pdf": (lambda: vg.pdf("ggx", 0.5, wo, theta_i_deg=30.0, threads=1), "pdf"),
        "BRDF.eval": (lambda: f.eval(wi, wo, threads=1), "brdf_default"),
        "BRDF.sample": (lambda: f.sample(light, u, threads=1), "sample"),
        "BRDF.pdf": (lambda: f.pdf(light, wo, threads=1), "pdf"),
    }
    py = {k: [] for k in calls}
    py_cpu = {k: [] for k in calls}
    cpp, cpp_cpu = {}, {}
    for _ in range(rounds):
        for name, (call, _) in calls.items():
            t, c = time.perf_counter(), time.process_time()
            call()
            py[name].append(1e3 * (time.perf_counter() - t))
            py_cpu[name].append(1e3 * (time.process_time() - c))
        out = subprocess.run([os.path.join(build, "vgroove_bench"), "--benchmark_filter=BM_baseline_",
                              "--benchmark_format=json", "--benchmark_min_time=0.01"],
                             capture_output=True, text=True, check=True).stdout
        for b in json.loads(out)["benchmarks"]:
            name = b["name"][len("BM_baseline_"):].rsplit("_1e6", 1)[0]
            cpp.setdefault(name, []).append(b["real_time"])
            cpp_cpu.setdefault(name, []).append(b["cpu_time"])
    med = statistics.median
    print(f"10^6 rays or directions, one thread, medians of {rounds} alternated runs (ms):")
    print(f"  {'call':14s} {'C++ loop':>13s} {'Python wall':>12s} {'C++ wall':>9s} {'ratio':>6s}   {'Python CPU':>11s} "
          f"{'C++ CPU':>8s} {'ratio':>6s}")
    for name, (_, base) in calls.items():
        pw, cw, pc, cc = med(py[name]), med(cpp[base]), med(py_cpu[name]), med(cpp_cpu[base])
        print(f"  {name:14s} {base:>13s} {pw:12.1f} {cw:9.1f} {pw / cw:6.3f}   {pc:11.1f} {cc:8.1f} {pc / cc:6.3f}")


if __name__ == "__main__":
    main()
