"""sample(), pdf() and uniforms() from Python: the same samples as `vgroove sample` (its histogram
and its weights' moments to the last bit, from the same stream of uniform numbers), the pdf the
same density the command line integrates over its cells, and the physics: with the V-cavity's
visible normals the pdf is rho cos(theta_o), so every weight is 1."""

import json
import math

import numpy as np
import pytest

from conftest import cli, cli_error

STREAM = 0x5A3D  # `vgroove sample`'s stream: (seed, (0x5a3d, 0)) in 3D, (seed, (0x5a3d, 1)) in flatland


def cli_sample(tmp_path, dim, ndf, alpha, theta_i, strategy, n, seed, max_k=None, bins=None):
    # max_k None: the command's default, which the Python calls beside it leave at theirs.
    out = tmp_path / f"sample-{dim}-{strategy}-{max_k}.json"
    args = ["sample", "--dim", dim, "--ndf", ndf, "--alpha", alpha, "--theta-i-deg", theta_i, "--strategy", strategy,
            "--n", n, "--seed", seed, "--out", out]
    if max_k is not None:
        args += ["--max-k", max_k]
    for flag, v in (bins or {}).items():
        args += [flag, v]
    cli(*args)
    with open(out) as f:
        return json.load(f)["result"]


def moments(weights):
    # The command line's sums, in its order (validation/sampling_check.cpp, Moments).
    s = s2 = 0.0
    for w in weights.tolist():
        s += w
        s2 += w * w
    n = float(len(weights))
    mean = s / n
    return mean, max(0.0, s2 / n - mean * mean) * n / (n - 1.0)


@pytest.mark.parametrize("dim,ndf,alpha,theta_i,strategy", [
    ("3d", "ggx", 0.5, 30, "printed"),
    ("3d", "beckmann", 0.3, 75, "vndf"),
    ("3d", "ggx", 1.0, 60, "bounded-vndf"),
    ("flatland", "ggx", 0.5, 30, "smith-vndf"),
    ("flatland", "phong", 1.5, 85, "printed"),
])
def test_sample_equals_the_command_line_to_the_last_bit(vg, tmp_path, dim, ndf, alpha, theta_i, strategy):
    n, seed = 20000, 5
    theirs = cli_sample(tmp_path, dim, ndf, alpha, theta_i, strategy, n, seed)
    u = vg.uniforms(n, seed, (STREAM, 0 if dim == "3d" else 1))
    r = vg.sample(ndf, alpha, u, theta_i_deg=theta_i, strategy=strategy, dim=dim, threads=2)
    assert tally(r, dim, theirs["table"]) == tally_of(theirs)
    # Power: the next stream's samples, or the four numbers of each sample in another order, are
    # told apart.
    for other in (vg.uniforms(n, seed + 1, (STREAM, 0 if dim == "3d" else 1)), u[:, [1, 2, 3, 0]]):
        r2 = vg.sample(ndf, alpha, other, theta_i_deg=theta_i, strategy=strategy, dim=dim)
        assert tally(r2, dim, theirs["table"]) != tally_of(theirs)
    # Every returned direction is a unit vector above the horizon, pdf and weight finite.
    ok = r["k"] > 0
    assert np.all(np.isfinite(r["wo"])) and np.all(np.isfinite(r["pdf"])) and np.all(np.isfinite(r["weight"]))
    assert np.all(r["pdf"][ok] > 0) and np.all(r["wo"][ok][:, 2] > 0)
    assert np.all(r["pdf"][~ok] == 0) and np.all(r["weight"][~ok] == 0)
    assert np.allclose(np.linalg.norm(r["wo"], axis=-1), 1.0, atol=1e-12, rtol=0)


def tally_of(result):
    """What `vgroove sample --out` reports of its samples: histogram, no-direction count, moments."""
    t = result["table"]
    return t["observed"], t["observed_no_direction"], result["weight_mean"], result["weight_variance"]


def tally(r, dim, t):
    """The same of sample()'s output, binned and summed as validation/sampling_check.cpp does."""
    rows, cols = len(t["row_edges"]) - 1, len(t["col_edges"]) - 1
    observed = np.zeros((rows, cols))
    none = 0
    for o, k in zip(r["wo"].tolist(), r["k"].tolist()):
        if k == 0:
            none += 1
            continue
        if dim == "3d":
            row = min(max(int(o[2] * rows), 0), rows - 1)
            c = int((math.atan2(o[1], o[0]) + math.pi) / (2.0 * math.pi) * cols)
        else:
            row = 0
            c = int((math.atan2(-o[0], o[2]) + 0.5 * math.pi) / math.pi * cols)
        observed[row, min(max(c, 0), cols - 1)] += 1
    return (observed.tolist(), float(none), *moments(r["weight"]))


def gauss_legendre_cells(f, edges, cuts, nodes=48):
    """The integral of f over each cell [edges[c], edges[c + 1]], split at the cuts inside it."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    out = []
    for a, b in zip(edges[:-1], edges[1:]):
        pieces = sorted({a, b} | {c for c in cuts if a < c < b})
        total = 0.0
        for p, q in zip(pieces[:-1], pieces[1:]):
            t = 0.5 * (q - p) * x + 0.5 * (q + p)
            total += 0.5 * (q - p) * float(np.dot(w, f(t)))
        out.append(total)
    return np.array(out)


@pytest.mark.parametrize("strategy,ndf,alpha,theta_i", [("printed", "ggx", 0.5, 30), ("vndf", "phong", 1.5, 85),
                                                          ("smith-vndf", "ggx", 0.2, 60)])
def test_flatland_pdf_integrates_to_the_command_lines_expected_counts(vg, tmp_path, strategy, ndf, alpha, theta_i):
    # The command line's expected counts are N x the pdf (analytic/sampling_flatland.h) integrated
    # adaptively over its cells; Gauss-Legendre over the same cells, split at +-theta_i like the
    # command line's, of pdf() from Python must give the same to the quadratures' accuracy.
    # max_k 256 on both sides: the fixed Gauss-Legendre rule here resolves the pdf's structure near
    # the retro direction (paths of up to max_k reflections) to 1e-5 only that far.
    n, max_k = 100000, 256
    theirs = cli_sample(tmp_path, "flatland", ndf, alpha, theta_i, strategy, n, 1, max_k=max_k)
    edges = theirs["table"]["col_edges"]
    ti = math.radians(theta_i)

    def density(t):
        wo = np.stack([-np.sin(t), np.zeros_like(t), np.cos(t)], axis=-1)
        return vg.pdf(ndf, alpha, wo, theta_i_deg=theta_i, strategy=strategy, dim="flatland", max_k=max_k)

    ours = n * gauss_legendre_cells(density, edges, [-ti, ti])
    expected = np.array(theirs["table"]["expected"][0])
    assert np.max(np.abs(ours - expected)) < 1e-3 * max(1.0, expected.max()), np.max(np.abs(ours - expected))
    # Power: another strategy's density is told apart at this tolerance.
    other = "vndf" if strategy != "vndf" else "printed"
    wrong = n * gauss_legendre_cells(
        lambda t: vg.pdf(ndf, alpha, np.stack([-np.sin(t), 0 * t, np.cos(t)], axis=-1), theta_i_deg=theta_i,
                         strategy=other, dim="flatland", max_k=max_k), edges, [-ti, ti])
    assert np.max(np.abs(wrong - expected)) > 1e-2 * max(1.0, expected.max())
    # Normalization: the cells and the failure probability make 1.
    assert abs(ours.sum() / n + theirs["failure_probability"] - 1.0) < 1e-5


def test_vndf_pdf_is_the_brdf_times_cosine(vg):
    # Lee et al. 2018, Sec. 6 with the V-cavity's visible normals: the density of the sampled
    # directions is rho(i, o) cos(theta_o) (F = 1, k <= max_k), so every weight is 1.
    rng = np.random.default_rng(3)
    for dim, ndf, alpha in (("3d", "ggx", 0.5), ("3d", "beckmann", 1.0), ("flatland", "phong", 0.3)):
        n = 2000
        wi = vg.direction(rng.uniform(0, 85, n), rng.uniform(-180, 180, n) if dim == "3d" else 180.0)
        wo = vg.direction(rng.uniform(0, 89, n), rng.uniform(-180, 180, n) if dim == "3d" else
                          np.where(rng.uniform(size=n) < 0.5, 0.0, 180.0))
        p = vg.pdf(ndf, alpha, wo, wi=wi, strategy="vndf", max_k=64, dim=dim)
        f = vg.brdf("vgroove", ndf, alpha, wi, wo, max_k=64, dim=dim)
        assert np.all(np.isfinite(p)) and np.all(p >= 0)
        np.testing.assert_allclose(p, f * wo[:, 2], rtol=1e-9, atol=1e-300)
        # Power: the paper's printed facet density does not sample the BRDF exactly.
        printed = vg.pdf(ndf, alpha, wo, wi=wi, strategy="printed", max_k=64, dim=dim)
        assert not np.allclose(printed, f * wo[:, 2], rtol=1e-3)
        u = vg.uniforms(n, 11, (1, 2))
        s = vg.sample(ndf, alpha, u, wi=wi, strategy="vndf", max_k=64, dim=dim)
        ok = s["k"] > 0
        np.testing.assert_allclose(s["weight"][ok], 1.0, rtol=1e-9)
        # The pdf a sample returns is pdf() at its direction.
        np.testing.assert_allclose(vg.pdf(ndf, alpha, s["wo"][ok], wi=wi[ok], strategy="vndf", max_k=64, dim=dim),
                                   s["pdf"][ok], rtol=1e-9)


def test_vectorized_equals_row_by_row_and_any_thread_count(vg):
    u = vg.uniforms(300, 2, (7, 7))
    ti = np.linspace(0, 89.9, 300)
    batch = vg.sample("ggx", 0.7, u, theta_i_deg=ti, strategy="printed", threads=1)
    again = vg.sample("ggx", 0.7, u, theta_i_deg=ti, strategy="printed", threads=3)
    for key in batch:
        assert np.array_equal(batch[key], again[key])
    for j in range(0, 300, 37):
        one = vg.sample("ggx", 0.7, u[j], theta_i_deg=ti[j], strategy="printed")
        for key in batch:
            assert np.array_equal(one[key], batch[key][j]), key
    p = vg.pdf("ggx", 0.7, batch["wo"], theta_i_deg=ti, strategy="printed", threads=2)
    assert np.array_equal(p, vg.pdf("ggx", 0.7, batch["wo"], theta_i_deg=ti, strategy="printed", threads=1))
    assert p[7] == vg.pdf("ggx", 0.7, batch["wo"][7], theta_i_deg=ti[7], strategy="printed")
    # Runs of equal angles (a light direction computed once per run) against row by row.
    runs = np.array([20.0] * 5 + [60.0] * 5 + [20.0] * 5 + [0.0])
    batch = vg.sample("ggx", 0.7, u[:16], theta_i_deg=runs, threads=1)
    for j in range(16):
        one = vg.sample("ggx", 0.7, u[j], theta_i_deg=runs[j])
        for key in batch:
            assert np.array_equal(one[key], batch[key][j]), (key, j)
    assert np.array_equal(vg.pdf("ggx", 0.7, batch["wo"], theta_i_deg=runs),
                          [vg.pdf("ggx", 0.7, batch["wo"][j], theta_i_deg=runs[j]) for j in range(16)])
    # Broadcasting: one light, many u (shape S + (4,)).
    grid = vg.sample("beckmann", 0.4, u.reshape(20, 15, 4), wi=vg.direction(40, 180))
    assert grid["wo"].shape == (20, 15, 3) and grid["k"].shape == (20, 15)
    # uniforms: the same stream in one call or two calls of the same length.
    assert np.array_equal(vg.uniforms(10, 4, (1, 1)), vg.uniforms(10, 4, (1, 1)))
    assert vg.uniforms(5, 4, (1, 1), dims=2).shape == (5, 2)


@pytest.mark.parametrize("theta_i,alpha,ndf,strategy", [(89.9, 0.01, "ggx", "vndf"), (89.9, 2.0, "phong", "printed"),
                                                        (0.0, 0.01, "beckmann", "vndf"), (0.0, 2.0, "ggx", "bounded-vndf"),
                                                        (60.0, 0.01, "ggx", "smith-vndf")])
def test_hard_cases_stay_finite(vg, theta_i, alpha, ndf, strategy):
    u = vg.uniforms(4000, 9, (3, 4))
    u[:4] = [[0, 0, 0, 0], [0.9999999999, 0.9999999999, 0.9999999999, 0.9999999999], [0.5] * 4, [0, 0.5, 0, 0.5]]
    for dim in ("3d", "flatland"):
        if strategy == "bounded-vndf" and dim == "flatland":
            continue
        s = vg.sample(ndf, alpha, u, theta_i_deg=theta_i, strategy=strategy, dim=dim, max_k=1000)
        for key in s:
            assert np.all(np.isfinite(s[key])), (dim, key)
        ok = s["k"] > 0
        p = vg.pdf(ndf, alpha, s["wo"][ok], theta_i_deg=theta_i, strategy=strategy, dim=dim, max_k=1000)
        assert not np.any(np.isnan(p)) and np.all(p >= 0)


@pytest.mark.parametrize("kwargs,flags", [
    ({"strategy": "bogus"}, ["--strategy", "bogus"]),
    ({"strategy": "smith-vndf", "ndf": "phong"}, ["--strategy", "smith-vndf", "--ndf", "phong"]),
    ({"strategy": "bounded-vndf", "dim": "flatland"}, ["--strategy", "bounded-vndf", "--dim", "flatland"]),
    ({"max_k": 0}, ["--max-k", 0]),
    ({"alpha": 3.0}, ["--alpha", 3]),
    ({"ndf": "gauss"}, ["--ndf", "gauss"]),
    ({"dim": "2d"}, ["--dim", "2d"]),
])
def test_bad_input_gives_the_command_lines_message(vg, kwargs, flags):
    expected = cli_error("sample", *flags)
    for flag in ("--max-k", "--strategy", "--ndf", "--dim", "--alpha"):
        expected = expected.replace(flag, flag[2:].replace("-", "_"))
    args = {"ndf": "ggx", "alpha": 0.5, "strategy": "vndf", "dim": "3d", "max_k": 256}
    args.update(kwargs)
    ndf, alpha = args.pop("ndf"), args.pop("alpha")
    with pytest.raises(ValueError) as e:
        vg.sample(ndf, alpha, [[0.1, 0.2, 0.3, 0.4]], theta_i_deg=30, **args)
    assert str(e.value) == expected
    with pytest.raises(ValueError) as e:
        vg.pdf(ndf, alpha, [[0.0, 0.0, 1.0]], theta_i_deg=30, **args)
    assert str(e.value) == expected


def test_bad_arrays_are_value_errors(vg):
    u = np.full((50000, 4), 0.5)
    u[43210, 3] = -0.0 - 1e-300
    with pytest.raises(ValueError, match=r"u\[43210\]\[3\] = -1e-300 is out of range \[0, 1\)"):
        vg.sample("ggx", 0.5, u, theta_i_deg=30)
    with pytest.raises(ValueError, match=r"u\[0\]\[2\] = 1 is out of range \[0, 1\)"):
        vg.sample("ggx", 0.5, [[0.1, 0.2, 1.0, 0.3]], theta_i_deg=30)
    with pytest.raises(ValueError, match=r"u\[1\]\[0\] = nan"):
        vg.sample("ggx", 0.5, [[0.1, 0.2, 0.3, 0.3], [math.nan, 0, 0, 0]], theta_i_deg=30)
    with pytest.raises(ValueError, match="either wi"):
        vg.sample("ggx", 0.5, [[0.1, 0.2, 0.3, 0.3]])
    with pytest.raises(ValueError, match="either wi"):
        vg.pdf("ggx", 0.5, [0, 0, 1], wi=[0, 0, 1], theta_i_deg=3)
    with pytest.raises(ValueError, match=r"wi\[0\] = \(0, 0, 2\) is not a unit vector"):
        vg.sample("ggx", 0.5, [[0.1, 0.2, 0.3, 0.3]], wi=[0, 0, 2])
    with pytest.raises(ValueError, match=r"theta_i_deg\[0\] = 90 is out of range"):
        vg.sample("ggx", 0.5, [[0.1, 0.2, 0.3, 0.3]], theta_i_deg=90)
    with pytest.raises(ValueError, match=r"wo\[0\] = \(1, 0, 1\) is not a unit vector"):
        vg.pdf("ggx", 0.5, [1, 0, 1], theta_i_deg=3)
    with pytest.raises(ValueError, match="not in the plane y = 0"):
        vg.pdf("ggx", 0.5, [0, 1, 0], theta_i_deg=3, dim="flatland")
    with pytest.raises(ValueError, match=r"u must be an array of uniform numbers"):
        vg.sample("ggx", 0.5, [0.1, 0.2, 0.3], theta_i_deg=30)
    with pytest.raises(ValueError, match=r"threads = -1 is out of range"):
        vg.sample("ggx", 0.5, [0.1, 0.2, 0.3, 0.4], theta_i_deg=30, threads=-1)
    with pytest.raises(ValueError, match=r"n = -1 is out of range"):
        vg.uniforms(-1)
    with pytest.raises(ValueError, match=r"seed = 1.5 must be an integer"):
        vg.uniforms(3, 1.5)


def test_ctrl_c_stops_a_long_call(vg):
    # pdf() of 3 x 10^6 directions on one thread (tens of seconds) stops within seconds of SIGINT.
    import signal
    import subprocess
    import sys
    import time
    code = ("import signal, numpy as np, vgroove\n"
            "signal.signal(signal.SIGINT, signal.default_int_handler)\n"
            "wo = np.tile(vgroove.direction(40, 10), (3 * 10**6, 1))\n"
            "print('started', flush=True)\n"
            "try:\n"
            "    vgroove.pdf('ggx', 0.5, wo, theta_i_deg=30, threads=1)\n"
            "    print('finished', flush=True)\n"
            "except KeyboardInterrupt:\n"
            "    print('interrupted', flush=True)\n")
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "started"
    time.sleep(0.5)
    t0 = time.monotonic()
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=60)
    assert out.strip() == "interrupted"
    assert time.monotonic() - t0 < 10  # a chunk of 4096 directions in flight finishes


def test_nonsymmetric_sample_and_pdf_agree(vg):
    # model="vgroove-nonsymmetric" (analytic/sampling_nonsymmetric.h): the pdf of each sample is
    # pdf() at its direction; the symmetric model's pdf is another density. (`vgroove sample --model
    # vgroove-nonsymmetric` integrates this pdf over its cells, minutes at any sample count: not here.)
    for dim in ("3d", "flatland"):
        u = vg.uniforms(40, 3, (STREAM, 0 if dim == "3d" else 1), dims=5)
        r = vg.sample("ggx", 0.5, u, theta_i_deg=30, dim=dim, model="vgroove-nonsymmetric", tolerance=1e-6)
        ok = r["k"] > 0
        assert ok.sum() > 30 and np.all(np.isfinite(r["weight"])) and np.all(r["pdf"][ok] > 0)
        p = vg.pdf("ggx", 0.5, r["wo"][ok], theta_i_deg=30, dim=dim, model="vgroove-nonsymmetric", tolerance=1e-6)
        np.testing.assert_allclose(p, r["pdf"][ok], rtol=1e-9)  # flatland: theta_o read back from wo
        sym = vg.pdf("ggx", 0.5, r["wo"][ok], theta_i_deg=30, dim=dim)
        assert not np.allclose(sym, p, rtol=1e-3)


@pytest.mark.parametrize("kwargs,flags", [
    ({"model": "cook_torrance"}, ["--model", "cook_torrance"]),
    ({"model": "vgroove-nonsymmetric", "ndf": "phong", "alpha": 1.5},
     ["--model", "vgroove-nonsymmetric", "--ndf", "phong", "--alpha", 1.5]),
])
def test_nonsymmetric_bad_input_gives_the_command_lines_message(vg, kwargs, flags):
    expected = cli_error("sample", *flags)
    for flag in ("--model", "--ndf", "--alpha"):
        expected = expected.replace(flag, flag[2:])
    args = {"ndf": "ggx", "alpha": 0.5}
    args.update(kwargs)
    ndf, alpha = args.pop("ndf"), args.pop("alpha")
    m = 5 if args.get("model") == "vgroove-nonsymmetric" else 4
    with pytest.raises(ValueError) as e:
        vg.sample(ndf, alpha, [[0.1] * m], theta_i_deg=30, **args)
    assert str(e.value) == expected
    with pytest.raises(ValueError) as e:
        vg.pdf(ndf, alpha, [[0.0, 0.0, 1.0]], theta_i_deg=30, **args)
    assert str(e.value) == expected
    with pytest.raises(ValueError, match=r"tolerance = 0 is out of range"):
        vg.pdf("ggx", 0.5, [0, 0, 1], theta_i_deg=30, model="vgroove-nonsymmetric", tolerance=0)
    with pytest.raises(ValueError, match=r"shape \(\.\.\., 5\)"):
        vg.sample("ggx", 0.5, [0.1] * 4, theta_i_deg=30, model="vgroove-nonsymmetric")


@pytest.mark.parametrize("theta_i", [-1.0, 89.95])
def test_sample_and_pdf_take_the_command_lines_theta_i_range(vg, theta_i):
    expected = cli_error("sample", "--theta-i-deg", theta_i).replace("--theta-i-deg", "theta_i_deg[0]")
    assert expected.endswith("is out of range [0, 89.9]")
    with pytest.raises(ValueError) as e:
        vg.sample("ggx", 0.5, [[0.1] * 4], theta_i_deg=theta_i)
    assert str(e.value) == expected
    with pytest.raises(ValueError) as e:
        vg.pdf("ggx", 0.5, [0.0, 0.0, 1.0], theta_i_deg=[30.0, theta_i])
    assert str(e.value) == expected.replace("[0]", "[1]")
    with pytest.raises(ValueError, match=r"^wi\[0\] = .* is 89.95 deg from the normal, out of range \[0, 89.9\]$"):
        vg.pdf("ggx", 0.5, [0.0, 0.0, 1.0], wi=vg.direction(89.95, 180))
    # The edge itself, as a number and as a direction (its angle rounded to 1e-9 deg, as reports print it).
    assert vg.sample("ggx", 0.5, [[0.1] * 4], theta_i_deg=np.float64(89.9))["k"].shape == (1,)
    assert vg.pdf("ggx", 0.5, [0.0, 0.0, 1.0], wi=vg.direction([0.0, 89.9], 180)).shape == (2,)
    # Flatland angles are signed: the mirror image of the range.
    assert np.isfinite(vg.pdf("ggx", 0.5, [0.0, 0.0, 1.0], theta_i_deg=-89.9, dim="flatland"))
    with pytest.raises(ValueError, match=r"^theta_i_deg\[0\] = -89.95 is out of range \[-89.9, 89.9\]$"):
        vg.pdf("ggx", 0.5, [0.0, 0.0, 1.0], theta_i_deg=-89.95, dim="flatland")
    with pytest.raises(ValueError, match=r"^wi\[0\] = .* is -89.95 deg from the normal, out of range \[-89.9, 89.9\]$"):
        vg.sample("ggx", 0.5, [[0.1] * 4], wi=[np.sin(np.radians(89.95)), 0, np.cos(np.radians(89.95))], dim="flatland")


def test_the_samples_lost_beyond_max_k_and_the_default_are_the_command_lines(vg, tmp_path):
    # The default max_k is the command line's (16384; 256 for the nonsymmetric model), and a sample
    # lost because its path has more than max_k reflections says so: the same samples as `vgroove
    # sample` reports, at the share it expects (binomial, within 4.5 sigma).
    assert vg.SAMPLER_MAX_K == 16384 and vg.NONSYMMETRIC_SAMPLER_MAX_K == 256
    n, seed = 20000, 3
    default = cli_sample(tmp_path, "3d", "ggx", 1.0, 30, "printed", n, seed)
    assert default["max_k"] == vg.SAMPLER_MAX_K
    theirs = cli_sample(tmp_path, "3d", "ggx", 1.0, 30, "printed", n, seed, max_k=4)
    u = vg.uniforms(n, seed, (STREAM, 0))
    r = vg.sample("ggx", 1.0, u, theta_i_deg=30, strategy="printed", max_k=4)
    lost = r["beyond_max_k"]
    assert lost.dtype == bool and lost.shape == (n,)
    assert int(lost.sum()) == theirs["observed_beyond_max_k"]
    assert np.all(r["k"][lost] == 0) and np.all(r["weight"][lost] == 0)
    assert int(lost.sum()) < int((r["k"] == 0).sum())  # the printed strategy also fails on shadowed facets
    p = theirs["beyond_max_k_probability"]
    assert abs(lost.sum() - n * p) <= 4.5 * math.sqrt(n * p * (1 - p))
    r0 = vg.sample("ggx", 1.0, u, theta_i_deg=30, strategy="printed")
    assert default["observed_beyond_max_k"] == int(r0["beyond_max_k"].sum()) == 0
