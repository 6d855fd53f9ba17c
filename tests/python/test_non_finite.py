"""Numbers that are not finite (docs/conventions.md): the command line's JSON and the Python
module's report dicts write them as the strings "nan", "inf", "-inf", never null or None; a
sampling strategy of zero variance has the efficiency "inf" in both (timing, apart from the
compared fields)."""

import json

import pytest

from conftest import cli, cli_json, write_json

SAMPLING = {
    "name": "zero_variance", "kind": "sampling", "seed": 1, "max_k": 64,
    "chi_square": {"level": 0.01, "samples": {"3d": 2000, "flatland": 2000}, "cos_bins": 4, "phi_bins": 8,
                   "theta_bins": 18, "cases": [{"dimension": "flatland", "ndf": "ggx", "alpha": 0.5,
                                                "theta_i_deg": 30, "strategy": "vndf"}]},
    "variance": {"samples": 2000, "schlick_f0": [1.0],
                 "cases": [{"dimension": "flatland", "ndf": "ggx", "alpha": 0.5, "theta_i_deg": 30}]},
    "furnace": {"max_k": 16, "samples": 500, "strategy": "vndf", "rays": 500, "grooves": 500, "sigmas": 5,
                "quadrature_tolerance": {"flatland": 1e-9, "3d": 1e-5},
                "cases": [{"dimension": "flatland", "ndf": "ggx", "alpha": 0.5, "theta_i_deg": 30}]},
}


def efficiencies(report):
    return {s["strategy"]: s["efficiency"] for s in report["variance"][0]["timing"]["strategies"]}


def test_the_command_line_writes_inf_as_a_string(tmp_path):
    out = tmp_path / "r.json"
    cli("validate", write_json(tmp_path / "s.json", SAMPLING), "--out", out, "--threads", 1)
    text = out.read_text()
    assert "null" not in text
    # The V-cavity strategy (vndf) samples the flatland BRDF exactly: weight 1, variance 0.
    assert efficiencies(json.loads(text))["vndf"] == "inf"
    p = cli_json("brdf", "--json", "--per-k", "--per-k-max", 2, "--theta-i-deg", 0, "--theta-o-deg", 0)["points"][0]
    assert p["by_k"][1] == "inf" and float(p["by_k"][1]) == float("inf")


def test_the_module_writes_the_same_strings(vg, tmp_path):
    r = vg.validate(write_json(tmp_path / "s.json", SAMPLING), threads=1)
    assert efficiencies(r)["vndf"] == "inf"
    assert all(isinstance(v, (float, str)) and v is not None for v in efficiencies(r).values())
