"""glass_energy from Python: the same tables as `vgroove energy --eta --out` (the command line and
the module call one library function), the reciprocity of the averages within noise, and bad input
refused with the command line's message naming the argument. The glass report's plot
(python/vgroove/plot.py, kind "glass_energy"): one figure per (NDF, side, eta), each panel the
report's error map of a form and quantity; a report without maps is a one-line error."""

import importlib.util
import json
import os
import subprocess

import pytest

from conftest import PLOT, cli

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


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
    assert r["kulla_conty_glass"]["summary"] == cli["kulla_conty_glass"]["summary"]
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


@pytest.fixture(scope="module")
def glass_report(tmp_path_factory):
    """A small grid against the walk (2 eta x 2 alpha x 3 mu, both sides, 1000 walks a cell: ~2 s)."""
    path = tmp_path_factory.mktemp("glass") / "glass.json"
    r = cli("energy", "--eta", "1.5,2.4", "--alpha", "0.3,0.7", "--mu", "0.2,0.5,0.9", "--dim", "3d", "--rays",
            "1000", "--max-k", "4", "--reference", "smith_walk", "--threads", "2", "--out", path, check=False)
    assert r.returncode == 0, r.stderr
    assert "The forms over the grid against smith_walk" in r.stdout
    assert "closest from both, all, R+T'" in r.stdout
    return str(path)


def plot_module():
    spec = importlib.util.spec_from_file_location("vgroove_plot_glass", PLOT)
    m = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(m)
    return m


def test_one_figure_per_ndf_side_and_eta(glass_report, tmp_path, capsys):
    status = plot_module().main([glass_report, "--out", str(tmp_path / "g")])
    out, err = capsys.readouterr()
    assert status == 0, err
    names = sorted(os.listdir(tmp_path))
    assert names == ["g-ggx-above-eta-1p5.png", "g-ggx-above-eta-2p4.png", "g-ggx-below-eta-1p5.png",
                     "g-ggx-below-eta-2p4.png"], names
    for n in names:
        assert (tmp_path / n).read_bytes().startswith(PNG_SIGNATURE)
        assert f"plot: {tmp_path / n}" in out


def test_panels_are_the_reports_error_maps(glass_report):
    """Each panel's drawn values are the report's error map at [ndf][side][eta][alpha][mu], which is
    the cell's form value minus the traced one (kulla_conty_glass.cells), and the circles mark the
    cells whose |z| is within the form's summary threshold."""
    report = json.load(open(glass_report))
    kc = report["kulla_conty_glass"]
    maps = kc["error_maps"]
    assert maps["shape"] == [1, 2, 2, 2, 3]
    forms = [f["id"] for f in kc["forms"]]
    assert forms == ["moonray", "scale_one", "cycles_glass"]
    cells = [c for c in kc["cells"] if c["mu"] != "average"]
    assert len(cells) == 24
    for i, c in enumerate(cells):  # the grid's order: side, eta, alpha, mu (innermost)
        for f in forms:
            assert maps["forms"][f]["R"]["error"][i] == c[f + "_R"] - c["traced_R"]
            assert maps["forms"][f]["T"]["error"][i] == c[f + "_T"] - c["traced_T"]
    m = plot_module()
    figs = dict(m.figures_for(report, glass_report))
    threshold = {(x["form"], x["side"], x["quantity"]): x["z_threshold"] for x in kc["summary"]
                 if x["region"] == "all"}
    for s, side in enumerate(("above", "below")):
        for e, tag in enumerate(("1p5", "2p4")):
            fig = figs[f"-ggx-{side}-eta-{tag}"]()
            panels = [ax for ax in fig.axes if ax.collections and ax.get_title()]
            assert len(panels) == 9
            for ax in panels:
                form, q = ax.get_title().split(":")[0].split(" ")
                q = q.rstrip("'")
                drawn = ax.collections[0].get_array().reshape(2, 3)
                flat = maps["forms"][form][q]["error"]
                z = maps["forms"][form][q]["z"]
                base = (s * 2 + e) * 6
                for a in range(2):
                    for u in range(3):
                        assert drawn[a, u] == flat[base + a * 3 + u], (form, q, side, tag, a, u)
                circles = ax.collections[1].get_offsets().tolist() if len(ax.collections) > 1 else []
                want = [[report["grid"]["mu"][u], report["grid"]["alpha"][a]] for a in range(2) for u in range(3)
                        if abs(z[base + a * 3 + u]) <= threshold[(form, side, q)]]
                assert circles == want, (form, q, side, tag)


def test_moonray_from_below_is_beyond_noise_and_scale_one_is_not(glass_report):
    """The report's own verdict: from below MoonRay's R' + T' falls short of the walk's 1 (its n^2),
    the scale-one form's and Cycles' reach it within noise; from above all three do."""
    kc = json.load(open(glass_report))["kulla_conty_glass"]
    line = {(x["form"], x["side"], x["region"], x["quantity"]): x for x in kc["summary"]}
    assert not line[("moonray", "below", "all", "R+T")]["within_noise"]
    assert line[("moonray", "below", "all", "R+T")]["worst"] < -0.005
    for f in ("scale_one", "cycles_glass"):
        assert line[(f, "below", "all", "R+T")]["within_noise"], line[(f, "below", "all", "R+T")]
    for f in ("moonray", "scale_one", "cycles_glass"):
        assert line[(f, "above", "all", "R+T")]["within_noise"], line[(f, "above", "all", "R+T")]
    assert kc["regions"]["rough"] == "alpha >= 0.5" and kc["regions"]["grazing"] == "mu <= 0.25"


def test_a_glass_report_without_maps_is_a_one_line_error(glass_report, tmp_path, capsys):
    r = json.load(open(glass_report))
    del r["kulla_conty_glass"]["error_maps"]
    path = tmp_path / "r.json"
    path.write_text(json.dumps(r))
    status = plot_module().main([str(path)])
    _, err = capsys.readouterr()
    assert status == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "has no \"error_maps\"" in lines[0], err
    assert os.listdir(tmp_path) == ["r.json"]
