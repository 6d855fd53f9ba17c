"""energy_audit(): `vgroove energy --audit [--reference heightfield]` from Python (validation/
energy_audit.h through python/src/energy.cpp, which builds the command line's suite): the same
report as the command line's for the same grid, seed and rays (timings aside), with and without the
heightfield reference; and the command line's refusals, named by the arguments."""

import json

import pytest

from conftest import cli, cli_error, strip_timing as _strip_timing

# One cell (GGX, alpha 0.5, mu 0.5), 400 walk paths and 4 fields x 100 rays: a second or two.
GRID = dict(ndf="ggx", alpha=[0.5], mu=[0.5], rays=400, seed=3, max_k=4, threads=2)
FLAGS = ["--ndf", "ggx", "--alpha", "0.5", "--mu", "0.5", "--rays", "400", "--seed", "3", "--max-k", "4",
         "--threads", "2"]


def strip_timing(report):
    """The report without its timings and without "suite_file", the name the suite's messages
    give it: "vgroove energy --audit" on the command line, "energy_audit" here."""
    r = _strip_timing(report)
    r.pop("suite_file")
    r.pop("model_s")  # the V-groove model's quadrature, in seconds
    return r


def cli_audit(tmp_path, *extra):
    out = tmp_path / "audit.json"
    r = cli("energy", "--audit", *FLAGS, *extra, "--out", out)
    assert r.returncode in (0, 1), r.stdout + r.stderr
    with open(out) as f:
        return json.load(f)


def test_heightfield_reference_is_the_command_lines_report(vg, tmp_path):
    theirs = cli_audit(tmp_path, "--reference", "heightfield")
    ours = vg.energy_audit(**GRID, reference="heightfield")
    assert strip_timing(ours) == strip_timing(theirs)
    assert ours["suite_file"] == "energy_audit" and theirs["suite_file"] == "vgroove energy --audit"
    assert ours["spec"]["references"] == ["vgroove", "smith_walk", "heightfield"]
    assert ours["spec"]["heightfield"]["rays_per_field"] == 100
    # Power: another seed draws other walks and other fields: another report.
    other = vg.energy_audit(**dict(GRID, seed=4), reference="heightfield")
    assert strip_timing(other) != strip_timing(theirs)


def test_without_the_heightfields_is_the_command_lines_report(vg, tmp_path):
    theirs = cli_audit(tmp_path)
    ours = vg.energy_audit(**GRID)
    assert strip_timing(ours) == strip_timing(theirs)
    assert "references" not in ours["spec"] and "heightfield" not in ours["spec"]


def names(message):
    """The command line's message as Python words it: the arguments' names for the flags."""
    message = message.replace("vgroove energy --audit", "energy_audit").replace("--audit", "energy_audit")
    for flag in ("--alpha-points", "--mu-points", "--max-k", "--reference", "--rays", "--ndf", "--seed", "--threads",
                 "--alpha", "--mu"):
        message = message.replace(flag, flag[2:].replace("-", "_"))
    return message


@pytest.mark.parametrize("kwargs,flags", [
    ({"reference": "smith_walk"}, ["--reference", "smith_walk"]),
    ({"reference": "vgroove"}, ["--reference", "vgroove"]),
    ({"max_k": 0}, ["--max-k", "0"]),  # the command line's flag range, [1, 1000], first
    ({"max_k": 65}, ["--max-k", "65"]),  # then the audit's, [1, 64]
    ({"ndf": ["ggx", "phong"]}, ["--ndf", "ggx,phong"]),
    ({"alpha_points": 0}, ["--alpha-points", "0"]),
    ({"mu_points": 100000}, ["--mu-points", "100000"]),
    ({"rays": 0}, ["--rays", "0"]),
    ({"rays": 2_000_000_000}, ["--rays", "2000000000"]),
    ({"threads": -1}, ["--threads=-1"]),
    ({"alpha": [0.5, 3.0]}, ["--alpha", "0.5,3"]),
    ({"mu": [0.0]}, ["--mu", "0"]),
    ({"seed": -1}, ["--seed=-1"]),
])
def test_refusals_are_the_command_lines(vg, kwargs, flags):
    expected = names(cli_error("energy", "--audit", *flags))
    with pytest.raises(ValueError) as e:
        vg.energy_audit(**kwargs)
    assert str(e.value) == expected


def test_bad_types(vg):
    with pytest.raises(ValueError, match=r"^rays = 1.5 must be an integer"):
        vg.energy_audit(rays=1.5)
    with pytest.raises(ValueError, match=r"^reference = 3 must be a string"):
        vg.energy_audit(reference=3)
