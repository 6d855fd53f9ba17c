"""Rough surfaces and BRDFs from Python: tallies and lobes equal the suites' report; any thread
count gives the same counts; BRDFs over arrays equal their one-at-a-time values."""

import json

import numpy as np
import pytest

from conftest import TINY_BRDF


def test_trace_microsurface_and_lobe_equal_the_report(vg, reports):
    with open(reports["brdf"]) as f:
        report = json.load(f)
    s = TINY_BRDF
    for case in report["cases"]:
        surf = vg.microsurface(case["ndf"], case["alpha"], s["grooves"], s["seed"], dim=case["dimension"])
        t = vg.trace_microsurface(surf, case["theta_i_deg"], s["rays"], flatland_bins=s["flatland_bins"],
                                  theta_bins=s["theta_bins"], phi_bins=s["phi_bins"], max_k=s["max_k"], threads=2)
        assert t["rays"] == case["rays"] and t["escaped"] == case["escaped"] and t["bounces"] == case["bounces"]
        assert t["max_k_seen"] == case["max_k_seen"]
        assert list(t["by_k"] / t["rays"]) == case["by_k_sim"]
        m = vg.lobe("vgroove", case["ndf"], case["alpha"], case["theta_i_deg"], case["dimension"],
                    flatland_bins=s["flatland_bins"], theta_bins=s["theta_bins"], phi_bins=s["phi_bins"],
                    max_k=s["max_k"])
        assert list(m["by_k"]) == case["by_k_model"] and m["albedo"] == case["albedo_model"]
        ct = vg.lobe("cook_torrance", case["ndf"], case["alpha"], case["theta_i_deg"], case["dimension"],
                     flatland_bins=s["flatland_bins"], theta_bins=s["theta_bins"], phi_bins=s["phi_bins"])
        assert ct["albedo"] == case["albedo_cook_torrance"]
        # The plane of incidence of the flatland report: every bin, as a density per radian.
        if case["dimension"] == "flatland":
            width = np.pi / s["flatland_bins"]
            assert list(t["theta_o"] / t["rays"] / width) == case["plane"]["sim"]
            assert list(m["theta_o"] / width) == case["plane"]["model"]


@pytest.mark.parametrize("dim", ["flatland", "3d"])
def test_microsurface_counts_do_not_depend_on_threads(vg, dim):
    surf = vg.microsurface("beckmann", 0.7, 3000, 11, dim=dim)
    runs = [vg.trace_microsurface(surf, 35.0, 100_000, theta_bins=6, phi_bins=4, flatland_bins=12, threads=n)
            for n in (1, 2, 3)]
    for r in runs[1:]:
        for key, v in runs[0].items():
            assert np.array_equal(v, r[key]), key
    again = vg.trace_microsurface(surf, 35.0, 100_000, theta_bins=6, phi_bins=4, flatland_bins=12)
    assert all(np.array_equal(v, again[k]) for k, v in runs[0].items())
    assert surf.theta_m_deg.shape == (3000,) and np.all((surf.theta_m_deg >= 0) & (surf.theta_m_deg < 90))


def _pairs(n, seed, flat=False):
    rng = np.random.default_rng(seed)
    if flat:
        t = rng.uniform(-89.9, 89.9, (2, n))
        return [np.stack([-np.sin(np.radians(a)), np.zeros(n), np.cos(np.radians(a))], -1) for a in t]
    out = []
    for _ in range(2):
        v = rng.normal(size=(n, 3))
        v[:, 2] = np.abs(v[:, 2])
        out.append(v / np.linalg.norm(v, axis=1)[:, None])
    return out


@pytest.mark.parametrize("model", ["vgroove", "cook_torrance"])
@pytest.mark.parametrize("dim", ["3d", "flatland"])
def test_brdf_vectorized_equals_scalar(vg, model, dim):
    wi, wo = _pairs(300, 5, dim == "flatland")
    for ndf, alpha in (("ggx", 0.3), ("beckmann", 1.0), ("phong", 2.0)):
        all_ = vg.brdf(model, ndf, alpha, wi, wo, dim=dim, threads=3)
        one = np.array([vg.brdf(model, ndf, alpha, a, b, dim=dim, threads=1) for a, b in zip(wi, wo)])
        assert np.array_equal(all_, one)
        assert np.all(np.isfinite(all_)) and np.all(all_ >= 0)
        if model == "vgroove":
            per_k = vg.brdf(model, ndf, alpha, wi, wo, per_k=True, max_k=16, dim=dim)
            assert per_k.shape == (300, 16)
            np.testing.assert_allclose(per_k.sum(-1), all_, rtol=1e-12, atol=1e-300)
            assert np.array_equal(per_k[:, 0], vg.brdf("cook_torrance", ndf, alpha, wi, wo, dim=dim)) or \
                np.allclose(per_k[:, 0], vg.brdf("cook_torrance", ndf, alpha, wi, wo, dim=dim), rtol=1e-12)
    # Broadcasting: one wi against a grid of wo.
    grid = vg.direction(np.linspace(0, 89, 12)[:, None], np.linspace(-180, 180, 7)[None, :])
    assert vg.brdf("vgroove", "ggx", 0.5, vg.direction(40, 180), grid).shape == (12, 7)


def test_brdf_hard_cases_are_finite(vg):
    # Grazing directions, the horizon, normal incidence, the mirror direction, alpha at both ends.
    thetas = [0.0, 1e-7, 45.0, 89.9, 89.999999, 90.0]
    wi = vg.direction(np.array(thetas)[:, None], 180.0)
    wo = vg.direction(np.array(thetas)[None, :], 0.0)
    for alpha in (0.01, 0.3, 1.0, 2.0):
        for ndf in ("ggx", "beckmann", "phong"):
            for model in ("vgroove", "cook_torrance"):
                v = vg.brdf(model, ndf, alpha, wi, wo)
                # k >= 2 diverges exactly at the mirror direction (+inf, integrable); never NaN.
                assert not np.any(np.isnan(v)), (model, ndf, alpha)
                off_mirror = ~np.eye(len(thetas), dtype=bool)
                assert np.all(np.isfinite(v[off_mirror])), (model, ndf, alpha)


def test_unit_vector_rule_at_its_boundary(vg):
    # |len - 1| <= 1e-9 is the rule; lengths between the quick pass's bound (0.999e-9) and 1e-9 are
    # decided by the exact check, and the first bad row of a large array is the one named.
    wi = vg.direction(30, 180)
    ok = np.array([0.0, 0.0, 1.0 + 0.9995e-9])
    assert np.isfinite(vg.brdf("vgroove", "ggx", 0.5, wi, ok))
    with pytest.raises(ValueError, match=r"^wo\[0\] = .* is not a unit vector$"):
        vg.brdf("vgroove", "ggx", 0.5, wi, np.array([0.0, 0.0, 1.0 + 1.001e-9]))
    wo = np.tile(vg.direction(20, 0), (100000, 1))
    wo[77777] = [0.0, 0.0, 1.0 - 2e-9]
    with pytest.raises(ValueError, match=r"^wo\[77777\] = .* is not a unit vector$"):
        vg.brdf("vgroove", "ggx", 0.5, wi, wo)


def test_bad_brdf_input(vg):
    wi, wo = vg.direction(30, 180), vg.direction(20, 0)
    with pytest.raises(ValueError, match=r"^wo\[0\] = \(0\.5, 0, 0\.5\) is not a unit vector$"):
        vg.brdf("vgroove", "ggx", 0.5, wi, [0.5, 0, 0.5])
    with pytest.raises(ValueError, match=r"^wi\[0\] = \(nan, 0, 1\) is not a unit vector$"):
        vg.brdf("vgroove", "ggx", 0.5, [np.nan, 0, 1], wo)
    with pytest.raises(ValueError, match=r"^alpha = 0 is out of range \[0.01, 2\]$"):
        vg.brdf("vgroove", "ggx", 0.0, wi, wo)
    with pytest.raises(ValueError, match=r'^ndf = "gxx" is not one of "beckmann", "ggx", "phong"$'):
        vg.brdf("vgroove", "gxx", 0.5, wi, wo)
    with pytest.raises(ValueError, match=r'^model = "ct" is not one of "vgroove", "cook_torrance"$'):
        vg.brdf("ct", "ggx", 0.5, wi, wo)
    with pytest.raises(ValueError, match="not in the plane y = 0"):
        vg.brdf("vgroove", "ggx", 0.5, wi, vg.direction(20, 90), dim="flatland")
    with pytest.raises(ValueError, match=r"shape \(\.\.\., 3\)"):
        vg.brdf("vgroove", "ggx", 0.5, [1.0, 0.0], wo)
    with pytest.raises(ValueError, match=r"^max_k = 0 is out of range"):
        vg.brdf("vgroove", "ggx", 0.5, wi, wo, max_k=0)
    with pytest.raises(ValueError, match=r"^grooves = 0 is out of range \[1, 10000000\]$"):
        vg.microsurface("ggx", 0.5, 0, 1)
    surf = vg.microsurface("ggx", 0.5, 100, 1)
    with pytest.raises(ValueError, match=r"^theta_i_deg = 95 is out of range \[0, 90\)"):
        vg.trace_microsurface(surf, 95.0, 10)
