"""The heightfield albedo's plot (python/vgroove/plot.py, kind "heightfield_albedo"): one figure
per NDF, a row per alpha, columns E, E_1, E_ms over mu: the traced points with 2 se bars and each
model's line as the report gives them; a report that cannot be drawn is a one-line error."""

import importlib.util
import json
import math
import os

import pytest

from conftest import PLOT, cli

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """A tiny suite (Beckmann and GGX, alpha 0.3, mu 1 and 0.5, 2 fields of 32^2: well under 1 s)."""
    d = tmp_path_factory.mktemp("hfa")
    suite = {"name": "hfa", "kind": "heightfield_albedo", "ndf": ["beckmann", "ggx"], "alpha": [0.3],
             "mu": [1.0, 0.5], "field_size": 32, "correlation_length": 2, "fields": 2, "rays": 500,
             "walk_paths": 500, "thresholds": {"sigmas": 5}}
    (d / "s.json").write_text(json.dumps(suite))
    r = cli("validate", d / "s.json", "--out", d / "r.json", check=False)
    assert r.returncode == 0, r.stderr
    return str(d / "r.json")


def plot_module():
    spec = importlib.util.spec_from_file_location("vgroove_plot_heightfield_albedo", PLOT)
    m = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(m)
    return m


def test_one_figure_per_ndf_with_the_traced_points_and_each_models_line(report, tmp_path, capsys):
    status = plot_module().main([report, "--out", str(tmp_path / "a")])
    out, err = capsys.readouterr()
    assert status == 0, err
    assert sorted(os.listdir(tmp_path)) == ["a-beckmann.png", "a-ggx.png"]
    for n in os.listdir(tmp_path):
        assert (tmp_path / n).read_bytes().startswith(PNG_SIGNATURE)
    j = json.load(open(report))
    fig = dict(plot_module().figures_for(j, report))["-ggx"]()
    panels = {ax.get_title(): ax for ax in fig.axes if ax.get_title()}
    assert sorted(panels) == ["ggx alpha 0.3: E", "ggx alpha 0.3: E_1", "ggx alpha 0.3: E_ms"]
    # E_1: the walk, E_ss and the V-groove lines (mu ascending) and the traced points, the report's values.
    ggx = sorted((p for p in j["points"] if p["ndf"] == "ggx"), key=lambda p: p["mu"])
    lines = {ln.get_label(): list(ln.get_ydata()) for ln in panels["ggx alpha 0.3: E_1"].get_lines()}
    assert lines["Smith E_ss (exact)"] == [p["models"]["smith_ess"]["value"][1] for p in ggx]
    assert lines["V-groove model"] == [p["models"]["vgroove"]["value"][1] for p in ggx]
    # E_ms: E_ss has no such row (null): no line.
    labels = [ln.get_label() for ln in panels["ggx alpha 0.3: E_ms"].get_lines()]
    assert "Smith E_ss (exact)" not in labels and "Smith walk" in labels


def test_a_damaged_report_is_a_one_line_error(report, tmp_path, capsys):
    j = json.load(open(report))
    j["points"][0]["traced"] = j["points"][0]["traced"][:3]
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(j))
    status = plot_module().main([str(bad), "--out", str(tmp_path / "b")])
    _, err = capsys.readouterr()
    assert status == 2
    assert "/points/0/traced has 3 values, needs 5" in err, err
    assert not [n for n in os.listdir(tmp_path) if n.endswith(".png")]
