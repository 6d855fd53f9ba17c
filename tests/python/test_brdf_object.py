"""vgroove.BRDF against the other faces: each method's values equal the function it stands beside
(brdf, sample, pdf, lobe, trace_microsurface) and the command line (`vgroove brdf`, `vgroove
sample`, `vgroove validate`'s report) to the last bit, with the one max_k default of every face;
the physics each method must show (energy, the pdf as the BRDF times the cosine, Fresnel on
single-reflection paths by hand); and the results as frozen dataclasses."""

import dataclasses
import json
import math

import numpy as np
import pytest

from conftest import TINY_BRDF, cli, cli_json, write_json
from test_sampling import STREAM, cli_sample, tally, tally_of

# (model, dim, options) of vgroove.BRDF and the command line's flags for them.
CASES = [
    ("vgroove", "3d", {}, []),
    ("vgroove", "flatland", {"max_k": 64}, ["--max-k", 64]),
    ("cook-torrance", "3d", {}, []),
    ("cook-torrance", "flatland", {}, []),
    ("vgroove-nonsymmetric", "3d", {"max_k": 16}, ["--max-k", 16]),
    ("vgroove-nonsymmetric", "3d", {"max_k": 8, "alpha_y": 0.3, "partner": "symmetric"},
     ["--max-k", 8, "--alpha-y", 0.3, "--partner", "symmetric"]),
    ("vgroove-nonsymmetric", "flatland", {"max_k": 8}, ["--max-k", 8]),
]


def pairs_deg(dim, n, seed):
    """Direction pairs in degrees, as `vgroove brdf --directions` takes them (3D: the light at
    azimuth 0 as the command line's default; flatland: signed angles)."""
    rng = np.random.default_rng(seed)
    if dim == "flatland":
        return [{"theta_i_deg": float(a), "theta_o_deg": float(b)}
                for a, b in zip(rng.uniform(-85, 85, n).round(3), rng.uniform(-89, 89, n).round(3))]
    return [{"theta_i_deg": float(a), "phi_i_deg": float(p), "theta_o_deg": float(b), "phi_o_deg": float(q)}
            for a, p, b, q in zip(rng.uniform(0, 85, n).round(3), rng.uniform(-180, 180, n).round(3),
                                  rng.uniform(0, 89, n).round(3), rng.uniform(-180, 180, n).round(3))]


def directions_of(vg, pairs, dim):
    """The same pairs as unit vectors: the command line's conversion (vgroove.direction)."""
    if dim == "flatland":
        ti = np.array([p["theta_i_deg"] for p in pairs])
        to = np.array([p["theta_o_deg"] for p in pairs])
        return vg.direction(ti, 180.0) * [1, 0, 1], vg.direction(to, 180.0) * [1, 0, 1]
    get = lambda key: np.array([p[key] for p in pairs])  # noqa: E731
    return vg.direction(get("theta_i_deg"), get("phi_i_deg")), vg.direction(get("theta_o_deg"), get("phi_o_deg"))


@pytest.mark.parametrize("model,dim,options,flags", CASES)
def test_eval_equals_the_command_line_and_the_function_to_the_last_bit(vg, tmp_path, model, dim, options, flags):
    pairs = pairs_deg(dim, 40, 7)
    path = write_json(tmp_path / "pairs.json", {"directions": pairs})
    for ndf, alpha in (("ggx", 0.5), ("beckmann", 1.3)):
        theirs = cli_json("brdf", "--model", model, "--ndf", ndf, "--alpha", alpha, "--dim", dim, "--directions", path,
                          "--json", *flags)
        f = vg.BRDF(model, ndf, alpha, dim=dim, **options)
        wi, wo = directions_of(vg, pairs, dim)
        ours = f.eval(wi, wo, threads=2)
        assert ours.tolist() == [p["value"] for p in theirs["points"]], (ndf, alpha)
        assert f.max_k == theirs["inputs"]["max_k"]
        if not {"alpha_y", "partner"} & set(options):
            assert np.array_equal(ours, vg.brdf(model, ndf, alpha, wi, wo, dim=dim, max_k=options.get("max_k"),
                                                threads=1))
        # Power: the next order, or the pairs in another order, are told apart.
        assert f.eval(wi[::-1], wo[::-1]).tolist() != ours.tolist()


@pytest.mark.parametrize("dim", ["3d", "flatland"])
def test_walter_equals_the_command_line_on_both_sides_to_the_last_bit(vg, tmp_path, dim):
    # The viewer anywhere on the sphere (3D: polar angle 0-179 deg, over 90 below the interface;
    # flatland: signed angles -179..179 deg), light from the near side.
    rng = np.random.default_rng(11)
    n = 60
    ti = rng.uniform(0 if dim == "3d" else -85, 85, n).round(3)
    to = rng.uniform(0 if dim == "3d" else -179, 179, n).round(3)
    pairs = [{"theta_i_deg": float(a), "theta_o_deg": float(b)} for a, b in zip(ti, to)]
    if dim == "3d":
        for p, a, b in zip(pairs, rng.uniform(-180, 180, n).round(3), rng.uniform(-180, 180, n).round(3)):
            p["phi_i_deg"], p["phi_o_deg"] = float(a), float(b)
    path = write_json(tmp_path / "pairs.json", {"directions": pairs})
    wi, wo = directions_of(vg, pairs, dim)
    for eta, masking in ((1.33, "smith"), (1 / 1.5, "vcavity"), (2.4, None)):
        flags = ["--masking", masking] if masking else []
        theirs = cli_json("brdf", "--model", "walter", "--alpha", 0.4, "--eta", repr(eta), "--dim", dim,
                          "--directions", path, "--json", *flags)
        assert theirs["inputs"]["masking"] == (masking or "smith_separable")
        ours = vg.BRDF("walter", "ggx", 0.4, eta=eta, masking=masking, dim=dim).eval(wi, wo, threads=2)
        assert ours.tolist() == [p["value"] for p in theirs["points"]], (eta, masking)
        assert np.array_equal(ours, vg.brdf("walter", "ggx", 0.4, wi, wo, dim=dim, eta=eta, masking=masking))
        below = wo[:, 2] < 0
        # Power: both sides carry light (the transmitted values are not zeros of a reflection-only model).
        assert (ours[below] > 0).sum() > 5 and (ours[~below] > 0).sum() > 5, (eta, masking)


def test_walter_refuses_what_it_cannot_do(vg):
    f = vg.BRDF("walter", "beckmann", 0.3, eta=1.5)
    wi, below = vg.direction(30, 0), np.array([0.0, 0.0, -1.0])
    cases = [
        (lambda: vg.BRDF("walter", "ggx", 0.3, eta=0), r"eta = 0 is out of range \(0, 1000\] with model walter"),
        (lambda: vg.BRDF("walter", "ggx", 0.3, eta=1.5 + 0.1j), r"eta = 1.5 \+ 0.1j is out of range"),
        (lambda: vg.BRDF("walter", "ggx", 0.3, masking="heitz"), r'masking = "heitz" is not one of "smith"'),
        (lambda: vg.BRDF("walter", "phong", 0.3), r"model walter with ndf phong needs masking = \"vcavity\""),
        (lambda: vg.BRDF("vgroove", "ggx", 0.3, masking="smith"), r"masking applies to model walter only"),
        (lambda: f.eval(below, wi), r"wi\[0\] = \(0, 0, -1\) is not above the interface"),
        (lambda: f.sample(wi, [0.5, 0.5]), r"u must be an array of uniform numbers, shape \(\.\.\., 3\)"),
        (lambda: f.lobe(30), r'lobe: model = "walter" is not binned here'),
        (lambda: vg.check_brdf("walter", rays=10), r'f = "walter": check_brdf holds reflection BRDFs'),
    ]
    for call, message in cases:
        with pytest.raises(ValueError, match="^" + message):
            call()
    assert float(vg.BRDF("walter", "phong", 0.3, masking="vcavity").eval(wi, below)) > 0


@pytest.mark.parametrize("model,dim", [("vgroove", "3d"), ("vgroove", "flatland"), ("vgroove-nonsymmetric", "3d"),
                                       ("cook-torrance", "3d")])
def test_the_default_max_k_is_the_command_lines(vg, model, dim):
    # One pair near the mirror direction, where narrow grooves send light after many reflections
    ti, to = (30.0, -31.0) if dim == "flatland" else (30.0, 31.0)
    theirs = cli_json("brdf", "--model", model, "--ndf", "phong", "--alpha", 1.3, "--dim", dim, "--theta-i-deg", ti,
                      "--theta-o-deg", to, "--phi-o-deg", 180 if dim == "3d" else 0, "--json")
    f = vg.BRDF(model, "phong", 1.3, dim=dim)
    wi = vg.direction(ti, 0.0) if dim == "3d" else vg.direction(ti, 180.0) * [1, 0, 1]
    wo = vg.direction(to, 180.0) * ([1, 1, 1] if dim == "3d" else [1, 0, 1])
    assert f.max_k == theirs["inputs"]["max_k"] == vg.BRDF_MAX_K[(model, dim)]
    assert float(f.eval(wi, wo)) == theirs["points"][0]["value"]
    assert float(vg.brdf(model, "phong", 1.3, wi, wo, dim=dim)) == theirs["points"][0]["value"]
    # The defaults are the table's: every order in 3D (its sum costs the same for any max_k), the
    # flatland and nonsymmetric sums bounded.
    assert vg.BRDF_MAX_K == {("vgroove", "3d"): 1000000, ("vgroove", "flatland"): 4096,
                             ("vgroove-nonsymmetric", "3d"): 64, ("vgroove-nonsymmetric", "flatland"): 64,
                             ("cook-torrance", "3d"): 1000000, ("cook-torrance", "flatland"): 1000000,
                             ("walter", "3d"): 1000000, ("walter", "flatland"): 1000000}
    if model != "cook-torrance":
        # Power: at Phong alpha 1.3 the orders beyond 16 carry flux there, so another default differs.
        other = 16 if f.max_k != 16 else 64
        assert float(vg.BRDF(model, "phong", 1.3, dim=dim, max_k=other).eval(wi, wo)) != theirs["points"][0]["value"]


def fresnel_conductor(c, eta):
    """Unpolarized reflectance of a conductor n = eta (complex), written out here from the
    amplitudes r_s = (c - w) / (c + w), r_p = (n^2 c - w) / (n^2 c + w), w = sqrt(n^2 - 1 + c^2)."""
    n2 = complex(eta) ** 2
    w = np.sqrt(n2 - 1 + c.astype(complex) ** 2)
    rs = (c - w) / (c + w)
    rp = (n2 * c - w) / (n2 * c + w)
    return 0.5 * (np.abs(rs) ** 2 + np.abs(rp) ** 2)


def test_fresnel_on_single_reflections_is_f_at_the_half_vector(vg):
    # One reflection, on the facet whose normal is the half vector h: the value with eta is the
    # value with F = 1 times F(i . h) (Cook-Torrance, and vgroove with max_k = 1); the weight of a
    # sample of one reflection is F(i . h) (the VNDF draw samples the F = 1 BRDF exactly).
    eta = 0.2 + 3.0j
    rng = np.random.default_rng(5)
    wi = vg.direction(rng.uniform(0, 80, 500), 180.0)
    wo = vg.direction(rng.uniform(0, 85, 500), rng.uniform(-180, 180, 500))
    h = (wi + wo) / np.linalg.norm(wi + wo, axis=-1, keepdims=True)
    F = fresnel_conductor(np.sum(wi * h, -1), eta)
    for model, max_k in (("cook-torrance", None), ("vgroove", 1)):
        plain = vg.BRDF(model, "ggx", 0.6, max_k=max_k).eval(wi, wo)
        with_f = vg.BRDF(model, "ggx", 0.6, max_k=max_k, eta=eta).eval(wi, wo)
        np.testing.assert_allclose(with_f, plain * F, rtol=1e-12, atol=1e-300)
        # Power: another metal differs.
        assert not np.allclose(vg.BRDF(model, "ggx", 0.6, max_k=max_k, eta=1.5 + 2j).eval(wi, wo), with_f, rtol=1e-3)
    # Every order: 0 <= with F <= F = 1.
    full, plain = vg.BRDF("vgroove", "ggx", 0.6, eta=eta).eval(wi, wo), vg.BRDF("vgroove", "ggx", 0.6).eval(wi, wo)
    assert np.all(full >= 0) and np.all(full <= plain) and np.all(full < plain)
    # A sample's weight with F is the Fresnel-weighted BRDF over its pdf (sampling_3d.h weighs the
    # paths to wo by their Fresnel products, brdf_3d.h sums them): the two code paths agree, and
    # the weights are below 1 (each F < 1); the directions and the pdf do not depend on F.
    f = vg.BRDF("vgroove", "ggx", 0.6, eta=eta, max_k=64)
    b = f.sample(wi[0], vg.uniforms(5000, 3))
    ok = b.k > 0
    np.testing.assert_allclose(b.weight[ok] * b.pdf[ok], f.eval(wi[0], b.wo[ok]) * b.wo[ok, 2], rtol=1e-9)
    assert np.all(b.weight[ok] < 1) and np.all(b.weight[ok] > 0)
    plain_b = vg.BRDF("vgroove", "ggx", 0.6, max_k=64).sample(wi[0], vg.uniforms(5000, 3))
    assert np.array_equal(plain_b.wo, b.wo) and np.array_equal(plain_b.pdf, b.pdf)
    np.testing.assert_allclose(plain_b.weight[ok], 1.0, rtol=1e-9)


@pytest.mark.parametrize("dim,ndf,alpha,theta_i,strategy", [
    ("3d", "ggx", 0.5, 30, "vndf"),
    ("3d", "beckmann", 0.3, 75, "printed"),
    ("flatland", "ggx", 0.5, 30, "smith-vndf"),
])
def test_sample_equals_the_command_line_and_the_function(vg, tmp_path, dim, ndf, alpha, theta_i, strategy):
    n, seed = 20000, 5
    theirs = cli_sample(tmp_path, dim, ndf, alpha, theta_i, strategy, n, seed)
    u = vg.uniforms(n, seed, (STREAM, 0 if dim == "3d" else 1))
    wi = vg.direction(theta_i, 180.0)
    if dim == "flatland":
        wi = wi * [1, 0, 1]
    b = vg.BRDF("vgroove", ndf, alpha, dim=dim).sample(wi, u, strategy=strategy, threads=2)
    assert tally(b.as_dict(), dim, theirs["table"]) == tally_of(theirs)
    f = vg.sample(ndf, alpha, u, wi=wi, strategy=strategy, dim=dim)
    for key, a in f.items():
        assert np.array_equal(getattr(b, key), a), key
    # theta_i_deg and wi give the same bits (the command line's light: dir3(theta_i, pi)).
    g = vg.sample(ndf, alpha, u, theta_i_deg=theta_i, strategy=strategy, dim=dim)
    assert all(np.array_equal(g[key], a) for key, a in f.items())
    # pdf: the function's, bit for bit; and the density sample() returned at the same directions.
    ok = b.k > 0
    p = vg.BRDF("vgroove", ndf, alpha, dim=dim).pdf(wi, b.wo, strategy=strategy)
    assert np.array_equal(p, vg.pdf(ndf, alpha, b.wo, wi=wi, strategy=strategy, dim=dim))
    np.testing.assert_allclose(p[ok], b.pdf[ok], rtol=1e-9)


def test_pdf_is_eval_times_cosine_with_the_same_max_k(vg):
    rng = np.random.default_rng(9)
    wo = vg.direction(rng.uniform(0, 89, 3000), rng.uniform(-180, 180, 3000))
    wi = vg.direction(35.0, 180.0)
    for ndf, alpha in (("ggx", 0.5), ("beckmann", 1.0), ("phong", 0.4)):
        f = vg.BRDF("vgroove", ndf, alpha, max_k=64)
        np.testing.assert_allclose(f.pdf(wi, wo), f.eval(wi, wo) * wo[:, 2], rtol=1e-9, atol=1e-300)


def test_lobe_albedo_and_trace_equal_the_report(vg, reports):
    with open(reports["brdf"]) as f:
        report = json.load(f)
    s = TINY_BRDF
    for case in report["cases"]:
        dim = case["dimension"]
        f = vg.BRDF("vgroove", case["ndf"], case["alpha"], dim=dim)
        bins = dict(flatland_bins=s["flatland_bins"], theta_bins=s["theta_bins"], phi_bins=s["phi_bins"])
        lobe = f.lobe(case["theta_i_deg"], k_rows=s["max_k"], **bins)
        assert lobe.by_k.tolist() == case["by_k_model"] and lobe.albedo == case["albedo_model"]
        d = vg.lobe("vgroove", case["ndf"], case["alpha"], case["theta_i_deg"], dim, max_k=s["max_k"], **bins)
        assert d.keys() == lobe.as_dict().keys()
        assert all(np.array_equal(d[k], v) for k, v in lobe.as_dict().items())
        wi = vg.direction(case["theta_i_deg"], 180.0)
        if dim == "flatland":
            wi = wi * [1, 0, 1]
        assert float(f.albedo(wi, k_rows=s["max_k"], **bins)) == case["albedo_model"]
        ct = vg.BRDF("cook-torrance", case["ndf"], case["alpha"], dim=dim)
        assert float(ct.albedo(wi, k_rows=s["max_k"], **bins)) == case["albedo_cook_torrance"]
        t = f.trace(case["theta_i_deg"], s["rays"], grooves=s["grooves"], seed=s["seed"], k_rows=s["max_k"], **bins)
        assert t.rays == case["rays"] and t.escaped == case["escaped"] and t.bounces == case["bounces"]
        assert (t.by_k / t.rays).tolist() == case["by_k_sim"]
        surf = vg.microsurface(case["ndf"], case["alpha"], s["grooves"], s["seed"], dim=dim)
        d = vg.trace_microsurface(surf, case["theta_i_deg"], s["rays"], max_k=s["max_k"], **bins)
        assert d.keys() == t.as_dict().keys()
        assert all(np.array_equal(d[k], v) for k, v in t.as_dict().items())


def test_albedo_conserves_energy_and_does_not_depend_on_the_bins(vg):
    # Every order of the symmetric model: the albedo is 1 (Lee et al. 2018, Sec. 5.1: the grooves
    # send out all the light); Cook-Torrance loses the light single scattering does not send out.
    # The lobe's total is exact to rounding (analytic/lobe_3d.h: albedo - 1 < 3e-14 at the suites'
    # bins; coarser bins round it less well, 2.8e-13 at 1 x 2 bins).
    wi = vg.direction(np.array([0.0, 30.0, 60.0, 85.0]), 180.0)
    for ndf, alpha in (("ggx", 0.3), ("beckmann", 1.0), ("phong", 0.5), ("ggx", 2.0)):
        a = vg.BRDF("vgroove", ndf, alpha).albedo(wi)
        np.testing.assert_allclose(a, 1.0, rtol=0, atol=3e-14)
        np.testing.assert_allclose(a, vg.BRDF("vgroove", ndf, alpha).albedo(wi, theta_bins=1, phi_bins=2),
                                   rtol=0, atol=3e-13)
        assert np.array_equal(a, [vg.BRDF("vgroove", ndf, alpha).lobe(t).albedo for t in (0.0, 30.0, 60.0, 85.0)])
        ct = vg.BRDF("cook-torrance", ndf, alpha).albedo(wi)
        assert np.all(ct < 1) and np.all(ct > 0)
        flat = vg.BRDF("vgroove", ndf, alpha, dim="flatland").albedo(vg.direction([-60.0, 0.0, 40.0], 180) * [1, 0, 1])
        np.testing.assert_allclose(flat, 1.0, rtol=0, atol=1e-12)
    # max_k given: the orders up to it, which the lobe splits per order.
    f, g = vg.BRDF("vgroove", "ggx", 1.0, max_k=2), vg.BRDF("vgroove", "ggx", 1.0)
    full = g.lobe(40, k_rows=4)
    cut = f.lobe(40, k_rows=4)
    assert cut.albedo == float(full.by_k[:3].sum()) == float(f.albedo(vg.direction(40, 180)))
    np.testing.assert_allclose(cut.hist, full.hist_by_k[:3].sum(0), rtol=1e-15, atol=1e-300)
    assert cut.by_k[3] == 0 and cut.albedo < 0.99


def test_results_are_frozen(vg):
    f = vg.BRDF("vgroove", "ggx", 0.5, dim="flatland")
    for r in (f.lobe(30, flatland_bins=9), f.trace(30, 1000, grooves=500, flatland_bins=9),
              vg.BRDF().sample(vg.direction(30, 180), vg.uniforms(10))):
        field = dataclasses.fields(r)[0].name
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(r, field, None)
        arrays = [getattr(r, f.name) for f in dataclasses.fields(r) if isinstance(getattr(r, f.name), np.ndarray)]
        assert arrays and all(not a.flags.writeable for a in arrays)
    with pytest.raises(AttributeError):
        f.alpha = 1.0
    assert vg.BRDF("vgroove", "ggx", 0.5) == vg.BRDF() and hash(vg.BRDF()) == hash(vg.BRDF("vgroove"))
    assert vg.BRDF(max_k=16) != vg.BRDF()
    assert repr(vg.BRDF("vgroove-nonsymmetric", "ggx", 0.3, alpha_y=0.5, max_k=8)) == \
        'vgroove.BRDF(model="vgroove-nonsymmetric", ndf="ggx", alpha=0.3, alpha_y=0.5, max_k=8, dim="3d")'


def brdf_errors(vg):
    wi, wo = vg.direction(30, 180), vg.direction(40, 0)
    f = vg.BRDF()
    return [
        (lambda: vg.BRDF(alpha=0.0), r"alpha = 0 is out of range \[0.01, 2\]"),
        (lambda: vg.BRDF(alpha=True), r"alpha = True must be a real number, not a bool"),
        (lambda: vg.BRDF("ct"), r'model = "ct" is not one of "vgroove", "vgroove-nonsymmetric", "cook-torrance"'),
        (lambda: vg.BRDF(ndf="gxx"), r'ndf = "gxx" is not one of "beckmann", "ggx", "phong"'),
        (lambda: vg.BRDF(dim="2d"), r'dim = "2d" is not one of "3d", "flatland"'),
        (lambda: vg.BRDF(max_k=0), r"max_k = 0 is out of range \[1, 2147483647\]"),
        (lambda: vg.BRDF(max_k=1.5), r"max_k = 1.5 must be an integer"),
        (lambda: vg.BRDF(dim="flatland", max_k=5000),
         r"max_k = 5000 is out of range \[1, 4096\] with dim flatland$"),
        (lambda: vg.BRDF(alpha_y=0.3), r'alpha_y applies to model vgroove-nonsymmetric only \(model = "vgroove"\)'),
        (lambda: vg.BRDF("vgroove-nonsymmetric", alpha_y=3.0), r"alpha_y = 3 is out of range \[0.01, 2\]"),
        (lambda: vg.BRDF("vgroove-nonsymmetric", partner="twin"),
         r'partner = "twin" is not one of "independent", "symmetric"'),
        (lambda: vg.BRDF("vgroove-nonsymmetric", "phong", 1.5), r"alpha = 1.5 is out of range \(0, 1.4142135623730951\) with model vgroove-nonsymmetric ndf phong"),
        (lambda: vg.BRDF(eta=-1.0), r"eta = -1 \+ 0j is out of range: real part in \(0, 1000\]"),
        (lambda: vg.BRDF(eta="gold"), r"eta = 'gold' must be a number"),
        (lambda: vg.BRDF(eta=0.2 + 3j, dim="flatland"), r"eta applies to dim 3d only"),
        (lambda: f.eval(wi, [0.5, 0, 0.5]), r"wo\[0\] = \(0.5, 0, 0.5\) is not a unit vector \(\|len - 1\| <= 1e-06\)"),
        (lambda: f.eval(wi, [1.0, 0.0]), r"wo must be an array of unit vectors, shape \(\.\.\., 3\); got \(2,\)"),
        (lambda: f.eval(wi, wo, threads=-1), r"threads = -1 is out of range \[0, 1024\]"),
        (lambda: f.eval(wi, wo, progress="bar"), r"progress = 'bar' must be a callable progress\(done, total\)"),
        (lambda: f.sample(wi, [[0.5, 0.5, 0.5, 1.0]]), r"u\[0\]\[3\] = 1 is out of range \[0, 1\)"),
        (lambda: f.sample(wi, [[0.5] * 5]), r"u must be an array of uniform numbers, shape \(\.\.\., 4\)"),
        (lambda: f.sample(vg.direction(89.95, 180), vg.uniforms(1)), r"wi\[0\] = .* is 89.95 deg from the normal, "
                                                                      r"out of range \[0, 89.9\]"),
        (lambda: f.sample(wi, vg.uniforms(1), strategy="smith"), r'strategy = "smith" is not one of'),
        (lambda: vg.BRDF(max_k=200000).sample(wi, vg.uniforms(1)), r"max_k = 200000 is out of range \[1, 100000\]"),
        (lambda: vg.BRDF("cook-torrance").sample(wi, vg.uniforms(1)), r'sample: model = "cook-torrance" has no sampler'),
        (lambda: vg.BRDF("cook-torrance").pdf(wi, wo), r'pdf: model = "cook-torrance" has no sampler'),
        (lambda: f.pdf(wi, wo, tolerance="x"), r"tolerance = 'x' must be a real number"),
        (lambda: f.lobe(95.0), r"theta_i_deg = 95 is out of range \[0, 89.9\]"),
        (lambda: f.lobe(89.95), r"theta_i_deg = 89.95 is out of range \[0, 89.9\]"),
        (lambda: vg.BRDF(dim="flatland").lobe(-89.95), r"theta_i_deg = -89.95 is out of range \[-89.9, 89.9\]"),
        (lambda: f.trace(89.95, rays=10, grooves=10), r"theta_i_deg = 89.95 is out of range \[0, 89.9\]"),
        (lambda: f.lobe(30, k_rows=2000), r"k_rows = 2000 is out of range \[0, 1000\]"),
        (lambda: f.lobe(30, phi_bins=3), r"phi_bins = 3 is out of range \[2, 10000\], even"),
        (lambda: vg.BRDF(max_k=5000).lobe(30), r"lobe: max_k = 5000 is out of range \[1, 1000\]"),
        (lambda: vg.BRDF("vgroove-nonsymmetric").lobe(30), r'lobe: model = "vgroove-nonsymmetric" is not binned'),
        (lambda: vg.BRDF(eta=2j + 1).albedo(wi), r"albedo: eta = \(1\+2j\): lobes, albedos and traces"),
        (lambda: f.albedo(vg.direction(90, 0)), r"wi\[0\] = .* is 90 deg from the normal, out of range \[0, 89.9\]"),
        (lambda: f.albedo(vg.direction(89.95, 0)), r"wi\[0\] = .* is 89.95 deg from the normal, out of range \[0, 89.9\]"),
        (lambda: f.albedo([0, 0, 2.0]), r"wi\[0\] = \(0.0, 0.0, 2.0\) is not a unit vector"),
        (lambda: f.trace(30, rays=0), r"rays = 0 is out of range \[1, 1000000000\]"),
        (lambda: f.trace(30, grooves=0), r"grooves = 0 is out of range \[1, 10000000\]"),
        (lambda: f.trace(30, 10, seed=-1), r"seed = -1 is out of range \[0, 9223372036854775807\]"),
        (lambda: vg.validate({"name": "x"}), r"suite: "),
        (lambda: vg.validate({"rays": float("nan")}), r"suite is not JSON: Out of range float values"),
        (lambda: vg.validate(3), r"suite = 3 must be a suite file's path or a suite \(dict\)"),
    ]


def test_bad_input_to_every_new_entry_point_is_one_value_error_line(vg):
    for call, message in brdf_errors(vg):
        with pytest.raises(ValueError) as e:
            call()
        text = str(e.value)
        assert "\n" not in text, text
        assert __import__("re").search("^" + message, text), (message, text)


def test_validate_takes_a_dict(vg, suites, reports, tmp_path, monkeypatch):
    for kind in ("table1", "brdf", "sampling"):
        with open(suites[kind]) as f:
            suite = json.load(f)
        ours = vg.validate(suite, threads=2)
        with open(reports[kind]) as f:
            theirs = json.load(f)
        ours["threads"] = theirs["threads"]
        # The report names the suite's file; a dict's name is "suite".
        assert ours.pop("suite_file", "suite") == "suite"
        theirs.pop("suite_file", None)
        from conftest import strip_timing
        assert strip_timing(ours) == strip_timing(theirs), kind
    # A set names its suites relative to the current directory.
    with open(suites["table1_set"]) as f:
        suite = json.load(f)
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError, match=r"tiny_table1.json"):
        vg.validate(suite)
    monkeypatch.chdir(suites["table1_set"].rsplit("/", 1)[0])
    assert vg.validate(suite)["pass"] == vg.validate(suites["table1_set"])["pass"]
    # The message names the dict "suite" and the JSON path, as the command line names the file.
    bad = dict(json.load(open(suites["table1"])), rays=0)
    path = write_json(tmp_path / "bad.json", bad)
    expected = cli("validate", path, check=False).stderr.strip()
    with pytest.raises(ValueError) as e:
        vg.validate(bad)
    assert "vgroove: error: " + str(e.value).replace("suite: ", path + ": ") == expected


def test_broadcasting_and_shapes(vg):
    f = vg.BRDF("vgroove", "ggx", 0.5)
    grid = vg.direction(np.linspace(0, 89, 12)[:, None], np.linspace(-180, 180, 7)[None, :])
    wi = vg.direction(40, 180)
    v = f.eval(wi, grid)
    assert v.shape == (12, 7)
    # One light for every row (no copy) gives the bits of the light repeated.
    assert np.array_equal(v, f.eval(np.broadcast_to(wi, grid.shape).copy(), grid))
    assert np.array_equal(f.pdf(wi, grid), f.pdf(np.broadcast_to(wi, grid.shape).copy(), grid))
    u = vg.uniforms(60).reshape(3, 20, 4)
    b = f.sample(wi, u)
    assert b.wo.shape == (3, 20, 3) and b.k.shape == (3, 20)
    b2 = f.sample(np.broadcast_to(wi, (3, 20, 3)).copy(), u)
    assert all(np.array_equal(getattr(b, k), getattr(b2, k)) for k in ("wo", "k", "pdf", "weight"))
    assert f.albedo(np.broadcast_to(wi, (4, 2, 3))).shape == (4, 2)
    assert math.isclose(float(f.eval(wi, wi * [-1, -1, 1])), float(f.eval(wi * [-1, -1, 1], wi)), rel_tol=1e-12)
