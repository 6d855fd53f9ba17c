"""energy_lobe_shape from Python: the same rows as `vgroove energy --lobe-shape --out` (the
command line and the module call one library function), the controls within noise, and bad input
refused with the command line's message naming the argument."""

import json
import os
import subprocess

import pytest


def rows_without_timing(report):
    return [{k: v for k, v in r.items() if k != "sim_thread_s"} for r in report["rows"]]


def test_rows_are_the_command_lines(vg, tmp_path):
    r = vg.energy_lobe_shape(alpha=[0.5], theta_i_deg=[0], rays=20000, grooves=100000, threads=2)
    assert r["controls_pass"]
    out = tmp_path / "lobes.json"
    subprocess.run([os.environ["VGROOVE_BIN"], "energy", "--lobe-shape", "--alpha", "0.5", "--mu", "1",
                    "--rays", "20000", "--threads", "1", "--out", str(out)], check=True, capture_output=True)
    cli = json.loads(out.read_text())
    # --mu 1 is theta_i = 0 exactly; other threads, the same bits.
    assert rows_without_timing(r) == rows_without_timing(cli)
    # Kulla-Conty's lobe keeps the white furnace; f_ss alone on the walk loses the multiply scattered light.
    by = {(x["reference"], x["lobe"]): x for x in r["rows"]}
    assert by[("smith_walk", "kulla_conty")]["albedo_model"] == pytest.approx(1.0, abs=1e-3)
    assert by[("smith_walk", "single")]["albedo_model"] < 0.8


@pytest.mark.parametrize("kwargs, message", [
    (dict(ndf="phong"), 'ndf = "phong" is not one of "ggx", "beckmann"'),
    (dict(alpha=[0.005]), "alpha = 0.005 is out of range [0.01, 2]"),
    (dict(theta_i_deg=[95]), "theta_i_deg = 95 is out of range [0, 89.9]"),
    (dict(rays=0), "rays = 0 is out of range [1, 1000000000]"),
    (dict(phi_bins=3), "phi_bins = 3 is out of range"),
])
def test_bad_input_names_the_argument(vg, kwargs, message):
    with pytest.raises(ValueError) as e:
        vg.energy_lobe_shape(**kwargs)
    assert message in str(e.value)
