"""progress= on every long call: counts that only grow and end at done == total, called from the
calling thread while the work runs without the GIL; an exception in the callback stops the work
as Ctrl-C does; the tqdm adapter draws the counts; Ctrl-C still stops the object's calls."""

import io
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

from conftest import interrupted_after


class Recorder:
    def __init__(self):
        self.calls = []
        self.threads = set()

    def __call__(self, done, total):
        assert isinstance(done, int) and isinstance(total, int)
        self.calls.append((done, total))
        self.threads.add(threading.get_ident())

    def check(self):
        assert self.calls, "progress was never called"
        assert self.calls[-1][0] == self.calls[-1][1] > 0, self.calls[-3:]
        done = [d for d, _ in self.calls]
        assert done == sorted(done), self.calls
        assert self.threads == {threading.get_ident()}


def long_calls(vg, suites):
    f = vg.BRDF("vgroove", "ggx", 0.5)
    n = 300000
    wi = vg.direction(30.0, 180.0)
    wo = vg.direction(np.linspace(0, 89, n), np.linspace(-180, 180, n))
    u = vg.uniforms(n)
    surf = vg.microsurface("ggx", 0.5, 5000, 1, dim="flatland")
    return {
        "BRDF.eval": lambda p: f.eval(wi, wo, threads=2, progress=p),
        "BRDF.sample": lambda p: f.sample(wi, u, threads=2, progress=p),
        "BRDF.pdf": lambda p: f.pdf(wi, wo[:100000], threads=2, progress=p),
        "BRDF.lobe": lambda p: f.lobe(30, theta_bins=10, phi_bins=8, progress=p),
        "BRDF.albedo": lambda p: f.albedo(vg.direction(np.array([0.0, 20.0, 40.0]), 180), progress=p),
        "BRDF.trace": lambda p: f.trace(30, 200000, grooves=5000, threads=2, progress=p),
        "brdf": lambda p: vg.brdf("vgroove", "ggx", 0.5, wi, wo, progress=p),
        "sample": lambda p: vg.sample("ggx", 0.5, u, theta_i_deg=30, progress=p),
        "pdf": lambda p: vg.pdf("ggx", 0.5, wo[:100000], theta_i_deg=30, progress=p),
        "lobe": lambda p: vg.lobe("vgroove", "ggx", 0.5, 30, theta_bins=10, phi_bins=8, progress=p),
        "trace_microsurface": lambda p: vg.trace_microsurface(surf, 30, 200000, progress=p),
        "validate": lambda p: vg.validate(suites["table1"], progress=p),
        "check_brdf": lambda p: vg.check_brdf("vgroove", "ggx", 0.5, [0], rays=2000, grooves=500, theta_bins=4,
                                              phi_bins=4, progress=p),
    }


@pytest.mark.parametrize("name", ["BRDF.eval", "BRDF.sample", "BRDF.pdf", "BRDF.lobe", "BRDF.albedo", "BRDF.trace",
                                  "brdf", "sample", "pdf", "lobe", "trace_microsurface", "validate", "check_brdf"])
def test_every_long_call_reports_progress(vg, suites, name):
    call = long_calls(vg, suites)[name]
    r = Recorder()
    with_progress = call(r)
    r.check()
    # The result does not depend on the callback.
    without = call(None)
    if isinstance(without, dict):
        from conftest import strip_timing
        if "cases" in without:
            without["threads"] = with_progress["threads"]
            assert strip_timing(without) == strip_timing(with_progress)
        else:
            assert all(np.array_equal(without[k], with_progress[k]) for k in without)
    elif isinstance(without, np.ndarray):
        assert np.array_equal(without, with_progress)
    else:
        assert all(np.array_equal(a, b) for a, b in zip(without.as_dict().values(), with_progress.as_dict().values()))


def test_a_long_call_reports_along_the_way(vg):
    # A flatland eval of the nonsymmetric model (~0.8 ms a direction, read before each; 3000 of
    # them): several reports before the end, each from this thread, while other Python threads
    # keep running (the GIL is released).
    f = vg.BRDF("vgroove-nonsymmetric", "ggx", 0.5, dim="flatland")
    wi = vg.direction(np.linspace(-60, 60, 3000), 180) * [1, 0, 1]
    ticks = []
    stop = threading.Event()

    def ticker():
        while not stop.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.01)

    t = threading.Thread(target=ticker)
    t.start()
    r = Recorder()
    try:
        f.eval(wi, wi[::-1], threads=1, progress=r)
    finally:
        stop.set()
        t.join()
    r.check()
    assert len({d for d, _ in r.calls}) >= 3, r.calls
    assert len(ticks) > 50, len(ticks)


def test_an_exception_in_the_callback_stops_the_work_and_is_raised(vg):
    f = vg.BRDF("vgroove", "ggx", 0.5, dim="flatland")
    wi = vg.direction(np.full(200, 30.0), 180) * [1, 0, 1]
    seen = []

    def stop(done, total):
        seen.append(done)
        raise RuntimeError("enough")

    t0 = time.monotonic()
    with pytest.raises(RuntimeError, match="enough"):
        f.eval(wi, wi, threads=1, progress=stop)
    # ~0.4-2 s a direction: 200 of them would take minutes; the work stops within one of them.
    assert time.monotonic() - t0 < 10 and len(seen) == 1


def test_tqdm_adapter(vg):
    pytest.importorskip("tqdm")  # Debian's python3-tqdm (scripts/install-deps.sh)
    out = io.StringIO()
    bar = vg.tqdm_progress(file=out, desc="eval", mininterval=0)
    vg.BRDF().eval(vg.direction(30, 180), vg.direction(np.linspace(0, 89, 200000), 0), progress=bar)
    assert bar.bar.n == bar.bar.total == 200000
    assert "eval" in out.getvalue() and "200000/200000" in out.getvalue()


def test_tqdm_adapter_without_tqdm_says_what_is_missing(vg):
    code = ("import sys; sys.modules['tqdm'] = None\n"
            "import vgroove\n"
            "try:\n    vgroove.tqdm_progress()\nexcept ImportError as e:\n    print(e)\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == ("vgroove.tqdm_progress needs tqdm, which is not installed "
                                "(Debian: apt-get install python3-tqdm)")


@pytest.mark.parametrize("call", [
    # ~0.8 ms a direction of the nonsymmetric model (read before each): 20000 of them on one thread.
    "vgroove.BRDF('vgroove-nonsymmetric', 'ggx', 0.5, dim='flatland').eval("
    "vgroove.direction([30.0] * 20000, 180) * [1, 0, 1], [0.0, 0.0, 1.0], threads=1)",
    "vgroove.BRDF('vgroove', 'ggx', 0.5).lobe(30, theta_bins=200, phi_bins=200)",
    "vgroove.BRDF('vgroove', 'ggx', 0.5).trace(30, 10**9, grooves=1000)",
])
def test_ctrl_c_stops_the_objects_calls_within_a_second(vg, call):
    out, seconds = interrupted_after(call, delay=0.5)
    assert out == "interrupted"
    assert seconds < 1.5, seconds
