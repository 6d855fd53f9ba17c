"""check_brdf from Python: a vectorized callable gives the C++ API's report (same nodes, sums,
verdict); vgroove's own BRDF passes, Cook-Torrance fails at alpha = 1 (it loses the multiply
scattered light); errors in the callable surface as themselves."""

import re

import numpy as np
import pytest

SMALL = dict(rays=20000, grooves=20000)
# vgroove's 3D albedo reaches 1 at high roughness only with a large bounce limit (its single pass
# costs the same for any max_k); flatland is kept to 64 orders, as check_brdf_test.cpp does.
MAX_K = 10**6
MAX_K_FLATLAND = 64


def strip(report):
    return {k: ([{a: b for a, b in c.items() if "wall" not in a} for c in v] if k == "cases" else v)
            for k, v in report.items() if k not in ("wall_s", "threads")}


@pytest.mark.parametrize("dim", ["3d", "flatland"])
def test_callable_gives_the_cpp_report(vg, dim):
    def f(wi, wo):
        assert wi.shape == wo.shape and wi.shape[1] == 3 and wi.dtype == np.float64
        return vg.brdf("vgroove", "ggx", 1.0, wi, wo, max_k=max_k, dim=dim)

    max_k = MAX_K if dim == "3d" else MAX_K_FLATLAND
    ours = vg.check_brdf(f, "ggx", 1.0, [0, 40], dim=dim, threads=2, **SMALL)
    cpp = vg.check_brdf("vgroove", "ggx", 1.0, [0, 40], dim=dim, threads=1, max_k=max_k, **SMALL)
    assert strip(ours) == strip(cpp)
    assert ours["kind"] == "check_brdf" and len(ours["cases"]) == 2


def test_vgroove_passes_and_cook_torrance_fails_at_alpha_1(vg):
    vgroove = vg.check_brdf(lambda wi, wo: vg.brdf("vgroove", "ggx", 1.0, wi, wo, max_k=MAX_K), "ggx", 1.0, [0],
                            **SMALL)
    assert vgroove["pass"], vgroove["cases"]
    ct = vg.check_brdf(lambda wi, wo: vg.brdf("cook_torrance", "ggx", 1.0, wi, wo), "ggx", 1.0, [0], **SMALL)
    assert not ct["pass"]
    c = ct["cases"][0]
    # It fails on energy: the traced albedo is 1, Cook-Torrance's (V-cavity G) about 0.375 here.
    assert c["albedo_sim"] == pytest.approx(1.0, abs=1e-12)
    assert c["albedo_model"] < 0.4 and abs(c["albedo_sim"] - c["albedo_model"]) > 10 * c["albedo_threshold"]


def test_vgroove_passes_at_oblique_incidence(vg):
    r = vg.check_brdf(lambda wi, wo: vg.brdf("vgroove", "ggx", 1.0, wi, wo, max_k=MAX_K), "ggx", 1.0, [40, 80],
                      **SMALL)
    assert r["pass"], [(c["albedo_sim"], c["albedo_model"], c["albedo_threshold"]) for c in r["cases"]]


def test_threads_do_not_change_the_report(vg):
    f = lambda wi, wo: vg.brdf("cook_torrance", "beckmann", 0.4, wi, wo)  # noqa: E731
    a = vg.check_brdf(f, "beckmann", 0.4, [10, 50], threads=1, rays=5000, grooves=3000)
    b = vg.check_brdf(f, "beckmann", 0.4, [10, 50], threads=3, rays=5000, grooves=3000)
    assert strip(a) == strip(b) and a["threads"] == 1 and b["threads"] == 3


def test_errors_in_the_callable(vg):
    with pytest.raises(ZeroDivisionError):
        vg.check_brdf(lambda wi, wo: 1 / 0, rays=1000, grooves=100)
    with pytest.raises(ValueError, match=r"^f returned an array of shape \(3,\) for 16 directions"):
        vg.check_brdf(lambda wi, wo: np.zeros(3), rays=1000, grooves=100, theta_i_deg=[0])
    with pytest.raises(ValueError, match=r"^f returned a str for 16 directions"):
        vg.check_brdf(lambda wi, wo: "x", rays=1000, grooves=100, theta_i_deg=[0])
    with pytest.raises(ValueError, match=r"^theta_i_deg = 90 is out of range \[0, 89.9\]$"):
        vg.check_brdf(lambda wi, wo: np.zeros(len(wi)), theta_i_deg=[0, 90], rays=10, grooves=10)
    with pytest.raises(ValueError, match=r"^theta_i_deg = 89.95 is out of range \[0, 89.9\]$"):
        vg.check_brdf(lambda wi, wo: np.zeros(len(wi)), theta_i_deg=[89.95], rays=10, grooves=10)
    with pytest.raises(ValueError, match=r"^f = 3 must be a callable"):
        vg.check_brdf(3, rays=10, grooves=10)
    # A value that is not a BRDF's (NaN, an infinity, a negative number) is a ValueError at the first
    # call that returns it, naming it and its directions (validation/check_brdf.h); it was a failed
    # case reported after the first rule over every bin (3,600 calls). -0 is 0.
    for bad, text in ((np.nan, "nan"), (-1.0, "-1"), (np.inf, "inf"), (-np.inf, "-inf")):
        calls = []

        def f(wi, wo):
            calls.append(len(wi))
            return np.full(len(wi), bad)
        with pytest.raises(ValueError, match=r"^f\(wi, wo\) = " + re.escape(text) + r" at wi = \(-0, 0, 1\), "
                           r"wo = \([^)]*\) \(theta_i_deg 0\): a BRDF's values must be finite and >= 0$"):
            vg.check_brdf(f, rays=1000, grooves=100, theta_i_deg=[0])
        assert calls == [16], calls
    r = vg.check_brdf(lambda wi, wo: np.full(len(wi), -0.0), rays=1000, grooves=100, theta_i_deg=[0])
    assert not r["pass"] and not r["cases"][0]["non_finite"]


@pytest.mark.parametrize("f", [
    # A Python callable: f is not called again once the flag is set (python/src/brdfs.cpp).
    "lambda wi, wo: vgroove.brdf('vgroove', 'ggx', 0.5, wi, wo)",
    # A built-in model in C++ (flatland at max_k 1024: ~70 ms a direction, 0.3 s a bin's first
    # rule): the flag read before each bin's first rule (validation/check_brdf.cpp).
    "'vgroove'",
])
def test_ctrl_c_stops_a_check_with_a_callback_within_a_second(vg, f):
    # 300 x 300 bins (or 100000 flatland bins: the flatland sum's single pass takes a few us a pair,
    # 1000 bins were done within the delay): the first rule alone evaluates f on every bin of every
    # angle (tens of seconds in all) before any refinement.
    from conftest import interrupted_after
    dim = "dim='flatland', flatland_bins=100000, max_k=1024" if f == "'vgroove'" else "theta_bins=300, phi_bins=300"
    out, seconds = interrupted_after(f"vgroove.check_brdf({f}, 'ggx', 0.5, [0, 40], rays=10**5, grooves=10**4, "
                                     f"{dim}, threads=2)", delay=0.5)
    assert out == "interrupted"
    assert seconds < 1.5, seconds


# check_brdf with eta: a BSDF against the dielectric V-groove surface (validation/check_bsdf.h).
GLASS = dict(rays=20000, grooves=20000, theta_bins=6, phi_bins=4)


def test_a_bsdf_is_called_below_the_surface_and_reported_per_lobe(vg):
    seen = []

    def walter(wi, wo):
        seen.append(wo[:, 2].min())
        return vg.brdf("walter", "ggx", 0.5, wi, wo, eta=1.5, masking="smith")

    r = vg.check_brdf(walter, "ggx", 0.5, [30], eta=1.5, threads=2, **GLASS)
    assert min(seen) < -0.9  # wo below: the transmitted hemisphere
    assert r["inputs"]["eta"] == 1.5 and r["inputs"]["side"] == "above"
    c = r["cases"][0]
    assert [s["lobe"] for s in c["lobes"]] == ["reflected", "transmitted"]
    R, T = (s["albedo_sim"] for s in c["lobes"])
    assert R + T == pytest.approx(1.0, abs=1e-12) and 0.02 < R < 0.06  # about Fresnel's 0.04 (0.032 measured)
    assert c["pass"] == (r["pass"]) == all(s["pass"] for s in c["lobes"]) and c["pass"] is not None
    # The same light seen from inside the glass (eta inverted): total internal reflection, it fails.
    bad = vg.check_brdf(lambda wi, wo: vg.brdf("walter", "ggx", 0.5, wi, wo, eta=1 / 1.5), "ggx", 0.5, [30],
                        eta=1.5, **GLASS)
    assert not bad["pass"] and not any(s["pass"] for s in bad["cases"][0]["lobes"])
    # The conductor check's report has no eta, side or lobes.
    plain = vg.check_brdf(lambda wi, wo: np.zeros(len(wi)), "ggx", 0.5, [30], **GLASS)
    assert "eta" not in plain["inputs"] and "lobes" not in plain["cases"][0]


def test_bad_eta_and_side_are_named(vg):
    f = lambda wi, wo: np.zeros(len(wi))  # noqa: E731
    for eta, text in ((-1, "-1"), (0.05, "0.05"), (1, "1"), (float("nan"), "nan"), (11, "11"), (0, "0")):
        with pytest.raises(ValueError, match=r"^eta = " + re.escape(text) +
                           r" is out of range \[0.1, 10\], not 1 \((0|None): the conductor check\)$"):
            vg.check_brdf(f, eta=eta, rays=10, grooves=10)
    with pytest.raises(ValueError, match=r'^side = "sideways" is not one of "above", "below"$'):
        vg.check_brdf(f, eta=1.5, side="sideways", rays=10, grooves=10)
    with pytest.raises(ValueError, match=r"^surface = heightfield: with eta the traced surface is the dielectric"):
        vg.check_brdf(f, eta=1.5, surface="heightfield", rays=10, grooves=10)
    with pytest.raises(ValueError, match=r"^f\(wi, wo\) = nan at wi = \(-0\.4999[0-9]*, [^,]+, -0\.866[0-9]*\), wo = \([^)]+, -[0-9.]+\) "
                       r"\(theta_i_deg 30\): a BSDF's values must be finite and >= 0$"):
        vg.check_brdf(lambda wi, wo: np.where(wo[:, 2] < 0, np.nan, 0.1), theta_i_deg=[30], eta=1.5, side="below", rays=10,
                      grooves=10)


def test_a_bsdf_report_draws_both_lobes(vg, tmp_path):
    import json
    from vgroove import plot
    r = vg.check_brdf(lambda wi, wo: vg.brdf("walter", "ggx", 0.3, wi, wo, eta=1.5), "ggx", 0.3, [0, 40], eta=1.5,
                      **GLASS)
    path = tmp_path / "bsdf.json"
    path.write_text(json.dumps(r))
    assert plot.main([str(path), "--out", str(tmp_path / "bsdf")]) == 0
    assert (tmp_path / "bsdf.png").stat().st_size > 0
    # One figure, a series per lobe beside both as one (python/vgroove/plot.py check_brdf_figures).
    (suffix, draw), = plot.figures_for(r, str(path))
    fig = draw()
    labels = [t.get_text() for ax in fig.axes if ax.get_legend() for t in ax.get_legend().get_texts()]
    for lobe in ("R + T", "reflected", "transmitted"):
        assert any(f"({lobe})" in t for t in labels), labels
    assert "eta 1.5 from above" in fig._suptitle.get_text()
