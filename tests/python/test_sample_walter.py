"""sample() and pdf() with model="walter" (Walter et al. 2007's rough dielectric BSDF, analytic/
walter_sampling.h): the same draws as `vgroove sample --model walter` (its histogram over both
hemispheres, its reflected and transmitted counts and its weights' moments to the last bit, from
the stream (seed, (0x5a3d, 2))), the pdf of each draw pdf() at its direction, the weight f |cos| /
pdf with f from brdf(), and the command line's messages for bad input."""

import json
import math

import numpy as np
import pytest

from conftest import cli, cli_error

STREAM = (0x5A3D, 2)  # `vgroove sample --model walter`'s stream, three numbers a draw


def cli_walter(tmp_path, ndf, alpha, eta, theta_i, masking, n, seed):
    out = tmp_path / f"walter-{ndf}-{eta}-{masking}.json"
    r = cli("sample", "--model", "walter", "--ndf", ndf, "--alpha", alpha, "--eta", repr(eta), "--theta-i-deg",
            theta_i, "--masking", masking, "--n", n, "--seed", seed, "--out", out)
    assert r.returncode == 0, r.stdout + r.stderr
    with open(out) as f:
        return json.load(f)["result"]


def moments(weights):
    # The command line's sums, in its order (app/cmd_sample.cpp, run_walter).
    s = s2 = 0.0
    for w in weights.tolist():
        s += w
        s2 += w * w
    n = float(len(weights))
    mean = s / n
    return mean, max(0.0, s2 / n - mean * mean) * n / (n - 1.0)


def tally(r, t):
    """sample()'s output binned and counted as the command line does: cos theta_o in [-1, 1]."""
    rows, cols = len(t["row_edges"]) - 1, len(t["col_edges"]) - 1
    observed = np.zeros((rows, cols))
    for o, k in zip(r["wo"].tolist(), r["k"].tolist()):
        if k == 0:
            continue
        row = min(max(int((o[2] + 1.0) * 0.5 * rows), 0), rows - 1)
        c = min(max(int((math.atan2(o[1], o[0]) + math.pi) / (2.0 * math.pi) * cols), 0), cols - 1)
        observed[row, c] += 1
    none = float(np.sum(r["k"] == 0))
    return (observed.tolist(), none, int(np.sum(r["transmitted"])), int(np.sum((r["k"] > 0) & ~r["transmitted"])),
            *moments(r["weight"]))


def tally_of(result):
    t = result["table"]
    return (t["observed"], t["observed_no_direction"], result["transmitted"], result["reflected"],
            result["weight_mean"], result["weight_variance"])


CASES = [("ggx", 0.5, 1.5, 40, "smith"), ("beckmann", 0.4, 1 / 1.5, 30, "smith_separable"),
         ("phong", 0.7, 2.4, 70, "vcavity")]


@pytest.mark.parametrize("ndf,alpha,eta,theta_i,masking", CASES)
def test_walter_sample_equals_the_command_line_to_the_last_bit(vg, tmp_path, ndf, alpha, eta, theta_i, masking):
    n, seed = 20000, 5
    theirs = cli_walter(tmp_path, ndf, alpha, eta, theta_i, masking, n, seed)
    u = vg.uniforms(n, seed, STREAM, dims=3)
    r = vg.sample(ndf, alpha, u, theta_i_deg=theta_i, model="walter", eta=eta, masking=masking, threads=2)
    assert tally(r, theirs["table"]) == tally_of(theirs)
    # Power: the next seed's draws, the numbers of each draw in another order, or another G2 are told apart.
    for other, g in ((vg.uniforms(n, seed + 1, STREAM, dims=3), masking), (u[:, [2, 0, 1]], masking),
                     (u, "vcavity" if masking != "vcavity" else "smith")):
        if g != masking and ndf == "phong":
            continue
        r2 = vg.sample(ndf, alpha, other, theta_i_deg=theta_i, model="walter", eta=eta, masking=g)
        assert tally(r2, theirs["table"]) != tally_of(theirs)
    # Both sides: wo.z < 0 exactly where transmitted; unit vectors; pdf > 0 where a direction.
    ok = r["k"] > 0
    assert r["transmitted"].any() and (~r["transmitted"] & ok).any()
    assert np.array_equal(r["wo"][ok][:, 2] < 0, r["transmitted"][ok])
    assert np.all(r["pdf"][ok] > 0) and np.all(r["pdf"][~ok] == 0) and np.all(r["weight"][~ok] == 0)
    assert np.allclose(np.linalg.norm(r["wo"], axis=-1), 1.0, atol=1e-12, rtol=0)


def test_walter_pdf_and_weight_are_pdf_and_brdf_at_the_draw(vg):
    # The pdf a draw returns is pdf() at its direction, and its weight f |cos theta_o| / pdf with f
    # Walter's BSDF from brdf() (the brdf command's values) on either side.
    for ndf, alpha, eta, theta_i, masking in CASES:
        u = vg.uniforms(3000, 11, (4, 5), dims=3)
        r = vg.sample(ndf, alpha, u, theta_i_deg=theta_i, model="walter", eta=eta, masking=masking)
        ok = r["k"] > 0
        wo = r["wo"][ok]
        p = vg.pdf(ndf, alpha, wo, theta_i_deg=theta_i, model="walter", eta=eta, masking=masking)
        np.testing.assert_allclose(p, r["pdf"][ok], rtol=1e-12)
        f = vg.brdf("walter", ndf, alpha, vg.direction(theta_i, 180), wo, eta=eta, masking=masking)
        np.testing.assert_allclose(f * np.abs(wo[:, 2]) / p, r["weight"][ok], rtol=1e-9)
        # Power: the BSDF with the light's eta inverted is another function.
        g = vg.brdf("walter", ndf, alpha, vg.direction(theta_i, 180), wo, eta=1 / eta, masking=masking)
        assert not np.allclose(g * np.abs(wo[:, 2]) / p, r["weight"][ok], rtol=1e-3)


def test_walter_mean_weight_is_the_albedo_over_many_draws(vg):
    # GGX with Smith's separable G2 and the Smith VNDF: every weight is G1(o) (analytic/
    # walter_sampling.h); so the weight's mean is E[G1(o)] <= 1, and R + T <= 1 (no gain).
    u = vg.uniforms(20000, 3, STREAM, dims=3)
    r = vg.sample("ggx", 0.5, u, theta_i_deg=60, model="walter", eta=1.5, masking="smith_separable")
    ok = r["k"] > 0
    theta_o = np.arccos(np.abs(r["wo"][ok][:, 2]))
    a = 0.5 * np.tan(theta_o)
    g1 = 2.0 / (1.0 + np.sqrt(1.0 + a * a))  # GGX Smith G1 = 1 / (1 + Lambda)
    np.testing.assert_allclose(r["weight"][ok], g1, rtol=1e-12)
    assert 0.0 < r["weight"].mean() <= 1.0


@pytest.mark.parametrize("kwargs,flags", [
    ({"eta": 0.0}, ["--eta", "0"]),
    ({"eta": 1.0}, ["--eta", "1"]),
    ({"eta": -1.5}, ["--eta=-1.5"]),
    ({"eta": 1001.0}, ["--eta", "1001"]),
    ({"masking": "bogus"}, ["--masking", "bogus"]),
    ({"ndf": "phong"}, ["--ndf", "phong"]),
    ({"ndf": "phong", "masking": "smith"}, ["--ndf", "phong", "--masking", "smith"]),
    ({"strategy": "vndf"}, ["--strategy", "vndf"]),
    ({"max_k": 3}, ["--max-k", "3"]),
    ({"dim": "flatland"}, ["--dim", "flatland"]),
    ({"alpha": 3.0}, ["--alpha", "3"]),
])
def test_walter_bad_input_gives_the_command_lines_message(vg, kwargs, flags):
    expected = cli_error("sample", "--model", "walter", *flags)
    for flag in ("--max-k", "--strategy", "--ndf", "--dim", "--alpha", "--eta", "--masking", "--model"):
        expected = expected.replace(flag, flag[2:].replace("-", "_"))
    args = {"ndf": "ggx", "alpha": 0.5}
    args.update(kwargs)
    ndf, alpha = args.pop("ndf"), args.pop("alpha")
    with pytest.raises(ValueError) as e:
        vg.sample(ndf, alpha, [[0.1, 0.2, 0.3]], theta_i_deg=30, model="walter", **args)
    assert str(e.value) == expected
    with pytest.raises(ValueError) as e:
        vg.pdf(ndf, alpha, [[0.0, 0.0, -1.0]], theta_i_deg=30, model="walter", **args)
    assert str(e.value) == expected


@pytest.mark.parametrize("model,kwargs,flags", [
    ("vgroove", {"eta": 1.5}, ["--eta", "1.5"]),
    ("vgroove-nonsymmetric", {"masking": "smith"}, ["--masking", "smith"]),
    ("vgroove-dielectric", {"masking": "smith"}, ["--masking", "smith"]),
    ("cook-torrance", {}, []),
])
def test_eta_and_masking_belong_to_walter(vg, model, kwargs, flags):
    # eta belongs to walter and vgroove-dielectric, masking to walter: both faces name them alike.
    expected = cli_error("sample", "--model", model, *flags)
    for flag in ("--eta", "--masking", "--model"):
        expected = expected.replace(flag, flag[2:])
    if "eta" in kwargs:
        assert expected == f'eta applies to model walter and vgroove-dielectric only (model = "{model}")'
    m = 5 if model == "vgroove-nonsymmetric" else 4
    with pytest.raises(ValueError) as e:
        vg.sample("ggx", 0.5, [[0.1] * m], theta_i_deg=30, model=model, **kwargs)
    assert str(e.value) == expected


def test_walter_bad_arrays(vg):
    with pytest.raises(ValueError, match=r"shape \(\.\.\., 3\)"):
        vg.sample("ggx", 0.5, [0.1] * 4, theta_i_deg=30, model="walter")
    with pytest.raises(ValueError, match=r"u\[0\]\[2\] = 1 is out of range \[0, 1\)"):
        vg.sample("ggx", 0.5, [[0.1, 0.2, 1.0]], theta_i_deg=30, model="walter")
    with pytest.raises(ValueError, match=r"theta_i_deg\[0\] = 90 is out of range"):
        vg.sample("ggx", 0.5, [[0.1, 0.2, 0.3]], theta_i_deg=90, model="walter")
    with pytest.raises(ValueError, match="eta"):
        vg.sample("ggx", 0.5, [[0.1, 0.2, 0.3]], theta_i_deg=30, model="walter", eta=math.nan)


@pytest.mark.parametrize("ndf,alpha,eta,theta_i,masking", CASES)
def test_brdf_object_samples_walter_as_the_functions(vg, ndf, alpha, eta, theta_i, masking):
    # BRDF("walter").sample and .pdf are sample() and pdf() with model="walter" to the last bit; the
    # batch carries `transmitted` (no beyond_max_k), and as_dict() is sample()'s dict.
    f = vg.BRDF("walter", ndf, alpha, eta=eta, masking=masking)
    wi = vg.direction(theta_i, 180)
    u = vg.uniforms(2000, 5, STREAM, dims=3)
    b = f.sample(wi, u)
    r = vg.sample(ndf, alpha, u, wi=wi, model="walter", eta=eta, masking=masking)
    d = b.as_dict()
    assert list(d) == list(r) and b.beyond_max_k is None
    for key in r:
        np.testing.assert_array_equal(d[key], r[key])
    assert b.transmitted.any() and (b.wo[b.transmitted, 2] < 0).all() and (b.wo[~b.transmitted & (b.k > 0), 2] > 0).all()
    ok = b.k > 0
    np.testing.assert_array_equal(f.pdf(wi, b.wo[ok]), vg.pdf(ndf, alpha, b.wo[ok], wi=wi, model="walter", eta=eta,
                                                              masking=masking))
    np.testing.assert_allclose(f.pdf(wi, b.wo[ok]), b.pdf[ok], rtol=1e-12)
    # Power: the other side's eta gives other draws.
    other = vg.BRDF("walter", ndf, alpha, eta=1 / eta, masking=masking).sample(wi, u)
    assert not np.array_equal(other.wo, b.wo)


def test_brdf_object_walter_defaults_and_refusals(vg):
    # eta None is 1.5 and masking None smith_separable, as sample()'s; a strategy or max_k is refused
    # with sample()'s message; Cook-Torrance still has no sampler.
    wi, u = vg.direction(30, 180), vg.uniforms(500, 2, STREAM, dims=3)
    b = vg.BRDF("walter", "ggx", 0.5).sample(wi, u)
    r = vg.sample("ggx", 0.5, u, wi=wi, model="walter")
    np.testing.assert_array_equal(b.weight, r["weight"])
    with pytest.raises(ValueError) as e:
        vg.sample("ggx", 0.5, u, wi=wi, model="walter", strategy="vndf")
    with pytest.raises(ValueError) as e2:
        vg.BRDF("walter", "ggx", 0.5).sample(wi, u, strategy="vndf")
    assert str(e2.value) == str(e.value)
    with pytest.raises(ValueError, match=r"shape \(\.\.\., 3\)"):
        vg.BRDF("walter", "ggx", 0.5).sample(wi, vg.uniforms(5))
    with pytest.raises(ValueError, match="has no sampler here"):
        vg.BRDF("cook-torrance", "ggx", 0.5).sample(wi, vg.uniforms(5))
