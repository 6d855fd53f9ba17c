"""Plots: every report kind drawn by `vgroove plot` (matplotlib) opens as a valid image, with
hostile names in the report; reports that cannot be drawn are a one-line error, exit 2, and
leave nothing; output is all or nothing."""

import importlib.util
import json
import os
import xml.etree.ElementTree as ET

import pytest

from conftest import PLOT, SOURCE, cli

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
EXPECTED = {  # report -> the suffixes of its figures
    "table1": [""], "table1_set": [""], "furnace": ["", "-errors"], "table2": [""], "accuracy": ["", "-cost"],
    "brdf": ["-ggx-flatland", "-ggx-3d"],
    "sampling": ["", "-variance", "-furnace", "-furnace-errors"],
    "nonsymmetric_brdf": ["", "-ggx-flatland", "-ggx-3d", "-aniso-ggx-3d"],
    "profiles": ["", "-lobes"],
    "model_table": ["-ggx-flatland", "-ggx-3d"],
}


def check_image(path, fmt):
    data = open(path, "rb").read()
    if fmt == "png":
        assert data.startswith(PNG_SIGNATURE), path
        from PIL import Image
        with Image.open(path) as im:
            im.verify()
        import matplotlib.image
        img = matplotlib.image.imread(path)
        assert img.shape[0] > 100 and img.shape[1] > 100
    elif fmt == "svg":
        root = ET.parse(path).getroot()
        assert root.tag.endswith("svg"), root.tag
    else:
        assert data.startswith(b"%PDF-") and data.rstrip().endswith(b"%%EOF"), path


def plot(report, *args, check=0):
    r = cli("plot", report, *args, check=False)
    assert r.returncode == check, (r.returncode, r.stdout, r.stderr)
    return r


_PLOT_MODULE = []


def plot_module():
    """plot.py loaded into this process (the checks and most renders run here, without starting a
    Python per plot)."""
    if not _PLOT_MODULE:
        spec = importlib.util.spec_from_file_location("vgroove_plot_under_test", PLOT)
        m = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(m)
        _PLOT_MODULE.append(m)
    return _PLOT_MODULE[0]


def plot_in_process(capsys, *args):
    """plot.py's main() in this process: (exit status, stdout, stderr)."""
    status = plot_module().main([str(a) for a in args])
    out, err = capsys.readouterr()
    return status, out, err


@pytest.mark.parametrize("kind", sorted(EXPECTED))
def test_every_report_kind_draws_valid_pngs(reports, tmp_path, capsys, kind):
    base = tmp_path / kind
    status, out, err = plot_in_process(capsys, reports[kind], "--out", base)
    assert status == 0, err
    for suffix in EXPECTED[kind]:
        assert f"plot: {base}{suffix}.png" in out
        check_image(f"{base}{suffix}.png", "png")
    assert sorted(os.listdir(tmp_path)) == sorted(f"{kind}{s}.png" for s in EXPECTED[kind])


def test_the_command_line_draws(reports, tmp_path):
    r = plot(reports["accuracy"], "--out", tmp_path / "acc")
    assert r.stdout.split() == ["plot:", f"{tmp_path}/acc.png", "plot:", f"{tmp_path}/acc-cost.png"]
    check_image(tmp_path / "acc.png", "png")
    check_image(tmp_path / "acc-cost.png", "png")


@pytest.mark.parametrize("fmt,kind", [("svg", "brdf"), ("pdf", "table1"), ("svg", "table1_set")])
def test_svg_and_pdf(reports, tmp_path, capsys, fmt, kind):
    assert plot_in_process(capsys, reports[kind], "--out", tmp_path / "x", "--format", fmt)[0] == 0
    for suffix in EXPECTED[kind]:
        check_image(f"{tmp_path}/x{suffix}.{fmt}", fmt)
    # The extension of --out names the format too.
    assert plot_in_process(capsys, reports[kind], "--out", tmp_path / f"y.{fmt}")[0] == 0
    check_image(f"{tmp_path}/y{EXPECTED[kind][0]}.{fmt}", fmt)


def test_default_name_and_force(reports, tmp_path):
    report = tmp_path / "acc.json"
    report.write_bytes(open(reports["accuracy"], "rb").read())
    plot(report)
    check_image(tmp_path / "acc.png", "png")
    check_image(tmp_path / "acc-cost.png", "png")
    before = (tmp_path / "acc.png").stat().st_mtime_ns
    r = plot(report, check=2)
    assert r.stderr.strip() == f"vgroove: error: {tmp_path}/acc.png exists (use --force to overwrite)"
    assert (tmp_path / "acc.png").stat().st_mtime_ns == before
    assert plot_module().main([str(report), "--force"]) == 0  # in this process: no second matplotlib start


HOSTILE = ['<R&D> "quotes"', "<script>alert('x')</script>", "ggx <R&D>", "$\\frac{1}{$ and $x^", "a\x1b[31mred\x00nul",
           "line\nbreak\r", "\u202eevil\u202c bidi \ufeff", "\ud800 lone surrogate", "x" * 5000, "]]>&amp;&#0;"]


@pytest.mark.parametrize("fmt", ["svg", "png"])
def test_hostile_names_render(reports, tmp_path, capsys, fmt):
    # Every hostile name in a field that is drawn: the titles (suite, version, git) and the
    # panels' names (the suites of a set).
    for kind, fields in (("table1_set", 5),):
        with open(reports[kind]) as f:
            r = json.load(f)
        for first in range(0, len(HOSTILE), fields):
            names = (HOSTILE * 2)[first:first + fields]
            r["suite"], r["version"], r["git"] = names[:3]
            for s, name in zip(r.get("suites", []), names[3:]):
                s["suite"] = name
            path = tmp_path / f"{kind}{first}.json"
            path.write_text(json.dumps(r))
            status, _, err = plot_in_process(capsys, path, "--format", fmt)
            assert status == 0, err
            for suffix in EXPECTED[kind]:
                check_image(f"{tmp_path}/{kind}{first}{suffix}.{fmt}", fmt)
    # And through the command line.
    with open(reports["brdf"]) as f:
        r = json.load(f)
    r["suite"] = 'ggx <R&D> "quotes" <script>'
    (tmp_path / "cli.json").write_text(json.dumps(r))
    plot(tmp_path / "cli.json", "--format", fmt)
    for suffix in EXPECTED["brdf"]:
        check_image(f"{tmp_path}/cli{suffix}.{fmt}", fmt)


def broken(report_path, edit):
    with open(report_path) as f:
        r = json.load(f)
    edit(r)
    return r


BROKEN = [
    ("brdf", lambda r: r["cases"][0]["plane"].update(sim=[]), "/cases/0/plane/sim has 0 values, needs"),
    ("brdf", lambda r: r["cases"][1]["plane"].update(model=r["cases"][1]["plane"]["model"][:-1]),
     "/cases/1/plane/model has"),
    ("brdf", lambda r: r["cases"][0]["plane"].update(cook_torrance=None), "/cases/0/plane/cook_torrance is null"),
    ("brdf", lambda r: r["cases"][0]["plane"].update(theta_deg=[]), "/cases/0/plane/theta_deg has 0 values"),
    ("brdf", lambda r: r["cases"][0].update(ndf="../../etc/x"), "/cases/0/ndf = \"../../etc/x\" is not one of"),
    ("brdf", lambda r: r.update(cases=[]), "/cases is an empty list"),
    ("brdf", lambda r: r["cases"][0]["plane"]["sim"].__setitem__(3, "1"), "/cases/0/plane/sim/3 is a string"),
    ("furnace", lambda r: r["cases"][0].update(albedo_sim=None), "/cases/0/albedo_sim is null"),
    ("furnace", lambda r: r["cases"][1].pop("albedo_estimate"), "/cases/1 has no \"albedo_estimate\""),
    ("sampling", lambda r: r["chi_square"][0]["table"]["observed"].pop(), "/chi_square/0/table has"),
    ("sampling", lambda r: r["chi_square"][1]["table"]["expected"][0].__setitem__(2, -1.0),
     "/chi_square/1/table/expected/0/2 = -1.0 is out of range"),
    ("sampling", lambda r: r["variance"][0].update(strategies=[]), "/variance/0/strategies is an empty list"),
    ("sampling", lambda r: r["furnace"]["cases"][0].update(ndf="x"), "/furnace/cases/0/ndf = \"x\" is not one of"),
    ("nonsymmetric_brdf", lambda r: r["cases"][2]["plane"].update(other_model=[0.0]),
     "/cases/2/plane/other_model has 1 values"),
    ("nonsymmetric_brdf", lambda r: r["cases"][0].update(anisotropic_block="no"),
     "/cases/0/anisotropic_block is a string"),
    ("profiles", lambda r: r["cases"][0]["surfaces"][1]["g1"].update(traced=[0.5]), "/cases/0/surfaces/1/g1/traced has"),
    ("profiles", lambda r: r["bins"].update(exit_deg_edges=[0.0]), "/bins/exit_deg_edges has 1 values, needs at least 2"),
    ("table1", lambda r: r.update(cases=None), "/cases is null"),
    ("table1", lambda r: r["cases"][0].update(l1=1e308 * 10), None),
    ("table1_set", lambda r: r["suites"][1].pop("thresholds"), "/suites/1 has no \"thresholds\""),
    ("accuracy", lambda r: r.update(runs=[{}]), "/runs/0 has no"),
    ("accuracy", lambda r: r["cost_vs_theta_v"].update(points=[]), "/cost_vs_theta_v/points is an empty list"),
    ("table2", lambda r: r["entries"][0].update(ours=[1]), "/entries/0/ours is a list, not a number"),
    ("model_table", lambda r: r["cases"][1].update(ndf="cauchy"), "/cases/1/ndf"),
    ("model_table", lambda r: r["cases"][0].update(l1_threshold="inf"), "/cases/0/l1_threshold is a string"),
    ("model_table", lambda r: r["cases"][0].pop("albedo_sim"), "is a model table, not a report"),
]


@pytest.mark.parametrize("kind,edit,message", BROKEN, ids=[f"{k}-{n}" for n, (k, _, _) in enumerate(BROKEN)])
def test_broken_reports_are_one_line_errors_and_leave_nothing(reports, tmp_path, capsys, kind, edit, message):
    path = tmp_path / "r.json"
    text = json.dumps(broken(reports[kind], edit))
    path.write_text(text.replace("Infinity", "1e400"))
    status, _, err = plot_in_process(capsys, path)
    assert status == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"vgroove: error: {path}: "), r.stderr
    if message:
        assert message in lines[0], lines[0]
    assert os.listdir(tmp_path) == ["r.json"]


UNREADABLE = [
    (b"", "not JSON"), (b"{", "not JSON"), (b"[1, 2]", "is a list: a report is a JSON object"),
    (b"{\"a\": NaN}", "NaN is not JSON"), (b"\xff\xfe", "not UTF-8"), (b"[" * 100000 + b"]" * 100000, None),
    (b"{}", "is not a vgroove report"), (b"{\"kind\": \"brdf\"}", "has no \"cases\""),
]


@pytest.mark.parametrize("content,message", UNREADABLE, ids=[str(n) for n in range(len(UNREADABLE))])
def test_unreadable_reports(tmp_path, capsys, content, message):
    path = tmp_path / "r.json"
    path.write_bytes(content)
    status, _, err = plot_in_process(capsys, path)
    lines = err.strip().splitlines()
    assert status == 2 and len(lines) == 1 and lines[0].startswith("vgroove: error: "), err
    if message:
        assert message in lines[0]
    assert os.listdir(tmp_path) == ["r.json"]


def test_command_line_errors(tmp_path, reports):
    # The command line passes the script's status and its one line on.
    path = tmp_path / "r.json"
    path.write_text(json.dumps(broken(reports["brdf"], lambda r: r["cases"][0]["plane"].update(sim=[]))))
    r = plot(path, check=2)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"vgroove: error: {path}: /cases/0/plane/sim has 0 values"), lines
    r = plot(tmp_path / "missing.json", check=2)
    assert "cannot read" in r.stderr
    r = plot(tmp_path, check=2)
    assert r.stderr.count("\n") == 1
    r = plot(path, "--format", "gif", check=2)
    assert r.stderr.strip() == 'vgroove: error: --format = "gif" is not one of "png", "svg", "pdf"'


def six_group_report(brdf_report_path):
    with open(brdf_report_path) as f:
        r = json.load(f)
    cases = []
    for ndf in ("ggx", "beckmann", "phong"):
        for c in r["cases"]:
            cases.append(dict(c, ndf=ndf))
    r["cases"] = cases
    return r


def test_a_plot_failing_on_its_sixth_file_leaves_nothing(reports, tmp_path):
    m = plot_module()
    figs = m.figures_for(six_group_report(reports["brdf"]), "six.json")
    assert len(figs) == 6
    drawn = []

    def failing(draw):
        def f():
            if len(drawn) == 5:
                raise OSError(28, "No space left on device")
            drawn.append(1)
            return draw()
        return f

    figs = [(s, failing(d)) for s, d in figs]
    import matplotlib
    matplotlib.use("Agg")
    with pytest.raises(OSError):
        m.render_all(figs, str(tmp_path / "six"), "png", force=False)
    assert len(drawn) == 5 and os.listdir(tmp_path) == []
    # The same through the command line: the sixth target exists (no --force), nothing is written.
    report = tmp_path / "six.json"
    report.write_text(json.dumps(six_group_report(reports["brdf"])))
    (tmp_path / "six-phong-3d.png").write_bytes(b"old")
    r = plot(report, check=2)
    assert "six-phong-3d.png exists" in r.stderr
    assert sorted(os.listdir(tmp_path)) == ["six-phong-3d.png", "six.json"]


def test_safe_text():
    m = plot_module()
    assert m.safe_text("a$b") == "a\\$b"
    assert m.safe_text("x\ny\x00\u202e\ud800") == "x\\u000ay\\u0000\\u202e\\ud800"
    assert len(m.safe_text("x" * 500)) == 80


def test_fuzz_corpus_replays():
    """The inputs scripts/fuzz_reports.py kept (tests/fuzz/corpus/report_plot/): each is drawn or
    refused with a ReportError, nothing else."""
    m = plot_module()
    corpus = os.path.join(SOURCE, "tests", "fuzz", "corpus", "report_plot")
    files = sorted(os.listdir(corpus))
    assert len(files) >= 6
    drawn = 0
    for name in files:
        data = open(os.path.join(corpus, name), "rb").read()
        try:
            doc = json.loads(data.decode("utf-8"), parse_constant=lambda c: (_ for _ in ()).throw(m.ReportError(c)))
            figs = m.figures_for(doc, name)
        except (m.ReportError, UnicodeDecodeError, json.JSONDecodeError, RecursionError):
            continue
        if drawn < 3:
            for _, draw in figs:
                draw()
        drawn += 1


def test_fig11_grid_has_one_panel_per_case(reports):
    m = plot_module()
    with open(reports["brdf"]) as f:
        r = json.load(f)
    figs = dict(m.figures_for(r, "r.json"))
    assert sorted(figs) == ["-ggx-3d", "-ggx-flatland"]
    for suffix, dim in (("-ggx-3d", "3d"), ("-ggx-flatland", "flatland")):
        fig = figs[suffix]()
        panels = [ax for ax in fig.axes if ax.get_visible() and ax.get_title().startswith("alpha")]
        assert len(panels) == sum(c["dimension"] == dim for c in r["cases"])
        for ax in panels:
            assert ax.get_xlabel().startswith("theta_o (deg") and "per steradian" in ax.get_ylabel() or \
                "per radian" in ax.get_ylabel()


def test_the_main_job_plots_every_report_it_writes():
    # scripts/run.sh: the plot loop covers the suites the validate loop runs, and each suite's kind
    # is one plot.py draws (the tiny reports of every kind are drawn above).
    import re
    m = plot_module()
    text = open(os.path.join(SOURCE, "scripts", "run.sh")).read()
    loops = re.findall(r"^for suite in ([^;]+); do\n(.*?)^done", text, re.S | re.M)
    validated = [s.split() for s, body in loops if "vgroove validate" in body]
    plotted = [s.split() for s, body in loops if "vgroove plot" in body]
    assert len(validated) == 1 and len(plotted) == 1, loops
    assert plotted[0] == validated[0]
    for suite in validated[0]:
        with open(os.path.join(SOURCE, "data", "suites", f"{suite}.json")) as f:
            kind = json.load(f).get("kind", "table1")  # a set of suites: Table 1's two columns
        kind = {"table1": "single_grooves", "stress": "single_grooves"}.get(kind, kind)
        assert kind in m.KINDS, (suite, kind)
        assert kind == "single_grooves" or kind in EXPECTED, (suite, kind)


def test_exact_table1_errors_are_drawn_on_a_log_scale(reports):
    # Breakpoint search gives L1 of 1e-13 and zeros against thresholds of 1e-9: a linear scale up to
    # the paper's 0.003 would draw every cell alike. Far below the paper, the scale is logarithmic,
    # zeros drawn at its floor; at the paper's scale it stays linear.
    from matplotlib.colors import LogNorm, Normalize
    m = plot_module()
    with open(reports["table1"]) as f:
        r = json.load(f)
    [(_, draw)] = m.figures_for(r, "r.json")
    def maps(fig):  # the heatmaps' normalizations (the panels, not their colorbars)
        return [c.norm for ax in fig.axes if ax.get_ylabel() == "theta_v (deg)" for c in ax.collections]

    norms = maps(draw())
    assert norms and all(type(n) is Normalize for n in norms)
    r["thresholds"]["max_l1"] = 3e-9
    for n, c in enumerate(r["cases"]):
        c["l1"] = [0.0, 1e-16, 3.6e-14][n % 3]
    [(_, draw)] = m.figures_for(r, "r.json")
    fig = draw()
    norms = maps(fig)
    assert norms and all(isinstance(n, LogNorm) for n in norms)
    assert all(n.vmin == pytest.approx(1e-17) and n.vmax >= 3.6e-14 for n in norms)
    assert any("log scale" in ax.get_ylabel() for ax in fig.axes)


def test_a_model_table_report_draws_a_figure_per_ndf_and_dimension_and_its_input_table_is_refused(reports, tmp_path,
                                                                                                     capsys):
    # `vgroove validate SUITE --model-table TABLE` reports were refused as "not a vgroove report"
    # (the kind was unknown to plot.py); the table itself (kind model_table, fluxes only) is not one.
    status, out, err = plot_in_process(capsys, reports["model_table"], "--out", tmp_path / "m")
    assert status == 0, err
    assert out.split() == ["plot:", f"{tmp_path}/m-ggx-flatland.png", "plot:", f"{tmp_path}/m-ggx-3d.png"]
    table = os.path.join(os.path.dirname(reports["model_table"]), "model_table_input.json")
    status, _, err = plot_in_process(capsys, table, "--out", tmp_path / "t")
    assert status == 2
    assert err.strip() == (f"vgroove: error: {table}: / is a model table, not a report: draw the report of "
                           "`vgroove validate SUITE --model-table TABLE --out REPORT`")


def test_a_heightfield_report_with_anisotropic_cases_draws(tmp_path, capsys):
    # aspect [1, 1.5]: the anisotropic cases skip Cook-Torrance and the V-groove model (the report
    # says "skipped"); the figure draws the isotropic cases' models and every case's walk.
    suite = {"name": "tiny_hf_aspects", "kind": "heightfield", "aspect": [1, 1.5], "ndf": ["beckmann"],
             "alpha": [0.3], "theta_i_deg": [0, 60], "field_size": 64, "correlation_length": 4, "fields": 2,
             "rays": 500, "walk_paths": 1000, "theta_bins": 6, "phi_bins": 4, "seed": 3, "thresholds": {"sigmas": 5}}
    spec, report = tmp_path / "hf.json", tmp_path / "hf-report.json"
    spec.write_text(json.dumps(suite))
    r = cli("validate", spec, "--out", report, check=False)
    assert r.returncode in (0, 1), r.stderr
    cases = json.loads(report.read_text())["cases"]
    assert any("skipped" in c["cook_torrance_smith"] for c in cases)
    assert any("against_traced" in c["cook_torrance_smith"] for c in cases)
    status, out, err = plot_in_process(capsys, report, "--out", tmp_path / "hf")
    assert status == 0, err
    check_image(tmp_path / "hf-beckmann.png", "png")
    check_image(tmp_path / "hf-lobes-beckmann.png", "png")
    # The lobes per k: the traced points and each model's line are the report's lobes summed over
    # phi_o, theta_o bin by bin (k = 1 of the first case: the isotropic one, every model drawn).
    j = json.loads(report.read_text())
    m = plot_module()
    fig = dict(m.figures_for(j, str(report)))["-lobes-beckmann"]()
    c, tb, pb = j["cases"][0], j["inputs"]["theta_bins"], j["inputs"]["phi_bins"]

    def marginal(row):
        return [sum(row[t * pb + p] for p in range(pb)) for t in range(tb)]

    ax = fig.axes[0]
    lines = {ln.get_label(): list(ln.get_ydata()) for ln in ax.get_lines()}
    assert lines["Smith walk"] == marginal(c["smith_walk"]["lobe_by_k"][0])
    assert lines["V-groove model"] == marginal(c["vgroove"]["lobe_by_k"][0])
    assert lines["Cook-Torrance, Smith G (k = 1)"] == marginal(c["cook_torrance_smith"]["lobe_k1"])
    traced = [list(cont.lines[0].get_ydata()) for cont in ax.containers][0]
    assert traced == marginal(c["traced"]["lobe_by_k"][0])
