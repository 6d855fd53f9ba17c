"""The energy audit's plot (python/vgroove/plot.py, kind "energy_audit"): one error map per
(reference, NDF), one panel per compensation formula, each cell the grey F0 with the largest
|error|; a report that cannot be drawn is a one-line error that leaves nothing."""

import copy
import importlib.util
import json
import math
import os

import pytest

from conftest import PLOT, cli

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def audit(tmp_path_factory):
    """A small audit (GGX, 2 alpha x 2 mu, 200 walk paths per cell: about 6 s of CPU)."""
    path = tmp_path_factory.mktemp("audit") / "audit.json"
    r = cli("energy", "--audit", "--ndf", "ggx", "--mu", "0.3,0.8", "--alpha", "0.4,1", "--rays", "200",
            "--max-k", "3", "--out", path, check=False)
    assert r.returncode == 0, r.stderr
    return str(path)


def plot_module():
    spec = importlib.util.spec_from_file_location("vgroove_plot_energy_audit", PLOT)
    m = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(m)
    return m


def test_one_map_per_reference_and_ndf(audit, tmp_path, capsys):
    status = plot_module().main([audit, "--out", str(tmp_path / "a")])
    out, err = capsys.readouterr()
    assert status == 0, err
    names = sorted(os.listdir(tmp_path))
    assert names == ["a-smith-walk-ggx.png", "a-vgroove-ggx.png"], names
    for n in names:
        assert (tmp_path / n).read_bytes().startswith(PNG_SIGNATURE)
        assert f"plot: {tmp_path / n}" in out


def panels_of(report_path, figure):
    """Each panel's title and drawn values ([alpha][mu]) of one figure."""
    m = plot_module()
    figs = dict(m.figures_for(json.load(open(report_path)), report_path))
    fig = figs[figure]()
    out = {}
    for ax in fig.axes:
        if ax.collections and ax.get_title():
            out[ax.get_title().split(":")[0]] = ax.collections[0].get_array().reshape(2, 2)
    return out


def test_each_cell_is_the_grey_f0_with_the_largest_error_and_single_scattering_loses_energy(audit):
    report = json.load(open(audit))
    grey = [c for c, ch in enumerate(report["channels"]) if ch["group"] == "grey"]
    for ref, figure in (("vgroove", "-vgroove-ggx"), ("smith_walk", "-smith-walk-ggx")):
        panels = panels_of(audit, figure)
        assert "single" in panels and "kulla_conty" in panels, sorted(panels)
        for vid, drawn in panels.items():
            errors = report["errors"][vid][ref][0]
            for a in range(2):
                for u in range(2):
                    values = [errors[a][u][c] for c in grey]
                    want = max(values, key=abs)
                    assert drawn[a, u] == pytest.approx(want, abs=0.0), (vid, ref, a, u)
        # Single scattering keeps less than the exact albedo at every F0 of every cell (it loses the
        # light of two or more reflections): its drawn errors are all negative, and at F0 = 1 (the
        # white furnace) the loss is 1 - E_ss, more than 0.1 at alpha 1 for GGX.
        single = panels["single"]
        assert (single < 0).all(), single
        assert -single.min() > 0.1, single


def broken(path, edit):
    r = json.load(open(path))
    edit(r)
    return r


BROKEN = [
    (lambda r: r.pop("errors"), "has no \"errors\""),
    (lambda r: r["grid"].update(mu=[0.3]), "has 2 mu values, the grid 1"),
    (lambda r: [c.update(group="metal") for c in r["channels"]], "has no channel of group \"grey\""),
    (lambda r: r["errors"]["kulla_conty"]["vgroove"][0][0][0].__setitem__(0, "x"), "is a string, not a number"),
    (lambda r: r.update(errors={}), "is not an object of the formulas' errors"),
]


@pytest.mark.parametrize("edit,message", BROKEN, ids=[str(n) for n in range(len(BROKEN))])
def test_broken_audits_are_one_line_errors_and_leave_nothing(audit, tmp_path, capsys, edit, message):
    path = tmp_path / "r.json"
    path.write_text(json.dumps(broken(audit, edit)))
    status = plot_module().main([str(path)])
    _, err = capsys.readouterr()
    assert status == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"vgroove: error: {path}: "), err
    assert message in lines[0], lines[0]
    assert os.listdir(tmp_path) == ["r.json"]


def test_a_nan_error_is_a_gap(audit, tmp_path, capsys):
    """The report writes an undefined error as "nan" (exact_json): the cell is left blank."""
    def edit(r):
        for c in range(len(r["channels"])):
            r["errors"]["kulla_conty"]["vgroove"][0][1][1][c] = "nan"
    report = broken(audit, edit)
    path = tmp_path / "r.json"
    path.write_text(json.dumps(report))
    panels = panels_of(str(path), "-vgroove-ggx")
    assert math.isnan(float(panels["kulla_conty"].filled(math.nan)[1, 1]))
    assert copy.deepcopy(panels["kulla_conty"]).count() == 3
