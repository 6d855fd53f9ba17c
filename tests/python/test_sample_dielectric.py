"""sample() with model="vgroove-dielectric" (the kaleidoscopic dielectric model's sampler,
analytic/sampling_dielectric.h): the extension's draws to the last bit, the same draws as `vgroove
sample --model vgroove-dielectric` (its histogram over the lobe's bins, reflected and transmitted,
and its count of draws with no direction, from the streams (seed, (0x5a3d, 3)) in 3d and
(seed, (0x5a3d, 4)) in flatland), a chi-square against vgroove.dielectric_lobe's bins that rejects
the draws of the inverted eta, and the command line's messages for bad input."""

import json
import math

import numpy as np
import pytest

from conftest import cli, cli_error

STREAM = {"3d": (0x5A3D, 3), "flatland": (0x5A3D, 4)}  # `vgroove sample --model vgroove-dielectric`'s
DIMS = {"3d": 5, "flatland": 4}


def draws(vg, n, seed, dim):
    return vg.uniforms(n, seed, STREAM[dim], dims=DIMS[dim])


def tally(r, dim, theta_bins, phi_bins):
    """The draws binned as app/cmd_sample.cpp (sample_dielectric_command) bins them: reflected bins,
    transmitted bins (flatland: theta_o over (-90, 90) deg from the exit side's normal; 3d: theta_o
    over [0, 90) deg x phi_o centred on 0), and the draws with no direction."""
    bins = theta_bins if dim == "flatland" else theta_bins * phi_bins
    refl, trans = [0.0] * bins, [0.0] * bins
    none = 0.0
    dtheta = (math.pi if dim == "flatland" else 0.5 * math.pi) / theta_bins
    dphi = 2.0 * math.pi / phi_bins
    for o, w, reflected in zip(r["wo"].tolist(), r["weight"].tolist(), r["reflected"].tolist()):
        if not w > 0.0:
            none += 1.0
            continue
        if dim == "flatland":
            side = 1.0 if reflected else -1.0  # the light above: reflected exits above
            theta_o = math.atan2(-side * o[0], side * o[2])
            b = min(max(int(math.floor((theta_o + 0.5 * math.pi) / dtheta)), 0), theta_bins - 1)
        else:
            t = min(theta_bins - 1, int(math.atan2(math.hypot(o[0], o[1]), abs(o[2])) / dtheta))
            p = int(math.floor((math.atan2(o[1], o[0]) + 0.5 * dphi) / dphi)) % phi_bins
            b = t * phi_bins + p
        (refl if reflected else trans)[b] += 1.0
    return refl, trans, none


def cli_dielectric(tmp_path, ndf, alpha, eta, theta_i, dim, n, seed, theta_bins, phi_bins):
    out = tmp_path / f"dielectric-{ndf}-{eta}-{dim}.json"
    r = cli("sample", "--model", "vgroove-dielectric", "--ndf", ndf, "--alpha", alpha, "--eta", repr(eta),
            "--theta-i-deg", theta_i, "--dim", dim, "--n", n, "--seed", seed, "--theta-bins", theta_bins,
            "--phi-bins", phi_bins, "--out", out)
    assert r.returncode == 0, r.stdout + r.stderr
    with open(out) as f:
        return json.load(f)["result"]


CASES = [("ggx", 0.3, 1.5, 40.0, "flatland", 30, 2), ("beckmann", 0.5, 1 / 1.5, 30.0, "flatland", 24, 2),
         ("ggx", 0.4, 1.5, 50.0, "3d", 6, 8)]


@pytest.mark.parametrize("ndf,alpha,eta,theta_i,dim,theta_bins,phi_bins", CASES)
def test_draws_are_the_command_lines(vg, tmp_path, ndf, alpha, eta, theta_i, dim, theta_bins, phi_bins):
    n, seed = 20000, 7
    theirs = cli_dielectric(tmp_path, ndf, alpha, eta, theta_i, dim, n, seed, theta_bins, phi_bins)
    u = draws(vg, n, seed, dim)
    r = vg.sample(ndf, alpha, u, theta_i_deg=theta_i, model="vgroove-dielectric", eta=eta, dim=dim, threads=2)
    want = (theirs["observed_reflected"], theirs["observed_transmitted"], theirs["observed_no_direction"])
    assert tally(r, dim, theta_bins, phi_bins) == want
    # The extension's call, to the last bit (the wrapper adds nothing but the checks and shapes).
    x = vg._vgroove.dielectric_sample(ndf, alpha, eta, np.array([theta_i]), u, dim)
    assert list(r) == list(x) == ["wo", "k", "weight", "reflected"]
    for key in x:
        np.testing.assert_array_equal(r[key], x[key])
    # Power: the next seed's draws, the inverted eta, the numbers of each draw in another order.
    for other, e in ((draws(vg, n, seed + 1, dim), eta), (u, 1 / eta), (u[:, ::-1].copy(), eta)):
        r2 = vg.sample(ndf, alpha, other, theta_i_deg=theta_i, model="vgroove-dielectric", eta=e, dim=dim)
        assert tally(r2, dim, theta_bins, phi_bins) != want
    # Both sides; weight 1 exactly where a direction; wo below the surface exactly where transmitted.
    ok = r["weight"] > 0
    assert r["reflected"].any() and (~r["reflected"] & ok).any()
    assert np.all(r["weight"][ok] == 1.0) and np.all(r["k"][ok] >= 1) and np.all(r["k"][~ok] == 0)
    assert np.array_equal(r["wo"][ok][:, 2] < 0, ~r["reflected"][ok])
    assert np.allclose(np.linalg.norm(r["wo"], axis=-1), 1.0, atol=1e-12, rtol=0)


def test_shapes_broadcast_and_the_defaults_are_the_command_lines(vg):
    # u of shape (2, 3, 5) gives arrays over (2, 3); eta None is 1.5 (`vgroove sample --eta`'s
    # default) and dim "3d"; a theta_i_deg per row broadcasts.
    u = draws(vg, 6, 3, "3d")
    r = vg.sample("ggx", 0.5, u.reshape(2, 3, 5), theta_i_deg=[[10], [60]], model="vgroove-dielectric")
    assert r["wo"].shape == (2, 3, 3) and r["k"].shape == (2, 3) and r["reflected"].dtype == bool
    x = vg._vgroove.dielectric_sample("ggx", 0.5, 1.5, np.repeat([10.0, 60.0], 3), u, "3d")
    np.testing.assert_array_equal(r["wo"].reshape(6, 3), x["wo"])


def chi_square(observed, expected):
    """Pearson's statistic over the cells with expected >= 5, the rest pooled into one cell (when
    it holds >= 5), and its degrees of freedom."""
    o, e = np.asarray(observed, float), np.asarray(expected, float)
    big = e >= 5
    cells_o, cells_e = list(o[big]), list(e[big])
    if e[~big].sum() >= 5:
        cells_o.append(o[~big].sum())
        cells_e.append(e[~big].sum())
    cells_o, cells_e = np.array(cells_o), np.array(cells_e)
    return float(np.sum((cells_o - cells_e) ** 2 / cells_e)), len(cells_e) - 1


def chi_square_bound(dof, z=4.265):
    """Wilson and Hilferty's chi-square quantile at the normal quantile z (4.265: p = 1e-5)."""
    h = 2.0 / (9.0 * dof)
    return dof * (1.0 - h + z * math.sqrt(h)) ** 3


@pytest.mark.parametrize("ndf,alpha,eta,theta_i,dim", [("ggx", 0.3, 1.5, 40.0, "flatland"),
                                                       ("beckmann", 0.5, 1 / 1.5, 30.0, "flatland"),
                                                       ("ggx", 0.4, 1.5, 50.0, "3d")])
def test_draws_follow_the_lobe_and_the_inverted_eta_is_rejected(vg, ndf, alpha, eta, theta_i, dim):
    # The draws' density is the model's BSDF |cos theta_o| (analytic/sampling_dielectric.h): binned,
    # they are dielectric_lobe's bins (reflected, transmitted, and no direction with the rest of the
    # mass); the mean weight is R + T and the reflected share R, within 5 binomial standard errors.
    # The same draws with eta inverted (the light from the other medium) are far outside both.
    n, seed = 40000, 11
    tb, pb = (24, 2) if dim == "flatland" else (6, 8)
    kw = dict(dim=dim, flatland_bins=tb) if dim == "flatland" else dict(dim=dim, theta_bins=tb, phi_bins=pb)
    L = vg.dielectric_lobe(ndf, alpha, eta, theta_i, **kw)
    expected = np.concatenate([L["reflected"].ravel(), L["transmitted"].ravel(),
                               [max(0.0, 1.0 - L["albedo_r"] - L["albedo_t"])]]) * n
    u = draws(vg, n, seed, dim)
    for e, good in ((eta, True), (1 / eta, False)):
        r = vg.sample(ndf, alpha, u, theta_i_deg=theta_i, model="vgroove-dielectric", eta=e, dim=dim)
        refl, trans, none = tally(r, dim, tb, pb)
        stat, dof = chi_square(refl + trans + [none], expected)
        bound = chi_square_bound(dof)
        albedo, share_r = L["albedo_r"] + L["albedo_t"], L["albedo_r"]
        mean_ok = abs(r["weight"].mean() - albedo) <= 5 * math.sqrt(albedo * (1 - albedo) / n) + 1e-12
        refl_ok = abs(r["reflected"].mean() - share_r) <= 5 * math.sqrt(share_r * (1 - share_r) / n)
        msg = f"eta={e}: chi2 {stat:.1f} dof {dof} bound {bound:.1f}; R {r['reflected'].mean():.5f} vs {share_r:.5f}"
        if good:
            assert stat < bound and mean_ok and refl_ok, msg
        else:
            assert stat > 10 * bound and not refl_ok, msg


@pytest.mark.parametrize("kwargs,flags", [
    ({"eta": 0.0}, ["--eta", "0"]),
    ({"eta": 1.0}, ["--eta", "1"]),
    ({"eta": -1.5}, ["--eta=-1.5"]),
    ({"eta": 1001.0}, ["--eta", "1001"]),
    ({"masking": "smith"}, ["--masking", "smith"]),
    ({"strategy": "vndf"}, ["--strategy", "vndf"]),
    ({"max_k": 3}, ["--max-k", "3"]),
    ({"alpha": 3.0}, ["--alpha", "3"]),
    ({"ndf": "lambert"}, ["--ndf", "lambert"]),
    ({"dim": "2d"}, ["--dim", "2d"]),
])
def test_bad_input_gives_the_command_lines_message(vg, kwargs, flags):
    expected = cli_error("sample", "--model", "vgroove-dielectric", *flags)
    for flag in ("--max-k", "--strategy", "--ndf", "--dim", "--alpha", "--eta", "--masking", "--model"):
        expected = expected.replace(flag, flag[2:].replace("-", "_"))
    args = {"ndf": "ggx", "alpha": 0.5}
    args.update(kwargs)
    ndf, alpha = args.pop("ndf"), args.pop("alpha")
    with pytest.raises(ValueError) as e:
        vg.sample(ndf, alpha, [[0.1, 0.2, 0.3, 0.4, 0.5]], theta_i_deg=30, model="vgroove-dielectric", **args)
    assert str(e.value) == expected


def test_bad_arrays_and_what_the_model_does_not_take(vg):
    m = "vgroove-dielectric"
    with pytest.raises(ValueError, match=r"shape \(\.\.\., 4\)"):
        vg.sample("ggx", 0.5, [[0.1] * 5], theta_i_deg=30, model=m, dim="flatland")
    with pytest.raises(ValueError, match=r"shape \(\.\.\., 5\)"):
        vg.sample("ggx", 0.5, [[0.1] * 4], theta_i_deg=30, model=m)
    with pytest.raises(ValueError, match=r"u\[0\]\[4\] = 1 is out of range \[0, 1\)"):
        vg.sample("ggx", 0.5, [[0.1, 0.2, 0.3, 0.4, 1.0]], theta_i_deg=30, model=m)
    with pytest.raises(ValueError, match=r"theta_i_deg\[0\] = 90 is out of range \[0, 89.9\]"):
        vg.sample("ggx", 0.5, [[0.1] * 5], theta_i_deg=90, model=m)
    with pytest.raises(ValueError, match=r"eta = nan is out of range"):
        vg.sample("ggx", 0.5, [[0.1] * 5], theta_i_deg=30, model=m, eta=math.nan)
    with pytest.raises(ValueError, match=r"^wi does not apply to model vgroove-dielectric: give the light as"):
        vg.sample("ggx", 0.5, [[0.1] * 5], wi=vg.direction(30, 180), model=m)
    with pytest.raises(ValueError, match=r"^wi does not apply to model vgroove-dielectric"):
        vg.pdf("ggx", 0.5, [[0.0, 0.0, 1.0]], wi=vg.direction(30, 180), model=m)
    with pytest.raises(ValueError, match=r"^max_k applies to model vgroove and vgroove-nonsymmetric only"):
        vg.pdf("ggx", 0.5, [[0.0, 0.0, 1.0]], theta_i_deg=30, model=m, max_k=3)


def test_an_unknown_model_names_the_four(vg):
    # The command line and sample() list the same models (vgroove-dielectric among them).
    expected = cli_error("sample", "--model", "lambert").replace("--model", "model")
    with pytest.raises(ValueError) as e:
        vg.sample("ggx", 0.5, [[0.1] * 4], theta_i_deg=30, model="lambert")
    assert str(e.value) == expected and '"vgroove-dielectric"' in expected


def test_pdf_in_3d_is_the_bsdfs_density_at_every_draw(vg):
    # pdf(model="vgroove-dielectric") at the sampler's own directions: positive at every draw, and
    # dielectric_bsdf's pdf (f |cos theta_o|, the command line's numbers) at the same directions.
    r = vg.sample("ggx", 0.4, draws(vg, 400, 5, "3d"), theta_i_deg=50, model="vgroove-dielectric", eta=1.5)
    wo = r["wo"][r["k"] > 0]
    p = vg.pdf("ggx", 0.4, wo, theta_i_deg=50, model="vgroove-dielectric", eta=1.5)
    assert (p > 0).all()
    theta_o = np.degrees(np.arccos(np.clip(wo[:, 2], -1, 1)))
    phi_o = np.degrees(np.arctan2(wo[:, 1], wo[:, 0]))
    b = vg.dielectric_bsdf("ggx", 0.4, 1.5, 50, theta_o, phi_i_deg=180, phi_o_deg=phi_o)
    np.testing.assert_allclose(p, b["pdf"], rtol=1e-9)


@pytest.mark.parametrize("eta,broken", [(1.5, False), (1 / 1.5, False), (1.5, True)])
def test_pdf_in_flatland_integrates_to_the_draws(vg, eta, broken):
    # 40,000 draws binned in theta_o (24 bins a side, from each side's normal) against N times the
    # pdf integrated over each bin (midpoint rule, 256 points a bin: the lobes have integrable 1 / sqrt
    # folds, with 16 points the eta 1.5 case gave 81.9 at 36 dof, with 64 54.1), the zero-weight draws pooled
    # with the remainder; chi-square below its p = 1e-5 bound. Broken: the pdf at 1 / eta.
    n, bins, sub = 40000, 24, 256
    r = vg.sample("ggx", 0.3, draws(vg, n, 9, "flatland"), theta_i_deg=35, model="vgroove-dielectric", eta=eta,
                  dim="flatland")
    ok = r["k"] > 0
    wo = r["wo"][ok]
    above = wo[:, 2] > 0
    t = np.where(above, np.arctan2(-wo[:, 0], wo[:, 2]), np.arctan2(wo[:, 0], -wo[:, 2]))
    edges = np.linspace(-np.pi / 2, np.pi / 2, bins + 1)
    observed = np.concatenate([np.histogram(t[above], edges)[0], np.histogram(t[~above], edges)[0]])
    width = edges[1] - edges[0]
    mid = (edges[:-1, None] + (np.arange(sub) + 0.5) / sub * width).ravel()
    grid = np.concatenate([np.stack([-np.sin(mid), np.zeros_like(mid), np.cos(mid)], -1),
                           np.stack([np.sin(mid), np.zeros_like(mid), -np.cos(mid)], -1)])
    p = vg.pdf("ggx", 0.3, grid, theta_i_deg=35, model="vgroove-dielectric", eta=1 / eta if broken else eta,
               dim="flatland")
    expected = n * p.reshape(2 * bins, sub).mean(axis=1) * width
    observed = np.append(observed, n - ok.sum())
    expected = np.append(expected, max(n - expected.sum(), 0.0))
    stat, dof = chi_square(observed, expected)
    if broken:
        assert stat > chi_square_bound(dof), (stat, dof)
    else:
        assert stat < chi_square_bound(dof), (stat, dof)
