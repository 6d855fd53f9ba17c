"""vgroove.check_brdf(..., surface="heightfield"): a BRDF held against random heightfields traced in
3D (validation/check_brdf.h), from a Python callable as from a built-in model; Smith's single
scattering matches the smooth Beckmann field's shape at normal incidence and misses only its small
multiple scattering (the albedo), which scaling to albedo 1 restores; bad input is named per
argument, an oversized field refused before any work."""

import numpy as np
import pytest
from conftest import strip_timing

HF = dict(surface="heightfield", field_size=64, correlation_length=4, fields=4, rays=20000, theta_bins=9,
          phi_bins=8)


def smith_beckmann(alpha, scale=1.0):
    """Cook-Torrance with Smith's height-correlated G for Beckmann, F = 1 (Heitz 2014, Eq. 99)."""
    from math import erf, exp, pi, sqrt

    def lam(cos_t):
        a = cos_t / (alpha * np.sqrt(np.maximum(1.0 - cos_t * cos_t, 1e-300)))
        return np.array([0.0 if x > 1e8 else (erf(x) - 1.0) / 2.0 + exp(-x * x) / (2.0 * x * sqrt(pi)) for x in a])

    def f(wi, wo):
        h = wi + wo
        h /= np.linalg.norm(h, axis=1)[:, None]
        c2 = h[:, 2] ** 2
        d = np.exp(-(1.0 - c2) / (c2 * alpha * alpha)) / (np.pi * alpha * alpha * c2 * c2)
        g2 = 1.0 / (1.0 + lam(wi[:, 2]) + lam(wo[:, 2]))
        return scale * d * g2 / (4.0 * wi[:, 2] * wo[:, 2])

    return f


def test_smith_on_a_smooth_beckmann_field(vg):
    raw = vg.check_brdf(smith_beckmann(0.3), "beckmann", 0.3, [0], threads=2, **HF)
    assert raw["inputs"]["surface"] == "heightfield" and raw["inputs"]["heightfield"]["fields"] == 4
    c = raw["cases"][0]
    assert c["rays"] == 20000 and c["albedo_sim"] == pytest.approx(1.0, abs=1e-15)
    assert c["l1"] <= c["l1_threshold"]  # the shape is the field's
    assert abs(c["albedo_sim"] - c["albedo_model"]) > c["albedo_threshold"] and not raw["pass"]  # 0.03% short
    scaled = vg.check_brdf(smith_beckmann(0.3, 1.0 / c["albedo_model"]), "beckmann", 0.3, [0], threads=2, **HF)
    assert scaled["pass"], scaled["cases"]
    dim = vg.check_brdf(smith_beckmann(0.3, 0.98 / c["albedo_model"]), "beckmann", 0.3, [0], threads=2, **HF)
    assert not dim["pass"]


def test_a_callable_and_a_built_in_model_give_one_report(vg):
    ours = vg.check_brdf(lambda wi, wo: vg.brdf("cook-torrance", "ggx", 0.5, wi, wo), "ggx", 0.5, [0, 50], threads=2,
                         **dict(HF, rays=6000))
    cpp = vg.check_brdf("cook-torrance", "ggx", 0.5, [0, 50], threads=1, **dict(HF, rays=6000))
    assert {**strip_timing(ours), "threads": 0} == {**strip_timing(cpp), "threads": 0}
    # The V-groove surface is another surface: other traced figures.
    groove = vg.check_brdf("cook-torrance", "ggx", 0.5, [0, 50], threads=1, rays=6000, grooves=5000, theta_bins=9,
                           phi_bins=8)
    assert groove["inputs"]["surface"] == "vgroove"
    assert groove["cases"][1]["l1"] != cpp["cases"][1]["l1"]


def test_bad_input_is_named(vg):
    f = smith_beckmann(0.3)
    with pytest.raises(ValueError, match=r'^surface = "hf" is not one of "vgroove", "heightfield"$'):
        vg.check_brdf(f, "beckmann", 0.3, [0], **dict(HF, surface="hf"))
    with pytest.raises(ValueError, match=r"^field_size = 100 is out of range \[16, 65536\], a power of two$"):
        vg.check_brdf(f, "beckmann", 0.3, [0], **dict(HF, field_size=100))
    with pytest.raises(ValueError, match=r"^fields = 1 is out of range"):
        vg.check_brdf(f, "beckmann", 0.3, [0], **dict(HF, fields=1))
    with pytest.raises(ValueError, match=r"^ndf = phong: surface heightfield takes beckmann or ggx"):
        vg.check_brdf(f, "phong", 0.3, [0], **HF)
    with pytest.raises(ValueError, match=r"^field_size = 65536 needs 126.0 GB with its hierarchy, more than"):
        vg.check_brdf(f, "beckmann", 0.3, [0], **dict(HF, field_size=65536, correlation_length=8))


def test_the_heightfield_suite_from_python_reports_and_plots(vg, tmp_path):
    """vgroove.validate on a suite of kind "heightfield", and `vgroove plot` of its report."""
    import json
    import subprocess

    from conftest import BIN, SOURCE
    suite = json.load(open(f"{SOURCE}/data/suites/heightfield.json"))
    suite.update(ndf=["beckmann"], alpha=[0.3], theta_i_deg=[0, 60], field_size=64, correlation_length=4, fields=2,
                 rays=2000, walk_paths=5000)
    # The masking controls of the cases kept (a control must name a case of the suite).
    suite["masking"]["controls"] = [c for c in suite["masking"]["controls"]
                                    if c["ndf"] == "beckmann" and c["alpha"] == 0.3 and c["theta_i_deg"] in (0, 60)]
    r = vg.validate(suite, threads=2)
    assert r["kind"] == "heightfield" and r["pass"] and len(r["cases"]) == 2
    assert [c["within_noise"] for c in r["controls"]] == [True, True]
    path = tmp_path / "hf.json"
    path.write_text(json.dumps(r))
    out = subprocess.run([BIN, "plot", str(path), "--out", str(tmp_path / "hf.png")], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert (tmp_path / "hf-beckmann.png").stat().st_size > 10000
    big = dict(suite, field_size=65536)
    with pytest.raises(ValueError, match=r"/field_size = 65536 needs 126.0 GB with its hierarchy"):
        vg.validate(big, threads=1)
