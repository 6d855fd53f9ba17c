"""glass_energy from Python: the same tables as `vgroove energy --eta --out` (the command line and
the module call one library function), the reciprocity of the averages within noise, and bad input
refused with the command line's message naming the argument."""

import json
import os
import subprocess

import pytest


def tables(report):
    return {k: report[k] for k in ("grid", "arrays", "averages", "reciprocity")}


def test_tables_are_the_command_lines(vg, tmp_path):
    r = vg.glass_energy([1.5, 1 / 2.4], [0.4], [1.0, 0.3], dim=["3d", "flatland"], rays=4000, grooves=400, max_k=4,
                        threads=2)
    out = tmp_path / "glass.json"
    subprocess.run([os.environ["VGROOVE_BIN"], "energy", "--eta", repr(1.5) + "," + repr(1 / 2.4), "--alpha", "0.4",
                    "--mu", "1,0.3", "--dim", "3d,flatland", "--rays", "4000", "--grooves", "400", "--max-k", "4",
                    "--threads", "1", "--out", str(out)], check=True, capture_output=True)
    cli = json.loads(out.read_text())
    # Other threads, the same counts and so the same bits.
    assert tables(r) == tables(cli)
    assert len(r["reciprocity"]["pairs"]) == 4
    for p in r["reciprocity"]["pairs"]:
        assert abs(p["z"]) < 4.5, p


def test_smith_walk_tables_are_the_command_lines(vg, tmp_path):
    # reference="smith_walk": Heitz et al. 2016's dielectric walk, the same counts as
    # `vgroove energy --eta --reference smith_walk`, reciprocal averages, and not the traced surfaces'.
    kw = dict(dim=["3d", "flatland"], rays=4000, max_k=4)
    r = vg.glass_energy([1.5], [0.4], [1.0, 0.3], reference="smith_walk", threads=2, **kw)
    out = tmp_path / "walk.json"
    subprocess.run([os.environ["VGROOVE_BIN"], "energy", "--eta", "1.5", "--alpha", "0.4", "--mu", "1,0.3", "--dim",
                    "3d,flatland", "--rays", "4000", "--max-k", "4", "--reference", "smith_walk", "--threads", "1",
                    "--out", str(out)], check=True, capture_output=True)
    assert tables(r) == tables(json.loads(out.read_text()))
    assert r["grid"]["reference"] == "smith_walk"
    for p in r["reciprocity"]["pairs"]:
        assert abs(p["z"]) < 4.5, p
    traced = vg.glass_energy([1.5], [0.4], [1.0, 0.3], threads=2, grooves=400, **kw)
    assert traced["arrays"]["E_R_by_k"] != r["arrays"]["E_R_by_k"]
    with pytest.raises(ValueError, match='^reference = "walk" is not one of "vgroove", "smith_walk"'):
        vg.glass_energy([1.5], reference="walk")


@pytest.mark.parametrize("kwargs, message", [
    (dict(eta=[1.0]), "eta = 1 is no interface"),
    (dict(eta=[0.05]), "eta = 0.05 is out of range [0.1, 10]"),
    (dict(eta=[1.5], ndf="phong"), 'ndf = "phong" is not one of "ggx", "beckmann"'),
    (dict(eta=[1.5], side="inside"), 'side = "inside" is not one of "above", "below"'),
    (dict(eta=[1.5], dim="2d"), 'dim = "2d" is not one of'),
    (dict(eta=[1.5], alpha=[3]), "alpha = 3 is out of range [0.01, 2]"),
    (dict(eta=[1.5], mu=[0]), "mu = 0 is out of range"),
    (dict(eta=[1.5], grooves=0), "grooves = 0 is out of range [1, 1000000]"),
    (dict(eta=[1.5], max_k=0), "max_k = 0 is out of range [1, 1000]"),
])
def test_bad_input_names_the_argument(vg, kwargs, message):
    with pytest.raises(ValueError) as e:
        vg.glass_energy(**kwargs)
    assert str(e.value).startswith(message), str(e.value)
    assert "\n" not in str(e.value)
