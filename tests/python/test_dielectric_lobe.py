"""dielectric_lobe from Python: the kaleidoscopic dielectric model's binned lobe
(analytic/kaleidoscope_dielectric_lobe.h), the same numbers to the last bit as `vgroove brdf
--model vgroove-dielectric --json` (the command line and the module call one library function);
the light all accounted for (albedo_r + albedo_t + shadow_or_unknown = 1, bins and orders summing
to their totals); eta = 1 transmitting everything straight on, into the incident direction's bin;
bad input refused with the command line's range, naming the argument."""

import math
import re

import numpy as np
import pytest

from conftest import cli_error, cli_json


def lobe_cli(*args):
    return cli_json("brdf", "--model", "vgroove-dielectric", "--json", *args)


@pytest.mark.parametrize("dim, eta, theta_i_deg", [("flatland", 1 / 1.5, -40.0), ("flatland", 2.4, 75.0),
                                                    ("3d", 1.5, 50.0)])
def test_the_command_lines_numbers_bit_for_bit(vg, dim, eta, theta_i_deg):
    # The default bins are the command line's (90 flatland; 18 x 24 in 3D); per_k=3 is --per-k-max 3.
    L = vg.dielectric_lobe("beckmann", 0.4, eta, theta_i_deg, per_k=3, dim=dim)
    j = lobe_cli("--ndf", "beckmann", "--alpha", "0.4", "--eta", repr(eta), "--theta-i-deg", repr(theta_i_deg),
                 "--dim", dim, "--per-k", "--per-k-max", "3")
    assert j["inputs"]["eta"] == eta
    shape = (90,) if dim == "flatland" else (18, 24)
    for side in ("reflected", "transmitted"):
        assert L[side].shape == shape
        assert L[side].ravel().tolist() == j[side], side
        assert L[side + "_by_k"].shape == (5,) + shape
        assert L[side + "_by_k"].reshape(5, -1).tolist() == j[side + "_by_k"], side
    for key in ("albedo_r", "albedo_t", "shadow_or_unknown", "upward", "unresolved", "error_estimate"):
        assert L[key] == j[key], key
    # Broken variant: the next double of eta changes some bit (the comparison is not vacuous; in
    # flatland only: the command line's 3D bins cost 0.75 s a run).
    if dim == "flatland":
        other = vg.dielectric_lobe("beckmann", 0.4, math.nextafter(eta, 2 * eta), theta_i_deg, per_k=3, dim=dim)
        assert other["transmitted"].ravel().tolist() != j["transmitted"]


def test_flatland_bin_edges_are_the_command_lines(vg):
    L = vg.dielectric_lobe("ggx", 0.5, 1.5, 10, dim="flatland", flatland_bins=6)
    assert L["theta_edges_deg"].tolist() == [-90, -60, -30, 0, 30, 60, 90]
    assert "phi_edges_deg" not in L and L["reflected"].shape == (6,)


@pytest.mark.parametrize("ndf, alpha, eta, theta_i_deg", [("ggx", 0.3, 1.5, 30.0), ("beckmann", 0.8, 1 / 1.5, -60.0),
                                                          ("ggx", 0.1, 1 / 2.4, 10.0), ("phong", 1.0, 2.4, 80.0)])
def test_energy_is_conserved(vg, ndf, alpha, eta, theta_i_deg):
    # Per facet R + T = 1 (KD-2) and the lit widths make the opening: the lobes, the lobes travelling
    # back up and the grooves beyond k_cap hold all the light, to the quadrature error of the
    # density (the library's test: 1e-9). Each side's bins sum to its albedo, each bin's rows to it.
    L = vg.dielectric_lobe(ndf, alpha, eta, theta_i_deg, per_k=4, dim="flatland", flatland_bins=30)
    total = L["albedo_r"] + L["albedo_t"] + L["shadow_or_unknown"]
    assert abs(total - 1) < 1e-9, total
    assert L["upward"] + L["unresolved"] <= L["shadow_or_unknown"] + 1e-15
    for side, albedo in (("reflected", "albedo_r"), ("transmitted", "albedo_t")):
        assert (L[side] >= 0).all()
        assert abs(L[side].sum() - L[albedo]) < 1e-12, side
        np.testing.assert_allclose(L[side + "_by_k"].sum(axis=0), L[side], rtol=1e-12, atol=1e-15)


def test_energy_is_conserved_in_3d_and_its_broken_variant_is_not(vg):
    # 3D once, small bins: from inside glass at 70 deg (all-TIR azimuths). Broken variant: without
    # the flux that is not binned (here 0.06, mostly lobes travelling back up) the sum misses 1.
    L = vg.dielectric_lobe("beckmann", 0.5, 1 / 1.5, 70, theta_bins=6, phi_bins=4)
    assert L["reflected"].shape == L["transmitted"].shape == (6, 4)
    assert L["theta_edges_deg"].tolist() == [0, 15, 30, 45, 60, 75, 90]
    assert L["phi_edges_deg"].tolist() == [-45, 45, 135, 225, 315]  # the command line's phi_lo, phi_hi
    assert abs(L["albedo_r"] + L["albedo_t"] + L["shadow_or_unknown"] - 1) < 1e-9
    assert abs(L["reflected"].sum() - L["albedo_r"]) < 1e-12
    assert abs(L["transmitted"].sum() - L["albedo_t"]) < 1e-12
    assert abs(L["albedo_r"] + L["albedo_t"] - 1) > 1e-6


@pytest.mark.parametrize("theta_i_deg", [-40.0, 0.5, 33.0])
def test_eta_one_goes_straight_through_in_flatland(vg, theta_i_deg):
    # eta = 1: F = 0 at every hit and refraction unbent (KD-3): everything passes at the first hit
    # along theta_i, into the incident direction's bin (signed angles from the exit side's normal:
    # bin floor((theta_i + 90) / 4) of 45), all at k = 1; only grooves beyond k_cap are not binned.
    L = vg.dielectric_lobe("ggx", 0.5, 1.0, theta_i_deg, per_k=4, dim="flatland", flatland_bins=45)
    b = int((theta_i_deg + 90) // 4)
    assert L["albedo_r"] == 0 and not L["reflected"].any()
    assert abs(L["transmitted_by_k"][1][b] + L["unresolved"] - 1) < 1e-12
    assert abs(L["transmitted"][b] - L["albedo_t"]) < 1e-15
    assert L["upward"] == 0
    # Broken variant: a slightly bent interface spreads the light out of that bin and reflects some.
    bent = vg.dielectric_lobe("ggx", 0.5, 1.05, theta_i_deg, dim="flatland", flatland_bins=45)
    assert bent["albedo_r"] > 1e-4 and bent["albedo_t"] - bent["transmitted"][b] > 1e-3


def test_eta_one_goes_straight_through_in_3d(vg):
    # theta_i 35 deg: theta bin 3 of 9 (10 deg each), phi bin 0 (the light is at phi 180).
    L = vg.dielectric_lobe("ggx", 0.3, 1.0, 35, theta_bins=9, phi_bins=8)
    assert L["albedo_r"] == 0
    assert abs(L["transmitted"][3, 0] + L["unresolved"] - 1) < 1e-12


# The same input refused by the command line and the module: the module names the argument where
# the command line names the flag, and states the same range.
@pytest.mark.parametrize("kwargs, flags, message", [
    (dict(eta=0), ["--eta", "0"], "eta = 0 is out of range (0, 1000]"),
    (dict(eta=-1.5), ["--eta", "-1.5"], "eta = -1.5 is out of range (0, 1000]"),
    (dict(eta=1001), ["--eta", "1001"], "eta = 1001 is out of range (0, 1000]"),
    (dict(alpha=0), ["--alpha", "0"], "alpha = 0 is out of range [0.01, 2]"),
    (dict(theta_i_deg=90), ["--theta-i-deg", "90"], "theta_i_deg = 90 is out of range [0, 90)"),
    (dict(theta_i_deg=-10), ["--theta-i-deg", "-10"], "theta_i_deg = -10 is out of range [0, 90)"),
    (dict(theta_i_deg=-90, dim="flatland"), ["--theta-i-deg", "-90", "--dim", "flatland"],
     "theta_i_deg = -90 is out of range (-90, 90)"),
    (dict(ndf="cauchy"), ["--ndf", "cauchy"], 'ndf = "cauchy" is not one of'),
    (dict(dim="2d"), ["--dim", "2d"], 'dim = "2d" is not one of "3d", "flatland"'),
])
def test_bad_input_is_the_command_lines(vg, kwargs, flags, message):
    args = dict(ndf="ggx", alpha=0.5, eta=1.5, theta_i_deg=30.0)
    args.update(kwargs)
    with pytest.raises(ValueError) as e:
        vg.dielectric_lobe(args.pop("ndf"), args.pop("alpha"), args.pop("eta"), args.pop("theta_i_deg"), **args)
    assert str(e.value).startswith(message), str(e.value)
    name = message.split(" = ")[0]
    cli_message = cli_error("brdf", "--model", "vgroove-dielectric", *flags)
    assert cli_message.startswith("--" + name.replace("_", "-") + message[len(name):]), cli_message


@pytest.mark.parametrize("kwargs, message", [
    # NaN: the command line refuses the text ('--eta = "nan" is not a number'), the module the value.
    (dict(eta=float("nan")), "eta = nan is out of range (0, 1000]"),
    (dict(alpha=float("nan")), "alpha = nan is out of range [0.01, 2]"),
    (dict(theta_i_deg=float("nan")), "theta_i_deg = nan is out of range [0, 90)"),
    (dict(eta=float("inf")), "eta = inf is out of range (0, 1000]"),
    (dict(per_k=-1), "per_k = -1 is out of range [0, 1000]"),
    (dict(per_k=1001), "per_k = 1001 is out of range [0, 1000]"),
    (dict(per_k=2.0), "per_k = 2.0 must be an integer"),
    (dict(flatland_bins=0, dim="flatland"), "flatland_bins = 0 is out of range [1, 100000]"),
    (dict(theta_bins=0), "theta_bins = 0 is out of range [1, 10000]"),
    (dict(phi_bins=7), "phi_bins = 7 must be even"),
    (dict(phi_bins=0), "phi_bins = 0 is out of range [1, 10000]"),
    (dict(eta=1.5 + 0.1j), "eta = (1.5+0.1j) must be a real number"),
    (dict(eta="1.5"), "eta = '1.5' must be a real number"),
])
def test_bad_input_names_the_argument(vg, kwargs, message):
    args = dict(ndf="ggx", alpha=0.5, eta=1.5, theta_i_deg=30.0)
    args.update(kwargs)
    with pytest.raises(ValueError, match="^" + re.escape(message)):
        vg.dielectric_lobe(args.pop("ndf"), args.pop("alpha"), args.pop("eta"), args.pop("theta_i_deg"), **args)


def test_progress_reports_the_end(vg):
    calls = []
    vg.dielectric_lobe("ggx", 0.5, 1.5, 10, dim="flatland", flatland_bins=6, progress=lambda d, t: calls.append((d, t)))
    assert calls and calls[-1] == (1, 1), calls
    with pytest.raises(ValueError, match="^progress = 3 must be a callable"):
        vg.dielectric_lobe("ggx", 0.5, 1.5, 10, dim="flatland", progress=3)
